"""Help → Keyboard shortcuts: every menu command's key (from :mod:`jackpy.ui.commands`) and the
keys that are not menu commands. The keys work wherever the focus is, except while typing."""

from __future__ import annotations

from typing import TYPE_CHECKING

from imgui_bundle import imgui

from jackpy.ui.panels import Panel, panels

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Keyboard shortcuts"


def rows() -> list[tuple[str, str]]:
    """(key, what it does) for every shortcut, menu commands first."""
    from jackpy.ui.commands import OTHER_KEYS, commands

    keyed = [(c.shortcut, f"{c.menu} \u2192 {c.label}") for c in commands([p.title for p in panels()]) if c.shortcut]
    return keyed + list(OTHER_KEYS)


def draw(app: "App", ui: "UiState") -> None:
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels[TITLE])
    if visible and imgui.begin_table("keys", 2, imgui.TableFlags_.row_bg | imgui.TableFlags_.borders_inner_v):
        imgui.table_setup_column("key", imgui.TableColumnFlags_.width_fixed)
        imgui.table_setup_column("action")
        for key, action in rows():
            imgui.table_next_row()
            imgui.table_next_column()
            imgui.text(key)
            imgui.table_next_column()
            imgui.text_wrapped(action)
        imgui.end_table()
    imgui.end()


PANEL = Panel(TITLE, draw, order=98)
