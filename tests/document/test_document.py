"""The scene document headless: a goal kind defined here only, saved and reopened; the Goals
panel's kinds; the headless document against the window's app fed the same input events; live
analyses current after a step without any draw."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.document import Document, new_goal, placeable_kinds
from jackpy.document.session import default_scene
from jackpy.ik.goals import GOAL_TYPES, SiteGoal
from jackpy.ik.goals.base import Context, GoalEval, point3


class AboveFloor(SiteGoal):
    """Test-only goal kind: keep the site at least ``height`` (m) above the plane y = ``floor_y``."""

    kind = "test-above-floor"
    targets = ("floor_y",)
    params = ("height",)

    def __init__(self, site, floor_y=0.0, height=0.5, chain=None, weight=1.0, name=None):
        super().__init__(site, chain, weight, name)
        self.floor_y = float(floor_y)
        self.height = float(height)

    def evaluate(self, ctx: Context) -> GoalEval:
        r = ctx.site(self.seg, self.location)[:3, 3]
        short = self.floor_y + self.height - r[1]
        if short <= 0.0:
            return GoalEval(np.zeros(1), np.zeros((1, ctx.cols.size)))
        return GoalEval(np.array([short]), -ctx.point_jacobian(self.seg, r)[1:2], metres=short)

    def set_frame(self, frame):
        self.floor_y = float(point3(frame)[1]) - self.height


def default_document() -> Document:
    env, base = default_scene()
    doc = Document(env)
    doc.scene_dir = base
    return doc


def test_a_goal_kind_defined_in_a_test_module_is_added_saved_reopened_and_offered(tmp_path):
    assert GOAL_TYPES["test-above-floor"] is AboveFloor  # registered by being defined, nothing else
    doc = default_document()
    fig = doc.figure_of_interest()
    g = doc.add_goal(fig, "right_palm.palm_centre", "test-above-floor", height=0.8)
    assert g.kind == "test-above-floor" and g.goal.height == 0.8
    y = fig.site_world("right_palm", "palm_centre")[1, 3]
    assert g.goal.floor_y == pytest.approx(y - 0.8)  # placed so that it holds now
    t = g.target
    t[:3, 3] += [0.0, 0.25, 0.0]
    g.target = t
    doc.goals_changed()
    for _ in range(40):
        doc.step()
    assert fig.site_world("right_palm", "palm_centre")[1, 3] >= g.goal.floor_y + 0.8 - 2e-3
    path = doc.save(tmp_path / "above.env")
    other = Document.open(path)
    h = other.goal(g.key)
    assert type(h.goal) is AboveFloor and h.goal.floor_y == g.goal.floor_y and h.goal.height == 0.8
    assert np.array_equal(h.target, g.target) and h.site == "right_palm.palm_centre"
    # the Goals panel's kind list (its data, read without a window) offers the new kind
    from jackpy.ui.panels import goals as goals_panel

    assert "test-above-floor" in goals_panel.kinds() and goals_panel.kinds() == placeable_kinds()
    assert {"position", "orientation", "position+orientation", "aim", "plane", "half-space", "line",
            "distance"} <= set(goals_panel.kinds())


def test_undo_labels_name_the_goal_kind():
    doc = default_document()
    fig = doc.figure_of_interest()
    doc.command("add", lambda: doc.add_goal(fig, "head.view", "distance", radius=0.3))
    doc.remove_goal(f"{fig.name}:head.view")
    assert doc.undo_stack.undo_label == f"remove distance goal {fig.name}:head.view"
    assert doc.undo() and doc.goal(f"{fig.name}:head.view").kind == "distance"


def _drag_events(app, start, end, frames):
    """The window's input for a hand drag: press on the hand, move in ``frames`` steps, release."""
    from jackpy.ui.app import MOUSE_LEFT, PRESS, RELEASE

    yield lambda: (app.on_cursor_pos(*start), app.on_mouse_button(MOUSE_LEFT, PRESS, 0))
    for t in np.linspace(0.0, 1.0, frames + 1)[1:]:
        p = np.asarray(start) + t * (np.asarray(end) - np.asarray(start))
        yield lambda p=p: app.on_cursor_pos(*p)
    yield lambda: app.on_mouse_button(MOUSE_LEFT, RELEASE, 0)


