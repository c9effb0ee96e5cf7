"""The workbench driven by Dear ImGui's test engine (jackpy.ui.gui_driver): a simulated user clicks
menus, buttons and list entries by their labels and types into fields, in a real window (Xvfb).

Open every panel from the View menu; Analysis → Reach on a workplace site; Save as through the
file browser (into a sub-folder it enters by a click), then File → Open Recent; quit with unsaved
changes and choose Cancel; the command palette runs "View: Side"; Preferences → Maya is saved.
"""

import json
import os
from pathlib import Path

import numpy as np
import pytest
from ui_support import in_child_process

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from imgui_bundle import imgui  # noqa: E402

from jackpy.ui import session  # noqa: E402
from jackpy.ui.app import App  # noqa: E402
from jackpy.ui.file_dialog import list_folder  # noqa: E402
from jackpy.ui.gui_driver import GuiDriver  # noqa: E402
from jackpy.ui.window import Window  # noqa: E402

MENU = "##MainMenuBar"
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


def drive(app, tests, size=(1280, 800)):
    """Run ``tests`` (name, func(ctx, window)) in one window; fail with every failed outcome."""
    win = Window(app, "jackpy gui test", size, visible=False)
    driver = GuiDriver(win)
    try:
        outcomes = [driver.run(name, lambda ctx, f=f: f(ctx, win)) for name, f in tests]
    finally:
        driver.stop()
        win.close()
        driver.destroy()
    failed = [str(o) for o in outcomes if not o.passed]
    assert not failed, "\n".join(failed)
    return outcomes


def default_app(tmp_path, monkeypatch):
    monkeypatch.setenv("HOME", str(tmp_path))  # the dialogs start in the home folder
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    return app


def test_every_panel_opens_from_the_view_menu(request, tmp_path, monkeypatch):
    if in_child_process(request):
        return
    app = default_app(tmp_path, monkeypatch)

    def open_all(ctx, win):
        ctx.set_ref(MENU)
        for title in win.ui.open_panels:
            ctx.menu_check(f"View/{title}")
        ctx.yield_(3)
        closed = [t for t, shown in win.ui.open_panels.items() if not shown]
        assert not closed, closed
        silent = {"Timeline"} if app.doc.timeline is None else set()  # drawn only with a motion
        missing = [t for t in win.ui.open_panels if t not in silent
                   and (imgui.internal.find_window_by_name(t) is None
                        or not imgui.internal.find_window_by_name(t).was_active)]
        assert not missing, missing

    drive(app, [("open every panel", open_all)])


def test_reach_in_the_analysis_panel(request, tmp_path, monkeypatch):
    if in_child_process(request):
        return
    from jackpy.body import make_human
    from jackpy.scene.workplace import load_workplace, stand_figure

    monkeypatch.setenv("HOME", str(tmp_path))
    wp = load_workplace(EXAMPLE)
    human = make_human("female", 50)
    stand_figure(human, wp.stand)
    wp.env.add(human)
    app = App(wp.env)

    def reach(ctx, win):
        ctx.set_ref(MENU)
        ctx.menu_check("View/Analysis")
        ctx.set_ref("Analysis")
        assert app.analysis.reach is None
        ctx.item_click("**/Reach")
        ctx.yield_(2)
        assert app.analysis.reach is not None, app.log[-3:]
        assert app.analysis.reach_target
        text = app.analysis.reach.describe()
        assert text.startswith("reached (") or text.startswith("short by ~"), text

    drive(app, [("press Reach", reach)])


