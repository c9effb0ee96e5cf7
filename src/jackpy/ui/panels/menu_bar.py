"""The main menu bar (File, Edit, View, Scene, Help, drawn from :mod:`jackpy.ui.commands`; File's
Open Recent and Recover lists), the file dialog, the quit and recovery prompts and the command
palette."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from imgui_bundle import imgui

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.commands import Command
    from jackpy.ui.panels import UiState

MENUS = ("File", "Edit", "View", "Scene", "Help")


def draw(app: "App", ui: "UiState") -> None:
    from jackpy.ui import commands as cmds
    from jackpy.ui.panels import panels

    table = cmds.commands([p.title for p in panels()])
    if imgui.begin_main_menu_bar():
        for menu in MENUS:
            if imgui.begin_menu(menu):
                for c in (c for c in table if c.menu == menu):
                    _menu_item(app, ui, c)
                    if c.label == "Open...":
                        _recent_menu(app, ui)
                        _recover_menu(app, ui)
                imgui.end_menu()
        imgui.end_main_menu_bar()
    answer = ui.files.draw()
    if answer is not None:
        cmds.file_chosen(app, ui, *answer)
    elif not ui.files.active:
        ui.quit_after_save = False  # the Save-as of the quit prompt was cancelled
        ui.after_save = None  # ... or of the unsaved-changes prompt before New / Open
    _draw_recovery(app, ui)
    _draw_confirm(app, ui)
    ui.palette.draw(app, ui, table)


def _menu_item(app: "App", ui: "UiState", c: "Command") -> None:
    if c.separator_before:
        imgui.separator()
    label, enabled = c.label, c.enabled is None or c.enabled(app, ui)
    if c.menu == "Edit" and c.label in ("Undo", "Redo"):
        pending = app.undo_stack.undo_label if c.label == "Undo" else app.undo_stack.redo_label
        label, enabled = f"{c.label} {pending or ''}###{c.label}", pending is not None
    if c.checked is not None:
        if imgui.menu_item(label, c.shortcut, c.checked(app, ui), enabled)[0]:
            c.run(app, ui)
    elif imgui.menu_item_simple(label, c.shortcut, enabled=enabled):
        c.run(app, ui)


def _recent_menu(app: "App", ui: "UiState") -> None:
    """File → Open Recent: the user's recent scenes (newest first) and *Clear recent files*."""
    from jackpy.ui.commands import open_recent

    recent = app.preferences.recent
    if imgui.begin_menu("Open Recent", bool(recent)):
        for i, path in enumerate(recent):
            if imgui.menu_item_simple(f"{Path(path).name}  ({Path(path).parent})###recent{i}"):
                open_recent(app, ui, path)
        imgui.separator()
        if imgui.menu_item_simple("Clear recent files"):
            app.preferences.forget_recent()
        imgui.end_menu()


def _recover_menu(app: "App", ui: "UiState") -> None:
    """File → Recover: the recovery files crashed runs left (newest first; the one offered at
    start-up is in its prompt), each named by its scene and time; a click recovers it."""
    import time

    from jackpy.ui import session
    from jackpy.ui.commands import recover_orphan

    if imgui.begin_menu("Recover"):
        found = [p for p in session.orphans() if str(p) != ui.recovery_offer]
        for i, path in enumerate(found):
            try:
                when = time.strftime("%Y-%m-%d %H:%M", time.localtime(path.stat().st_mtime))
            except OSError:
                continue  # (recovered or discarded meanwhile)
            scene = session.recovery_scene(path)
            name = f"{scene.name}  ({scene.parent})" if scene is not None else "untitled scene"
            if imgui.menu_item_simple(f"{name}, autosaved {when}###recover{i}"):
                recover_orphan(app, ui, path)
        if not found:
            imgui.menu_item_simple("No recovery files", enabled=False)
        imgui.end_menu()


