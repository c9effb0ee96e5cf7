"""The workbench's imgui panels, discovered like the CLI's commands: every module in this package
that defines ``PANEL = Panel(...)`` is one panel (a title, a ``draw(app, ui)`` function, whether
it starts open, its place in the View menu). Adding a panel is adding one module; nothing else
lists them. :func:`draw_all` draws the menu bar and every open panel.

Per-panel widget state (chosen indices, text fields) lives in the window's :class:`UiState`
(:meth:`UiState.panel_state`), not in module globals.
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from jackpy.ui.file_dialog import FileDialog
from jackpy.ui.palette import CommandPalette

if TYPE_CHECKING:
    from jackpy.ui.app import App


@dataclass(frozen=True)
class Panel:
    """A panel: ``title`` (its window title and View-menu entry), ``draw(app, ui)``, ``open`` at
    start, ``order`` in the menu and drawing, and ``always``: drawn every frame even when closed
    (the panel reads ``ui.open_panels`` itself, e.g. to tell the app to stop rendering for it)."""

    title: str
    draw: Callable[[App, UiState], None]
    open: bool = False
    order: int = 100
    always: bool = False


_PANELS: list[Panel] | None = None


def panels() -> list[Panel]:
    """Every panel of this package, in menu order (the modules are imported once)."""
    global _PANELS
    if _PANELS is None:
        found = []
        for info in pkgutil.iter_modules(__path__):
            module = importlib.import_module(f"{__name__}.{info.name}")
            panel = getattr(module, "PANEL", None)
            if isinstance(panel, Panel):
                found.append(panel)
        titles = [p.title for p in found]
        dupes = {t for t in titles if titles.count(t) > 1}
        if dupes:
            raise RuntimeError(f"two panels are titled {sorted(dupes)}")
        _PANELS = sorted(found, key=lambda p: (p.order, p.title))
    return list(_PANELS)


@dataclass
class UiState:
    """Window-level UI state: which panels are open, each panel's widget state, the file dialog,
    the command palette, the pending prompts."""

    open_panels: dict[str, bool] = field(default_factory=lambda: {p.title: p.open for p in panels()})
    panel_states: dict[str, dict[str, Any]] = field(default_factory=dict)
    files: FileDialog = field(default_factory=FileDialog)
    """The file dialog (open, save as, import, screenshot); at most one question at a time."""
    palette: CommandPalette = field(default_factory=CommandPalette)
    palette_open: bool = False
    """The command palette is shown (Ctrl+Shift+P, Help → Command palette)."""
    quit_requested: bool = False
    quit_confirmed: bool = False
    """Set by Discard (or a save) in the quit prompt: the next quit ends without asking."""
    quit_after_save: bool = False
    """The Save-as prompt was opened by the quit prompt's Save: quit once it saved."""
    confirm: str | None = None
    """An open confirmation of unsaved changes (Save / Discard / Cancel): ``"quit"``, or
    ``"unsaved"`` before New, Open or Open Recent (the action waits in :attr:`pending`)."""
    pending: tuple[str, Callable[[], None]] | None = None
    """What waits for the ``"unsaved"`` answer: (what it does, in words; the action)."""
    after_save: Callable[[], None] | None = None
    """The Save-as prompt was opened by the ``"unsaved"`` prompt's Save: run this once it saved."""
    recovery_offer: str | None = None
    """A recovery file found at start-up, offered once."""
    import_units: str = "m"
    """Units and up axis chosen in the Import CAD dialog."""
    import_up: str = "y"
    reset_layout: bool = False
    """View → Reset layout was chosen: the window rebuilds the default docked layout."""

    def panel_state(self, title: str, defaults: dict[str, Any] | None = None) -> dict[str, Any]:
        """Panel ``title``'s widget state, made from ``defaults`` on first use."""
        state = self.panel_states.get(title)
        if state is None:
            state = self.panel_states[title] = dict(defaults or {})
        return state


def draw_all(app: App, ui: UiState, before_panels: Callable[[], None] | None = None) -> None:
    """Draw the menu bar, ``before_panels`` (the window's status bar and dockspace), the open
    panels and any prompt."""
    from jackpy.ui.panels import menu_bar

    menu_bar.draw(app, ui)
    if before_panels is not None:
        before_panels()
    for p in panels():
        if p.always or ui.open_panels.get(p.title):
            p.draw(app, ui)
