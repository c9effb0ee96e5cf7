"""The timeline panel's Record button in a real window (Xvfb), clicked by Dear ImGui's test engine:
a drag of the right hand becomes a key track; Ctrl+Z takes the take back."""

import os

import numpy as np
import pytest
from ui_support import in_child_process

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from jackpy.document.effectors import find_effectors  # noqa: E402
from jackpy.ui import session  # noqa: E402
from jackpy.ui.app import MOD_CONTROL, PRESS, App  # noqa: E402
from jackpy.ui.gui_driver import GuiDriver  # noqa: E402
from jackpy.ui.panels.timeline import TITLE  # noqa: E402
from jackpy.ui.window import Window  # noqa: E402


def test_record_a_drag_with_the_button(request, tmp_path, monkeypatch):
    if in_child_process(request):
        return
    monkeypatch.setenv("HOME", str(tmp_path))
    app = App(session.default_scene()[0])
    fig = app.figure_of_interest()
    assert app.doc.timeline is None
    seen = {}

    def record(ctx, win):
        win.ui.open_panels[TITLE] = True
        ctx.yield_(3)
        ctx.window_focus(TITLE)  # (docked with other panels, its tab may not be the one shown)
        ctx.yield_(2)
        ctx.set_ref(TITLE)
        ctx.item_click("Record")
        g = app.doc.ensure_goal(fig, find_effectors(fig)["right_hand"])
        start = g.manip.copy()
        for k in range(1, 41):
            m = start.copy()
            m[:3, 3] += np.array([0.0, 0.2, 0.25]) * k / 40
            app.doc.move_goal(g, m)
            ctx.yield_(1)
        ctx.item_click("Stop")
        ctx.yield_(2)
        seen["label"] = app.doc.undo_stack.undo_label
        tl = app.doc.timeline
        track = tl.track(fig.name, "hand.right", create=False) if tl is not None else None
        seen["keys"] = None if track is None else len(track.keys)
        app.on_key(ord("Z"), 0, PRESS, MOD_CONTROL)
        ctx.yield_(2)
        seen["after_undo"] = len(app.doc.timeline.tracks) if app.doc.timeline else -1

    win = Window(app, "jackpy record test", (1200, 800), visible=False)
    driver = GuiDriver(win)
    try:
        outcomes = [driver.run("record a drag", lambda ctx: record(ctx, win))]
    finally:
        driver.stop()
        win.close()
        driver.destroy()
    assert all(o.passed for o in outcomes), [str(o) for o in outcomes]
    assert seen["keys"] is not None and seen["keys"] >= 2, seen
    assert seen["label"].startswith("record") and "hand.right" in seen["label"], seen
    assert seen["after_undo"] == 0, seen
