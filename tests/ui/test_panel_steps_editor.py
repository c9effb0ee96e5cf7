"""The step editor panel: plan, move and undo headless; saved with the document; and in a real
window (Xvfb) a footprint dragged with the mouse changes the walk, Ctrl+Z restores it."""

import os

import numpy as np
import pytest
from ui_support import in_child_process

from jackpy.document import Document
from jackpy.ui import session
from jackpy.ui.panels.steps_editor import (TITLE, View, add_stride, bake, defaults, delete_stride, footsteps_of,
                                           move_footstep, plan_to, walk_of)


def _planned():
    env, base = session.default_scene()
    doc = Document(env)
    doc.scene_dir = base
    fig = doc.figure_of_interest()
    st = defaults()
    c = fig.site_world("pelvis", "centre")[:3, 3]
    plan_to(doc, st, fig, (c[0], c[2] + 2.0))
    return doc, st, fig


def _targets(walk):
    return np.array([np.concatenate([walk.at(t).pelvis.ravel(), walk.at(t).feet["left"].ravel()])
                     for t in np.arange(0.0, walk.duration, 0.05)])


def test_move_is_one_undo_step_and_the_walk_follows():
    doc, st, fig = _planned()
    steps0 = footsteps_of(doc, fig.name)
    walk0 = _targets(walk_of(doc, st, fig))
    j = 3
    move_footstep(doc, fig.name, j, steps0[j].x + 0.05, steps0[j].z, steps0[j].psi + 0.1)
    steps1 = footsteps_of(doc, fig.name)
    assert steps1[j].x == pytest.approx(steps0[j].x + 0.05) and steps1[j].psi == pytest.approx(steps0[j].psi + 0.1)
    assert all(a == b for k, (a, b) in enumerate(zip(steps0, steps1)) if k != j)
    walk1 = _targets(walk_of(doc, st, fig))
    assert walk1.shape != walk0.shape or np.abs(walk1 - walk0).max() > 0.02
    assert doc.undo()
    assert footsteps_of(doc, fig.name) == steps0
    assert np.array_equal(_targets(walk_of(doc, st, fig)), walk0)
    assert doc.undo() and footsteps_of(doc, fig.name) is None  # the plan itself was one command
    assert doc.redo() and doc.redo() and footsteps_of(doc, fig.name) == steps1


def test_add_and_delete_a_stride_are_undoable():
    doc, st, fig = _planned()
    steps0 = footsteps_of(doc, fig.name)
    d0 = walk_of(doc, st, fig).duration
    add_stride(doc, fig.name, 3)
    steps1 = footsteps_of(doc, fig.name)
    assert len(steps1) == len(steps0) + 2
    assert all(a.side != b.side for a, b in zip(steps1[1:], steps1[2:]))
    assert walk_of(doc, st, fig).duration > d0  # two more steps to walk
    delete_stride(doc, fig.name, 4)  # the two just added
    assert footsteps_of(doc, fig.name) == steps0
    assert doc.undo() and footsteps_of(doc, fig.name) == steps1
    assert doc.undo() and footsteps_of(doc, fig.name) == steps0
    with pytest.raises(ValueError, match="standing feet"):
        delete_stride(doc, fig.name, len(steps0) - 3)


def test_standing_feet_do_not_move():
    doc, st, fig = _planned()
    with pytest.raises(ValueError, match="standing feet"):
        move_footstep(doc, fig.name, 1, 0.0, 0.0, 0.0)


def test_plan_is_saved_with_the_document(tmp_path):
    doc, st, fig = _planned()
    s = footsteps_of(doc, fig.name)[4]
    move_footstep(doc, fig.name, 4, s.x - 0.05, s.z + 0.05, s.psi)
    path = doc.save(tmp_path / "walk_scene.env")
    again = Document.open(path)
    assert footsteps_of(again, fig.name) == footsteps_of(doc, fig.name)


def test_plan_walks_round_the_scenes_props():
    """The default scene's worktable and chair are figures, not CAD objects: planned round too."""
    from shapely.geometry import Polygon

    from jackpy.ui.panels.steps_editor import floor_of, footprint, gait_of

    env, base = session.default_scene()
    doc = Document(env)
    fig = doc.figure_of_interest()
    st = defaults()
    floor = floor_of(doc, st, fig)
    assert len(floor.footprints) == 2  # worktable, chair
    c = fig.site_world("pelvis", "centre")[:3, 3]
    plan_to(doc, st, fig, (c[0] + 2.4, c[2] + 0.1))  # beyond the worktable (x 0.6..1.8 m)
    steps = footsteps_of(doc, fig.name)
    assert not any(Polygon(footprint(s, gait_of(st, fig))).intersects(f) for s in steps for f in floor.footprints)
    assert max(abs(s.z - c[2]) for s in steps) > 0.5  # went round it (z -0.3..0.5 m), not through


