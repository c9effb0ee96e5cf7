"""The path editor panel: add, move, delete points headless (one undo step each, the footsteps
follow), the mouse's press/drag/release, obstacles flagged, saved with the document; and in a real
window (Xvfb) a path point dragged with the mouse changes the footsteps, Ctrl+Z restores them."""

import os

import numpy as np
import pytest
from ui_support import in_child_process

from jackpy.document import Document
from jackpy.locomotion import footsteps
from jackpy.ui import session
from jackpy.ui.panels.path_editor import (TITLE, add_point, defaults, delete_at, delete_point, drag_to, flags_of,
                                          move_point, press, release, start_of, steps_for)
from jackpy.ui.panels.steps_editor import View, footsteps_of, move_footstep, path_of, plan_to


def _doc():
    env, base = session.default_scene()
    doc = Document(env)
    doc.scene_dir = base
    return doc, defaults(), doc.figure_of_interest()


def _plan(doc, name):
    return path_of(doc, name), footsteps_of(doc, name)


def test_add_move_delete_are_one_undo_step_each_and_the_footsteps_follow():
    doc, st, fig = _doc()
    x0, z0 = start_of(fig)
    assert add_point(doc, st, fig, (x0, z0 + 2.0)) == 1  # begins the path where the figure stands
    plan1 = _plan(doc, fig.name)
    assert plan1[0] == [(x0, z0), (x0, z0 + 2.0)] and plan1[1] == steps_for(st, fig, plan1[0])
    add_point(doc, st, fig, (x0 - 1.0, z0 + 3.0))
    plan2 = _plan(doc, fig.name)
    move_point(doc, st, fig, 1, (x0 + 0.4, z0 + 1.5))
    plan3 = _plan(doc, fig.name)
    assert plan3[0][1] == (x0 + 0.4, z0 + 1.5) and plan3[1] == steps_for(st, fig, plan3[0]) != plan2[1]
    delete_point(doc, st, fig, 1)
    assert _plan(doc, fig.name)[0] == [(x0, z0), (x0 - 1.0, z0 + 3.0)]
    for before in (plan3, plan2, plan1):
        assert doc.undo() and _plan(doc, fig.name) == before
    assert doc.undo() and _plan(doc, fig.name) == (None, None)
    assert doc.redo() and doc.redo() and _plan(doc, fig.name) == plan2
    with pytest.raises(ValueError, match="where the figure stands"):
        move_point(doc, st, fig, 0, (1.0, 1.0))
    delete_point(doc, st, fig, 2)
    with pytest.raises(ValueError, match="two points"):
        delete_point(doc, st, fig, 1)


def _view(doc, st, fig):
    path, steps = _plan(doc, fig.name)
    pts = [np.array(start_of(fig))] + [np.array(q) for q in path or []] + [s.point for s in steps or []]
    st["view"] = View((0.0, 0.0), (600.0, 500.0), np.array(pts), 0.5)
    return st["view"]


def test_press_adds_drags_inserts_and_deletes():
    doc, st, fig = _doc()
    x0, z0 = start_of(fig)
    add_point(doc, st, fig, (x0, z0 + 2.0))
    view = _view(doc, st, fig)
    # a press on the empty floor adds a point at the end and drags it: one undo step
    far = view.to_px((x0 - 1.0, z0 + 2.5))
    assert press(doc, st, fig, far) == 2
    drag_to(doc, st, fig, far + [0.0, -20.0])
    release(doc, st, fig)
    path = path_of(doc, fig.name)
    assert len(path) == 3 and path[2][1] == pytest.approx(z0 + 2.5 + 20.0 / view.scale)
    assert doc.undo_stack.undo_label == f"add path point 2 of {fig.name}"
    assert footsteps_of(doc, fig.name) == steps_for(st, fig, path)
    # a press on the spline between points 0 and 1 inserts point 1 there
    mid = view.to_px((x0, z0 + 1.0))
    assert press(doc, st, fig, mid) == 1
    release(doc, st, fig)
    assert path_of(doc, fig.name)[1] == pytest.approx(tuple(view.to_floor(mid)))
    assert len(path_of(doc, fig.name)) == 4
    # a press on a point moves it (grabbed where pressed); on point 0 it only selects
    before = path_of(doc, fig.name)
    p3 = view.to_px(before[3])
    assert press(doc, st, fig, p3 + [2.0, 0.0]) == 3
    drag_to(doc, st, fig, p3 + [32.0, 0.0])
    release(doc, st, fig)
    assert path_of(doc, fig.name)[3][0] == pytest.approx(before[3][0] - 30.0 / view.scale)
    assert doc.undo_stack.undo_label == f"move path point 3 of {fig.name}"
    assert press(doc, st, fig, view.to_px(before[0])) == 0 and st["drag"] is None
    # a right click on a point deletes it; undo puts it back
    assert delete_at(doc, st, fig, view.to_px(before[1])) == 1
    assert len(path_of(doc, fig.name)) == 3
    assert doc.undo() and len(path_of(doc, fig.name)) == 4


