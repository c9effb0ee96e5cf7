"""Preferences (Edit → Preferences...): the user's mouse preset and file dialogs, saved per user
in ``$JACKPY_HOME/preferences.json`` (:mod:`jackpy.ui.preferences`) the moment they change."""

from __future__ import annotations

from typing import TYPE_CHECKING

from imgui_bundle import imgui

from jackpy.ui.camera import MOUSE_MAPPINGS, NavAction
from jackpy.ui.file_dialog import native_available
from jackpy.ui.panels import Panel
from jackpy.ui.preferences import MOUSE_PRESET_LABELS

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Preferences"


def set_mouse_preset(app: "App", preset: str) -> None:
    """Use navigation preset ``preset`` from now on, in this document and the next ones; saved."""
    if preset not in MOUSE_MAPPINGS:
        raise ValueError(f"no mouse preset {preset!r} (known: {', '.join(MOUSE_MAPPINGS)})")
    app.preferences.mouse_preset = app.settings.mouse_mapping = preset
    app.preferences.save()
    app.info(f"mouse preset: {preset}")


def set_native_dialogs(app: "App", on: bool) -> None:
    """Use the desktop's file dialogs when one is installed (else the workbench's browser); saved."""
    app.preferences.native_dialogs = on
    app.preferences.save()


def draw(app: "App", ui: "UiState") -> None:
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels[TITLE])
    if visible:
        imgui.separator_text("Mouse")
        presets = list(MOUSE_MAPPINGS)
        current = presets.index(app.preferences.mouse_preset) if app.preferences.mouse_preset in presets else 0
        for i, preset in enumerate(presets):
            if i:
                imgui.same_line()
            if imgui.radio_button(MOUSE_PRESET_LABELS.get(preset, preset), i == current) and i != current:
                set_mouse_preset(app, preset)
        imgui.text_wrapped("On empty space: " + _describe(app.preferences.mouse_preset)
                           + "; the wheel zooms. A press on a figure or object starts the Jack operator"
                           + (" (Alt-drags still move the camera)." if app.preferences.mouse_preset == "maya" else "."))
        imgui.separator_text("Files")
        changed, on = imgui.checkbox("Desktop file dialogs", app.preferences.native_dialogs)
        if changed:
            set_native_dialogs(app, on)
        _note("a desktop dialog is installed" if native_available()
              else "no desktop dialog is installed (zenity, kdialog): the built-in browser is used")
        _note(f"saved in {app.preferences.path}")
    imgui.end()


def _note(text: str) -> None:
    imgui.push_style_color(imgui.Col_.text, imgui.get_style().color_(imgui.Col_.text_disabled))
    imgui.text_wrapped(text)
    imgui.pop_style_color()


def _describe(preset: str) -> str:
    words = {NavAction.ORBIT: "orbit", NavAction.PAN: "pan", NavAction.ZOOM: "zoom"}
    return ", ".join(f"{'+'.join([*sorted(b.modifiers), b.button])} {words[b.action]}" for b in MOUSE_MAPPINGS[preset])


PANEL = Panel(TITLE, draw, order=97)