def test_save_as_through_the_browser_then_open_recent(request, tmp_path, monkeypatch):
    if in_child_process(request):
        return
    app = default_app(tmp_path, monkeypatch)
    (tmp_path / "work").mkdir()
    (tmp_path / "work" / "notes.txt").write_text("not a scene")
    fig = app.figure_of_interest()

    def save_as(ctx, win):
        ctx.set_ref(MENU)
        ctx.menu_click("File/Save as...")
        ctx.yield_(2)
        assert win.ui.files.active and win.ui.files.folder == tmp_path  # starts at home, absolute
        ctx.set_ref("//Save scene as##jackpy file browser")
        ctx.item_click(r"**/work\/")  # a click on a folder ("work/", the slash escaped) enters it
        assert win.ui.files.folder == tmp_path / "work"
        listed = [e.name for e in list_folder(win.ui.files.folder, (".env",), win.ui.files.show_all)]
        assert listed == [], listed  # notes.txt is not a scene: not listed
        ctx.item_click("##name")
        ctx.key_chars_replace("bench")  # no extension: .env is added
        assert win.ui.files.active  # typed, not yet saved (Enter or Save saves)
        ctx.item_click("Save")
        ctx.yield_(2)
        assert not win.ui.files.active

    def open_recent(ctx, win):
        saved = tmp_path / "work" / "bench.env"
        assert saved.is_file() and Path(app.session_path) == saved and not app.dirty
        prefs = json.loads((tmp_path / "jackpy_home" / "preferences.json").read_text())
        assert prefs["recent"][0] == str(saved)
        app.doc.set_dof(fig, "right_elbow", 0, 0.7)
        ctx.set_ref(MENU)
        ctx.menu_click("File/New")
        ctx.yield_(2)
        assert win.ui.confirm == "unsaved" and Path(app.session_path) == saved  # New asks first
        ctx.set_ref("//Unsaved changes##unsaved")
        ctx.item_click("Discard")
        ctx.yield_(2)
        assert win.ui.confirm is None and app.session_path is None and not app.dirty
        ctx.set_ref(MENU)
        ctx.menu_click("File/Open Recent/###recent0")
        ctx.yield_(2)

    q_saved = fig.q.copy()
    drive(app, [("save as", save_as), ("open recent", open_recent)])
    assert Path(app.session_path) == tmp_path / "work" / "bench.env"
    assert np.array_equal(app.figure_of_interest().q, q_saved)


def test_quit_with_unsaved_changes_then_cancel(request, tmp_path, monkeypatch):
    if in_child_process(request):
        return
    app = default_app(tmp_path, monkeypatch)

    def quit_cancel(ctx, win):
        app.doc.set_dof(app.figure_of_interest(), "right_elbow", 0, 0.5)
        ctx.yield_(1)
        ctx.set_ref(MENU)
        ctx.menu_click("File/Quit")
        ctx.yield_(2)
        assert not win.should_close and win.ui.confirm == "quit"
        ctx.set_ref("//Unsaved changes##quit")
        ctx.item_click("Cancel")
        ctx.yield_(2)
        assert win.ui.confirm is None and not win.should_close and app.dirty

    drive(app, [("quit, cancel", quit_cancel)])


def test_command_palette_and_preferences(request, tmp_path, monkeypatch):
    if in_child_process(request):
        return
    app = default_app(tmp_path, monkeypatch)

    def palette(ctx, win):
        app.camera.set_preset("front")
        ctx.set_ref(MENU)
        ctx.menu_click("Help/Command palette")
        ctx.yield_(2)
        assert win.ui.palette_open
        names = win.ui.palette.names
        assert "File: Save as... (Ctrl+Shift+S)" in names and "View: Analysis" in names
        ctx.key_chars("side (3)")
        ctx.yield_(2)
        ctx.key_press(imgui.Key.enter)
        ctx.yield_(2)
        assert win.ui.palette.ran == ["View: Side (3)"] and not win.ui.palette_open
        assert abs(app.camera.yaw - np.pi / 2) < 1e-9 and app.camera.pitch == 0.0

    def preferences(ctx, win):
        ctx.set_ref(MENU)
        ctx.menu_click("Edit/Preferences...")
        ctx.set_ref("Preferences")
        ctx.item_click("**/Maya")
        assert app.preferences.mouse_preset == "maya" and app.settings.mouse_mapping == "maya"

    drive(app, [("palette", palette), ("preferences", preferences)])
    prefs = json.loads((tmp_path / "jackpy_home" / "preferences.json").read_text())
    assert prefs["mouse_preset"] == "maya"
    assert App(session.default_scene()[0]).settings.mouse_mapping == "maya"  # the next start uses it