def test_a_path_through_the_worktable_is_flagged():
    doc, st, fig = _doc()
    x0, z0 = start_of(fig)
    add_point(doc, st, fig, (x0, z0 + 1.5))
    flags, by_hand = flags_of(doc, st, fig, *_plan(doc, fig.name))
    assert flags.crossing == [] and flags.landing == [] and not by_hand
    add_point(doc, st, fig, (x0 + 2.4, z0 + 1.5))
    flags, _ = flags_of(doc, st, fig, *_plan(doc, fig.name))
    assert flags.crossing == [] and flags.landing == []
    # the worktable stands at x 0.6..1.8 m, z -0.3..0.5 m: a point on it
    move_point(doc, st, fig, 2, (x0 + 1.2, z0 + 0.1))
    flags, _ = flags_of(doc, st, fig, *_plan(doc, fig.name))
    assert flags.crossing == [1] and flags.inside.any()
    steps = footsteps_of(doc, fig.name)
    assert flags.landing and all(0.5 < steps[j].x < 1.9 for j in flags.landing)  # on the table's footprint
    assert len(steps) - 1 in flags.landing  # it would end standing on the table


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_a_path_turning_through_180_degrees_stands_facing_its_end(side):
    doc, st, fig = _doc()
    x0, z0 = start_of(fig)
    for q in ((x0, z0 + 2.0), (x0 + side * 1.2, z0 + 2.5), (x0 + side * 1.2, z0)):  # back along -z
        add_point(doc, st, fig, q)
    steps = footsteps_of(doc, fig.name)  # it stops (headings compared modulo 2π), turned the way it walked
    assert steps[-1].psi == steps[-2].psi == pytest.approx(side * np.pi, abs=0.1)
    assert all(abs(b.psi - a.psi) <= footsteps.MAX_TURN + 1e-9 for a, b in zip(steps[1:], steps[2:]))


def test_path_is_saved_with_the_document_and_old_plans_load(tmp_path):
    doc, st, fig = _doc()
    x0, z0 = start_of(fig)
    add_point(doc, st, fig, (x0 + 0.3, z0 + 2.0))
    add_point(doc, st, fig, (x0 - 0.5, z0 + 3.0))
    s = footsteps_of(doc, fig.name)[3]
    move_footstep(doc, fig.name, 3, s.x + 0.05, s.z, s.psi)  # a footstep edit keeps the path
    again = Document.open(doc.save(tmp_path / "path_scene.env"))
    assert _plan(again, fig.name) == _plan(doc, fig.name)
    assert flags_of(again, defaults(), again.figure_of_interest(), *_plan(again, fig.name))[1]  # moved by hand
    plan_to(doc, st, fig, (x0, z0 + 2.0))  # planned to a goal: footsteps without a path
    old = Document.open(doc.save(tmp_path / "old_scene.env"))
    assert path_of(old, fig.name) is None and footsteps_of(old, fig.name) == footsteps_of(doc, fig.name)
    st2 = defaults()
    add_point(old, st2, old.figure_of_interest(), (x0, z0 + 1.0))  # a click begins a path again
    assert len(path_of(old, fig.name)) == 2


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="window tests need an X display (xvfb-run)")
def test_drag_a_path_point_in_the_window_then_ctrl_z(request):
    if in_child_process(request):
        return
    from jackpy.ui.app import MOD_CONTROL, MOUSE_LEFT, PRESS, RELEASE, App
    from jackpy.ui.window import Window

    env, _ = session.default_scene()
    app = App(env)
    fig = app.figure_of_interest()
    win = Window(app, "path editor", (1100, 800), visible=False)
    try:
        win.ui.open_panels[TITLE] = True
        st = win.ui.panel_state(TITLE, defaults())
        x0, z0 = start_of(fig)
        for q in ((x0, z0 + 1.5), (x0 - 0.8, z0 + 2.5)):
            add_point(app.doc, st, fig, q)  # what two clicks on the floor do
        for _ in range(3):
            win.frame()
        path0, steps0 = _plan(app.doc, fig.name)
        px, scale = st["view"].to_px(path0[1]), st["view"].scale
        # the point is drawn (white) at its place (framebuffer rows bottom-up)
        fw, fh = win.ctx.screen.size
        pixels = np.frombuffer(win.ctx.screen.read(components=3), np.uint8).reshape(fh, fw, 3)
        assert pixels[fh - 1 - int(round(px[1])), int(round(px[0]))].min() > 200
        h = win.handle
        win.cursor_pos_callback(h, *px)
        win.frame()
        win.mouse_button_callback(h, MOUSE_LEFT, PRESS, 0)
        win.frame()
        for k in range(1, 11):
            win.cursor_pos_callback(h, px[0] + 4.0 * k, px[1])
            win.frame()
        win.mouse_button_callback(h, MOUSE_LEFT, RELEASE, 0)
        win.frame()
        win.frame()
        path1, steps1 = _plan(app.doc, fig.name)
        assert path1[1][0] - path0[1][0] == pytest.approx(-40.0 / scale, rel=0.05)  # right on screen: -x
        assert path1[2] == path0[2] and steps1 == steps_for(st, fig, path1)
        moved = max(abs(a.x - b.x) + abs(a.z - b.z) for a, b in zip(steps0, steps1))
        assert len(steps1) != len(steps0) or moved > 0.05  # the footprints followed
        assert app.doc.undo_stack.undo_label == f"move path point 1 of {fig.name}"
        app.on_key(ord("Z"), 0, PRESS, MOD_CONTROL)
        win.frame()
        assert _plan(app.doc, fig.name) == (path0, steps0)
    finally:
        win.close()
