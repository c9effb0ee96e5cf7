"""The workbench window opens, draws the 3-D view and the panels, and closes (Xvfb)."""

import os
import subprocess
import sys

import numpy as np
import pytest
from ui_support import in_child_process

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.scene_view import SegmentPick
from jackpy.ui.window import Window




def test_window_draws_view_and_panels(request):
    if in_child_process(request):
        return
    env, base = session.default_scene()
    app = App(env)
    win = Window(app, "jackpy smoke", (900, 640), visible=False)
    try:
        fig = app.figure_of_interest()
        app.select(SegmentPick(fig.name, "right_forearm"))
        for name in ("Figure", "Behaviors", "Devices"):  # every panel of the workbench draws
            win.ui.open_panels[name] = True
        from jackpy.ui.commands import file_request

        win.ui.files.ask(file_request(app, win.ui, "import"))  # the Import CAD browser with units and up axis
        for _ in range(3):
            win.frame()
        pixels = np.frombuffer(win.ctx.screen.read(components=3), np.uint8).reshape(640, 900, 3)
        assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50  # a scene and panels, not a blank
        r = win.view_rect  # the 3-D view fills the dock's central node
        assert app.renderer.size == (int(r.w), int(r.h)) and 0 < r.w < 900 and 0 < r.h < 640
    finally:
        win.close()


def test_jackpy_open_runs_frames_and_exits(tmp_path):
    env = dict(os.environ, JACKPY_HOME=str(tmp_path))
    done = subprocess.run([sys.executable, "-m", "jackpy", "open", "--frames", "3"], env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr


def test_quit_with_unsaved_changes_asks_and_the_title_shows_it(request, tmp_path):
    """Ctrl+Q (or the close button) on a modified document opens Save / Discard / Cancel; Cancel
    keeps the window, Save writes the file and quits, Discard quits; the title is ``name — jackpy``
    with ``*`` while modified."""
    if in_child_process(request):
        return
    from jackpy.ui.panels.menu_bar import quit_choice

    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    win = Window(app, "jackpy", (800, 600), visible=False)
    try:
        win.frame()
        assert win._title == "untitled \u2014 jackpy"
        fig = app.figure_of_interest()
        app.doc.set_dof(fig, "right_elbow", 0, 0.5)
        win.frame()
        assert app.dirty and win._title == "*untitled \u2014 jackpy"
        win.key_callback(None, ord("Q"), 0, 1, 2)  # Ctrl+Q
        assert not win.should_close and win.ui.confirm == "quit"
        win.frame()  # the prompt is drawn
        quit_choice(app, win.ui, "cancel")
        assert not win.should_close and win.ui.confirm is None
        import glfw

        glfw.set_window_should_close(win.handle, True)  # the window's close button
        assert not win.should_close and win.ui.confirm == "quit"
        app.doc.path = tmp_path / "q.env"
        quit_choice(app, win.ui, "save")
        assert (tmp_path / "q.env").is_file() and not app.dirty and win.should_close
        win.frame()
        assert win._title == "q.env \u2014 jackpy"
        win.ui.quit_confirmed = win.ui.quit_requested = False
        app.doc.set_dof(fig, "right_elbow", 0, 0.2)
        win.ui.quit_requested = True
        assert not win.should_close
        quit_choice(app, win.ui, "discard")
        assert win.should_close
    finally:
        win.close()