def test_headless_document_matches_the_window_app_bit_for_bit():
    """100 steps with a dragged hand goal: the app fed input events (press, moves, release) and a
    headless Document given the same goal moves give the same postures, bit for bit."""
    from jackpy.document.effectors import find_effectors
    from jackpy.ui.app import App
    from jackpy.ui.scene_view import GoalPick

    env, base = default_scene()
    app = App(env, size=(800, 600))
    app.settings.ik_time_budget_s = 0.0  # one behavior frame per step: no clock in the result
    fig = app.figure_of_interest()
    hand = app.ensure_goal(fig, find_effectors(fig)["right_hand"])
    app.camera.set_preset("front")
    app.manipulation_mode = True  # no renderer to pick with: the drag moves the selection
    app.select(GoalPick(hand.key))
    p0 = app.world_to_pixel(hand.target[:3, 3])
    frames = 60
    manips, postures = [], []
    events = list(_drag_events(app, p0, p0 + [120.0, -90.0], frames))
    for k in range(100):
        if k < len(events):
            events[k]()
        app.step()
        manips.append((hand.manip.copy(), app.manipulator.active))
        postures.append(fig.q.copy())
    assert np.linalg.norm(manips[-1][0][:3, 3] - manips[0][0][:3, 3]) > 0.1  # the hand goal moved

    env2, _ = default_scene()
    doc = Document(env2)
    doc.settings.ik_time_budget_s = 0.0
    fig2 = doc.figure_of_interest()
    hand2 = doc.ensure_goal(fig2, find_effectors(fig2)["right_hand"])
    before = doc.capture()
    for k in range(100):
        manip, active = manips[k]
        if not np.array_equal(manip, hand2.manip):
            doc.move_goal(hand2, manip)
        if k == len(events) - 1:  # the release
            doc.end_behavior_drag()
            doc.needs_solve = True
            doc.push("drag", before)
        doc.step(1 / 60)
        if active:
            doc.needs_solve = True
        assert np.array_equal(fig2.q, postures[k]), k


def test_live_analyses_are_current_after_a_step_without_any_draw():
    """Strength and clearance follow the posture in Document.step; nothing is drawn."""
    doc = default_document()
    live = doc.analyses
    live.strength_live, live.clearance_on, live.load_kg = True, True, 10.0
    fig = doc.figure_of_interest()
    doc.step()
    assert live.strength is not None and live.clearance is not None, (live.strength_error, live.clearance_error)
    tau0, d0, n0 = live.strength.torques.copy(), live.clearance.distance, live.refreshes
    g = doc.ensure_goal(fig, "right_palm.palm_centre")
    t = g.target
    t[:3, 3] += [0.15, 0.25, 0.2]
    doc.move_goal(g, t)
    for _ in range(20):
        doc.step()
    assert live.refreshes > n0
    assert not np.allclose(live.strength.torques, tau0) and live.clearance.distance != d0
    # they equal a fresh computation at the final posture
    from jackpy.document.analyses import LiveAnalyses

    fresh = LiveAnalyses(strength_live=True, clearance_on=True, load_kg=10.0,
                         clearance_object=live.clearance_object)
    fresh.refresh(doc.env)
    assert np.array_equal(fresh.strength.torques, live.strength.torques)
    assert fresh.clearance.distance == live.clearance.distance


def test_overlays_use_the_steps_results_and_the_draw_does_not_recompute():
    from jackpy.render import Scene
    from jackpy.ui.app import App

    env, base = default_scene()
    app = App(env)
    st = app.analysis
    st.torque_colouring, st.clearance_on, st.load_kg = True, True, 5.0
    app.step()  # no renderer: the document's step only
    n = st.refreshes
    assert st.strength is not None and app.doc.analyses is st
    scene = app.view.build(app.env, app.goals)
    st.overlay(app, scene, renderer=_NoUpload())
    assert st.refreshes == n  # building the overlays computed nothing
    coloured = {it.mesh: it.color for it in scene.items}
    key = app.view.mesh_key(app.figure_of_interest().name, "right_upper_arm")
    assert coloured[key] == pytest.approx(st.strength.segment_colours["right_upper_arm"])
    assert isinstance(scene, Scene)


class _NoUpload:
    """Stands in for a renderer where the overlays upload meshes (none needed for colours)."""

    def has_mesh(self, key):
        return True

    def add_mesh(self, key, mesh, replace=False):
        raise AssertionError("no mesh upload expected")


def test_document_imports_nothing_from_the_ui():
    import subprocess
    import sys

    code = ("import sys, jackpy.document, jackpy.document.session; "
            "bad = [m for m in sys.modules if m.startswith('jackpy.ui')]; "
            "print(bad); sys.exit(1 if bad else 0)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr


def test_timeline_is_applied_before_the_solve():
    class Clock:
        duration = 1.0

        def __init__(self):
            self.calls = []

        def apply(self, t, loops, env):
            self.calls.append((t, sorted(loops)))

        def to_dict(self):
            return {}

    doc = default_document()
    doc.timeline, doc.playing = Clock(), True
    doc.step(0.25)
    doc.step(0.25)
    assert doc.time == 0.5 and [c[0] for c in doc.timeline.calls] == [0.25, 0.5]
    assert doc.timeline.calls[0][1] == sorted(doc.loops)
    doc.playing = False
    doc.step(0.25)
    assert doc.time == 0.5


def test_new_goal_of_every_placeable_kind_holds_where_it_is_made():
    doc = default_document()
    fig = doc.figure_of_interest()
    for kind in placeable_kinds():
        e = new_goal(fig, "left_palm.palm_centre", kind)
        e.goal.bind(fig)
        kin = fig.kinematics()
        ev = e.goal.evaluate(Context(kin, kin.forward(fig.q, fig.location), np.zeros(0, dtype=int)))
        assert ev.metres < 1e-9 and ev.degrees < 1e-6, kind
