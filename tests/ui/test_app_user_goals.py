"""Goals panel goals on a behavior-driven human (user goals of its loop), and picking the eyes."""

import numpy as np
import pytest

from jackpy.ui.app import MOUSE_LEFT, PRESS, RELEASE, App
from jackpy.ui.scene_view import GoalPick
from jackpy.ui.session import default_scene

W, H = 800, 600


def make_app(renderer=None) -> App:
    env, base = default_scene()
    app = App(env, renderer, (W, H))
    app.scene_dir = base
    app.camera.set_preset("front")
    app.step()
    return app


def settle(app, frames=60):
    for _ in range(frames):
        if not app.needs_solve:
            break
        app.step()


def test_half_space_goal_on_the_elbow_is_solved_with_the_behaviors_and_undone():
    app = make_app()
    fig = app.figure_of_interest()
    eff = {s: fig.site_world(f"{s}_foot", "ball").copy() for s in ("left", "right")}
    e0 = fig.site_world("right_upper_arm", "elbow")[:3, 3].copy()
    app.command("add", lambda: app.add_goal(fig, "right_upper_arm.elbow", "half-space"))
    g = app.goal(f"{fig.name}:right_upper_arm.elbow")
    t = g.target
    t[:3, :3] = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]  # normal (the frame's y) +x
    g.target = t  # keep the elbow from swinging out (-x)
    assert np.allclose(g.goal.normal, [1.0, 0.0, 0.0])
    hand = app.ensure_goal(fig, "right_palm.palm_centre")
    before = hand.target.copy()
    for k in range(30):
        t = before.copy()
        t[:3, 3] += (k + 1) / 30 * np.array([0.15, 0.2, 0.35])
        hand.target = t
        app.drive_behaviors(hand, before)
        app.goals_changed()
        app.step()
    app.end_behavior_drag()
    app.needs_solve = True
    settle(app)
    assert app.user_goal_part(g.key) == "right"
    assert fig.site_world("right_upper_arm", "elbow")[0, 3] > e0[0] - 2e-3
    assert np.linalg.norm(fig.site_world("right_palm", "palm_centre")[:3, 3] - hand.target[:3, 3]) < 3e-3
    for s, w in eff.items():
        assert np.allclose(fig.site_world(f"{s}_foot", "ball"), w, atol=1e-5)
    app.remove_goal(g.key)
    app.needs_solve = True
    app.step()
    assert app.loops[fig.name].user_goals == []


def test_head_aim_goal_holds_with_behaviors():
    app = make_app()
    fig = app.figure_of_interest()
    app.command("add", lambda: app.add_goal(fig, "head.view", "aim"))
    g = app.goal(f"{fig.name}:head.view")
    t = g.target
    t[:3, 3] += [0.4, 0.2, 0.0]
    g.target = t
    app.goals_changed()
    settle(app)
    w = fig.site_world("head", "view")
    d = g.target[:3, 3] - w[:3, 3]
    assert np.degrees(np.arccos(w[:3, 2] @ d / np.linalg.norm(d))) < 1.0
    assert app.user_goal_part(g.key) == "head"


@pytest.fixture(scope="module")
def renderer():
    from ui_support import offscreen_renderer_or_skip

    r = offscreen_renderer_or_skip(W, H)
    yield r
    r.release()


def test_pressing_an_eye_grabs_the_gaze_target(renderer):
    app = make_app(renderer)
    fig = app.figure_of_interest()
    loop = app.loops[fig.name]
    app.camera.target = fig.site_world("head", "view")[:3, 3].copy()
    app.camera.distance = 0.6
    app.step()
    eye = fig.site_world("right_eye", "base")[:3, 3]
    p0 = app.world_to_pixel(eye)
    hit = app.pick(*p0)
    assert hit is not None and hit.segment == "right_eye", hit
    neck0 = fig.joint("atlanto_occipital").displacement.copy()
    eye0 = fig.joint("right_eye").displacement.copy()
    app.on_cursor_pos(*p0)
    app.on_mouse_button(MOUSE_LEFT, PRESS, 0)
    assert app.selection == GoalPick(f"{fig.name}:eyes")
    for t in np.linspace(0, 1, 6)[1:]:  # a little to the side: the eyes turn, the head stays
        app.on_cursor_pos(p0[0] + 120 * t, p0[1])
        app.step()
    app.on_mouse_button(MOUSE_LEFT, RELEASE, 0)
    settle(app)
    assert loop.state.eyes_target is not None
    assert np.abs(fig.joint("right_eye").displacement - eye0).max() > np.radians(1.0)
    assert np.abs(fig.joint("atlanto_occipital").displacement - neck0).max() < np.radians(0.5)
    g = app.goal(f"{fig.name}:eyes")
    t = g.target
    t[:3, 3] += [1.5, 0.0, 0.0]  # far out of the eyes' range: the head follows
    g.target = t
    app.drive_behaviors(g, g.target)
    app.goals_changed()
    settle(app)
    assert np.abs(fig.joint("atlanto_occipital").displacement - neck0).max() > np.radians(3)