def default_save_path(app: "App") -> str:
    """Absolute Save-as default (kept here for callers; see :func:`jackpy.ui.commands.default_save_path`)."""
    from jackpy.ui.commands import default_save_path as default

    return default(app)


IMPORT_UNITS = ["mm", "cm", "m", "in"]
IMPORT_UP = ["y", "z"]


def import_options(ui: "UiState") -> None:
    """Units and up axis of the file to import (remembered for the next import)."""
    imgui.set_next_item_width(80)
    i = IMPORT_UNITS.index(ui.import_units) if ui.import_units in IMPORT_UNITS else 2
    ui.import_units = IMPORT_UNITS[imgui.combo("units", i, IMPORT_UNITS)[1]]
    imgui.same_line()
    imgui.set_next_item_width(60)
    i = IMPORT_UP.index(ui.import_up) if ui.import_up in IMPORT_UP else 0
    ui.import_up = IMPORT_UP[imgui.combo("up axis", i, IMPORT_UP)[1]]


QUIT_PROMPT = "Unsaved changes##quit"


def quit_choice(app: "App", ui: "UiState", choice: str) -> None:
    """The quit prompt's answer: ``"save"`` (save, then quit; Save-as first for an unnamed
    document), ``"discard"`` (quit without saving), ``"cancel"`` (keep working)."""
    from jackpy.ui import session
    from jackpy.ui.commands import ask_file, run_reporting

    ui.confirm = None
    if choice == "save":
        if app.session_path is None:
            ask_file(app, ui, "save_as")
            ui.quit_after_save = True
            return
        run_reporting(app, lambda: session.save_session(app, app.session_path))
        if not app.dirty:
            ui.quit_confirmed = ui.quit_requested = True
    elif choice == "discard":
        ui.quit_confirmed = ui.quit_requested = True


UNSAVED_PROMPT = "Unsaved changes##unsaved"


def _draw_confirm(app: "App", ui: "UiState") -> None:
    from jackpy.ui.commands import unsaved_choice

    if ui.confirm == "quit":
        title, doing, answer = QUIT_PROMPT, "quitting", quit_choice
    elif ui.confirm == "unsaved" and ui.pending is not None:
        title, doing, answer = UNSAVED_PROMPT, ui.pending[0], unsaved_choice
    else:
        return
    imgui.open_popup(title)
    if imgui.begin_popup_modal(title, None, imgui.WindowFlags_.always_auto_resize)[0]:
        imgui.text(f"Save the changes to {app.doc.title.lstrip('*')} before {doing}?")
        for label, choice in (("Save", "save"), ("Discard", "discard"), ("Cancel", "cancel")):
            pressed = imgui.button(label)
            if pressed or (choice == "cancel" and imgui.is_key_pressed(imgui.Key.escape, False)):
                answer(app, ui, choice)  # Escape is Cancel
                imgui.close_current_popup()
            imgui.same_line()
        imgui.new_line()
        imgui.end_popup()


def _draw_recovery(app: "App", ui: "UiState") -> None:
    from jackpy.ui import session
    from jackpy.ui.commands import run_reporting

    if ui.recovery_offer is None:
        return
    imgui.open_popup("Recover")
    if imgui.begin_popup_modal("Recover", None, imgui.WindowFlags_.always_auto_resize)[0]:
        imgui.text("jackpy did not close cleanly last time.")
        imgui.text(f"Recover the autosaved scene from {ui.recovery_offer}?")
        if imgui.button("Recover") or imgui.is_key_pressed(imgui.Key.enter, False):  # Enter: the safe answer
            run_reporting(app, lambda: session.recover(app, Path(ui.recovery_offer)))
            ui.recovery_offer = None
            imgui.close_current_popup()
        imgui.same_line()
        if imgui.button("Discard"):
            session.discard_recovery(Path(ui.recovery_offer))
            ui.recovery_offer = None
            imgui.close_current_popup()
        imgui.end_popup()