def test_bake_writes_the_edited_walk_and_leaves_the_figure(tmp_path):
    from jackpy.motion import motion_file

    doc, st, fig = _planned()
    q0 = fig.q.copy()
    st["path"] = str(tmp_path / "w.motion.json")
    walk = walk_of(doc, st, fig)
    bake(st, fig, walk)
    mf = motion_file.load(st["path"])
    assert mf.timeline.duration == pytest.approx(walk.duration, abs=1.0 / 30)
    assert np.array_equal(fig.q, q0)


def test_view_round_trip():
    doc, st, fig = _planned()
    v = View((10.0, 20.0), (400.0, 300.0), [s.point for s in footsteps_of(doc, fig.name)])
    p = np.array([0.3, 1.2])
    assert np.allclose(v.to_floor(v.to_px(p)), p)
    assert v.to_px(p + [0.0, 0.1])[1] < v.to_px(p)[1]  # +z is up the screen
    assert v.to_px(p + [0.1, 0.0])[0] < v.to_px(p)[0]  # +x to the left, seen from above
    # walking up the screen (+z), the left foot (+x) is drawn on the left
    steps = footsteps_of(doc, fig.name)
    left = next(s for s in steps[2:] if s.side == "left")
    right = next(s for s in steps[2:] if s.side == "right")
    if abs(steps[-1].psi) < 0.5:
        assert v.to_px(left.point)[0] < v.to_px(right.point)[0]


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="window tests need an X display (xvfb-run)")
def test_drag_a_footprint_in_the_window_then_ctrl_z(request):
    if in_child_process(request):
        return
    from jackpy.ui.app import MOD_CONTROL, MOUSE_LEFT, PRESS, RELEASE, App
    from jackpy.ui.window import Window

    env, _ = session.default_scene()
    app = App(env)
    fig = app.figure_of_interest()
    win = Window(app, "step editor", (1100, 800), visible=False)
    try:
        win.ui.open_panels[TITLE] = True
        st = win.ui.panel_state(TITLE, defaults())
        c = fig.site_world("pelvis", "centre")[:3, 3]
        plan_to(app.doc, st, fig, (c[0], c[2] + 2.0))  # the Plan walk button's action
        for _ in range(3):
            win.frame()
        steps0 = footsteps_of(app.doc, fig.name)
        walk0 = _targets(walk_of(app.doc, st, fig))
        j = 3
        px, scale = st["view"].to_px(steps0[j].point), st["view"].scale
        # the footprint is drawn in its side's colour at its place (framebuffer rows bottom-up)
        fw, fh = win.ctx.screen.size
        pixels = np.frombuffer(win.ctx.screen.read(components=3), np.uint8).reshape(fh, fw, 3)
        r, g, b = pixels[fh - 1 - int(round(px[1])), int(round(px[0]))].astype(int)
        assert (b > r + 60) if steps0[j].side == "left" else (r > b + 60), (r, g, b)
        h = win.handle
        win.cursor_pos_callback(h, *px)
        win.frame()
        win.mouse_button_callback(h, MOUSE_LEFT, PRESS, 0)
        win.frame()
        for k in range(1, 11):
            win.cursor_pos_callback(h, px[0] + 3.0 * k, px[1])
            win.frame()
        win.mouse_button_callback(h, MOUSE_LEFT, RELEASE, 0)
        win.frame()
        win.frame()
        steps1 = footsteps_of(app.doc, fig.name)
        moved_by = steps1[j].x - steps0[j].x
        assert moved_by == pytest.approx(-30.0 / scale, rel=0.05)  # 30 px right: -x seen from above
        assert all(a == b for k, (a, b) in enumerate(zip(steps0, steps1)) if k != j)
        walk1 = _targets(walk_of(app.doc, st, fig))
        assert walk1.shape != walk0.shape or np.abs(walk1 - walk0).max() > 0.01  # the walk changed
        assert app.doc.undo_stack.undo_label == f"move footstep {j} of {fig.name}"
        app.on_key(ord("Z"), 0, PRESS, MOD_CONTROL)
        win.frame()
        assert footsteps_of(app.doc, fig.name) == steps0
        assert np.array_equal(_targets(walk_of(app.doc, st, fig)), walk0)
    finally:
        win.close()
