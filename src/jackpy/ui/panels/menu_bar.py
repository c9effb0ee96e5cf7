"""The main menu bar (File, Edit, View) and the path prompt its items open."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from imgui_bundle import imgui

from jackpy.errors import JackpyError

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

PROMPTS = {"open": "Open scene (.env)", "save_as": "Save scene as (.env)",
           "import": "Import CAD (stl, obj, ply, glb, 3mf, dae, step ...)", "screenshot": "Save screenshot (.png)"}


def draw(app: "App", ui: "UiState") -> None:
    from jackpy.ui import session

    if imgui.begin_main_menu_bar():
        if imgui.begin_menu("File"):
            if imgui.menu_item_simple("New"):
                app.command("new scene", lambda: session.new_scene(app), structural=True)
            if imgui.menu_item_simple("Open...", "Ctrl+O"):
                _prompt(ui, "open", "")
            if imgui.menu_item_simple("Save", "Ctrl+S"):
                if app.session_path is None:
                    _prompt(ui, "save_as", default_save_path(app))
                else:
                    _run(app, lambda: session.save_session(app, app.session_path))
            if imgui.menu_item_simple("Save as..."):
                _prompt(ui, "save_as", default_save_path(app))
            imgui.separator()
            if imgui.menu_item_simple("Import CAD..."):
                _prompt(ui, "import", "")
            if imgui.menu_item_simple("Screenshot..."):
                _prompt(ui, "screenshot", "screenshot.png")
            imgui.separator()
            if imgui.menu_item_simple("Quit", "Ctrl+Q"):
                ui.quit_requested = True
            imgui.end_menu()
        if imgui.begin_menu("Edit"):
            if imgui.menu_item_simple(f"Undo {app.undo_stack.undo_label or ''}", "Ctrl+Z",
                                      enabled=app.undo_stack.undo_label is not None):
                app.undo()
            if imgui.menu_item_simple(f"Redo {app.undo_stack.redo_label or ''}", "Ctrl+Y",
                                      enabled=app.undo_stack.redo_label is not None):
                app.redo()
            imgui.end_menu()
        if imgui.begin_menu("View"):
            for name, key in (("front", "1"), ("side", "3"), ("top", "7"), ("iso", "9")):
                if imgui.menu_item_simple(name.capitalize(), key):
                    app.camera.set_preset(name)
            if imgui.menu_item_simple("Frame all", "F"):
                app.frame_all()
            s = app.settings
            s.skeleton = imgui.menu_item("Skeleton", "K", s.skeleton)[1]
            s.show_floor = imgui.menu_item("Floor", "", s.show_floor)[1]
            app.camera.orthographic = imgui.menu_item("Orthographic", "", app.camera.orthographic)[1]
            s.literal_grab = imgui.menu_item("Literal Jack grab (jump)", "", s.literal_grab)[1]
            s.gizmo_local = imgui.menu_item("Gizmo in local frame", "", s.gizmo_local)[1]
            app.manipulation_mode = imgui.menu_item("Manipulation mode", "M", app.manipulation_mode)[1]
            if imgui.menu_item_simple("Reset layout"):
                ui.reset_layout = True
            imgui.separator()
            for name in ui.open_panels:
                ui.open_panels[name] = imgui.menu_item(name, "", ui.open_panels[name])[1]
            imgui.end_menu()
        imgui.end_main_menu_bar()
    _draw_prompt(app, ui)
    _draw_recovery(app, ui)
    _draw_confirm(app, ui)


def default_save_path(app: "App") -> str:
    """Absolute Save-as default: the document's own path, else ``scene.env`` in the user's home."""
    return str(Path(app.session_path).absolute() if app.session_path else Path.home().absolute() / "scene.env")


def _prompt(ui: "UiState", kind: str, text: str) -> None:
    ui.prompt, ui.prompt_text = kind, text


def _run(app: "App", action) -> None:
    try:
        action()
    except (JackpyError, OSError, ValueError) as exc:
        app.info(f"error: {exc}")


def _draw_prompt(app: "App", ui: "UiState") -> None:
    from jackpy.ui import screenshot, session

    if ui.prompt is None:
        return
    imgui.open_popup("path")
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((vp.size.x / 2, vp.size.y / 3), imgui.Cond_.appearing, (0.5, 0.5))
    if imgui.begin_popup_modal("path", None, imgui.WindowFlags_.always_auto_resize)[0]:
        imgui.text(PROMPTS[ui.prompt])
        imgui.set_next_item_width(420)
        done, ui.prompt_text = imgui.input_text("##path", ui.prompt_text, imgui.InputTextFlags_.enter_returns_true)
        if ui.prompt == "import":
            _import_options(ui)
        done = imgui.button("OK") or done
        imgui.same_line()
        cancel = imgui.button("Cancel")
        if done and ui.prompt_text.strip():
            path, kind = Path(ui.prompt_text.strip()).expanduser().absolute(), ui.prompt
            actions = {
                "open": lambda: session.open_session(app, path),
                "save_as": lambda: session.save_session(app, path),
                "import": lambda: app.import_cad(path, ui.import_units, ui.import_up),
                "screenshot": lambda: screenshot.save_view(app, path),
            }
            _run(app, actions[kind])
            if kind == "save_as" and ui.quit_after_save and not app.dirty:
                ui.quit_confirmed = ui.quit_requested = True
        if done or cancel:
            ui.quit_after_save = False
            ui.prompt = None
            imgui.close_current_popup()
        imgui.end_popup()


IMPORT_UNITS = ["mm", "cm", "m", "in"]
IMPORT_UP = ["y", "z"]


def _import_options(ui: "UiState") -> None:
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

    ui.confirm = None
    if choice == "save":
        if app.session_path is None:
            _prompt(ui, "save_as", default_save_path(app))
            ui.quit_after_save = True
            return
        _run(app, lambda: session.save_session(app, app.session_path))
        if not app.dirty:
            ui.quit_confirmed = ui.quit_requested = True
    elif choice == "discard":
        ui.quit_confirmed = ui.quit_requested = True


def _draw_confirm(app: "App", ui: "UiState") -> None:
    if ui.confirm != "quit":
        return
    imgui.open_popup(QUIT_PROMPT)
    if imgui.begin_popup_modal(QUIT_PROMPT, None, imgui.WindowFlags_.always_auto_resize)[0]:
        imgui.text(f"Save the changes to {app.doc.title.lstrip('*')} before quitting?")
        for label, choice in (("Save", "save"), ("Discard", "discard"), ("Cancel", "cancel")):
            if imgui.button(label):
                quit_choice(app, ui, choice)
                imgui.close_current_popup()
            imgui.same_line()
        imgui.new_line()
        imgui.end_popup()


def _draw_recovery(app: "App", ui: "UiState") -> None:
    from jackpy.ui import session

    if ui.recovery_offer is None:
        return
    imgui.open_popup("Recover")
    if imgui.begin_popup_modal("Recover", None, imgui.WindowFlags_.always_auto_resize)[0]:
        imgui.text("jackpy did not close cleanly last time.")
        imgui.text(f"Recover the autosaved scene from {ui.recovery_offer}?")
        if imgui.button("Recover"):
            _run(app, lambda: session.recover(app, Path(ui.recovery_offer)))
            ui.recovery_offer = None
            imgui.close_current_popup()
        imgui.same_line()
        if imgui.button("Discard"):
            session.discard_recovery(Path(ui.recovery_offer))
            ui.recovery_offer = None
            imgui.close_current_popup()
        imgui.end_popup()
