"""The App driven through its glfw-shaped input handlers, offscreen: pick, drag, undo, joint rotation."""

import numpy as np
import pytest

from jackpy.ui.app import MOD_CONTROL, MOUSE_LEFT, PRESS, RELEASE, App
from jackpy.ui.session import default_scene

W, H = 800, 600


@pytest.fixture(scope="module")
def renderer():
    from jackpy.render import offscreen_renderer

    try:
        r = offscreen_renderer(W, H, samples=0)
    except Exception as exc:  # no EGL device
        pytest.skip(f"no offscreen OpenGL context: {exc}")
    yield r
    r.release()


def make_app(renderer) -> App:
    env, base = default_scene()
    app = App(env, renderer, (W, H))
    app.scene_dir = base
    app.camera.set_preset("front")
    app.step()
    return app


def drag(app: App, p0, p1, button=MOUSE_LEFT, mods=0, steps=10, frames_after=30):
    app.on_cursor_pos(*p0)
    app.on_mouse_button(button, PRESS, mods)
    for t in np.linspace(0, 1, steps + 1)[1:]:
        app.on_cursor_pos(*(np.asarray(p0) + t * (np.asarray(p1) - np.asarray(p0))))
        app.step()
    app.on_mouse_button(button, RELEASE, mods)
    for _ in range(frames_after):
        if not app.needs_solve:
            break
        app.step()


def hand(app):
    fig = app.figure_of_interest()
    from jackpy.ui.app import find_effectors

    return fig, find_effectors(fig)["right_hand"]


def test_drag_right_hand_20cm_along_x_then_undo(renderer):
    app = make_app(renderer)
    fig, site = hand(app)
    eff = __import__("jackpy.ui.app", fromlist=["find_effectors"]).find_effectors(fig)
    feet0 = {r: fig.site_world(*eff[r].split(".")).copy() for r in ("right_foot", "left_foot")}
    q0 = fig.q.copy()
    h0 = fig.site_world(*site.split("."))[:3, 3].copy()
    target = h0 + [0.2, 0.0, 0.0]
    p0, p1 = app.world_to_pixel(h0), app.world_to_pixel(target)
    from jackpy.ui.app import effector_segments

    hit = app.pick(*p0)  # the palm centre, or a thumb in front of it: both grab the right hand
    assert hit is not None and effector_segments(fig, eff)[hit.segment] == "right_hand"
    drag(app, p0, p1)
    h1 = fig.site_world(*site.split("."))[:3, 3]
    assert np.linalg.norm(h1 - target) < 0.01
    for r, w in feet0.items():  # planted: neither moves nor turns
        assert np.allclose(fig.site_world(*eff[r].split(".")), w, atol=1e-6)
    heels0 = {s: fig.site_world(f"{s}_foot", "heel") for s in ("left", "right")}
    assert all(np.allclose(h, fig.site_world(f"{s}_foot", "heel"), atol=1e-6) for s, h in heels0.items())
    assert np.all(fig.q >= fig.lower - 1e-9) and np.all(fig.q <= fig.upper + 1e-9)
    app.on_key(ord("Z"), 0, PRESS, MOD_CONTROL)
    assert np.array_equal(fig.q, q0)
    app.step()
    assert np.array_equal(fig.q, q0)
    assert app.goal(f"{fig.name}:{site}") is None
    app.on_key(ord("Y"), 0, PRESS, MOD_CONTROL)
    assert np.linalg.norm(fig.site_world(*site.split("."))[:3, 3] - target) < 0.01


def test_empty_space_left_drag_orbits_camera(renderer):
    app = make_app(renderer)
    yaw = app.camera.yaw
    q0 = app.figure_of_interest().q.copy()
    drag(app, (20, 20), (120, 20))
    assert app.camera.yaw != yaw
    assert np.array_equal(app.figure_of_interest().q, q0)
    assert app.undo_stack.undo_label is None


def test_control_drag_stops_joint_at_limit_while_wheel_turns(renderer):
    app = make_app(renderer)
    fig = app.figure_of_interest()
    joint = fig.joint("right_elbow")
    lo, hi = joint.dofs[0].lower, joint.dofs[0].upper
    kin = fig.kinematics()
    W_ = kin.forward(fig.q, fig.location).segments[kin.segment_index["right_forearm"]]
    mid = (W_ @ np.array([0, -0.04, 0, 1.0]))[:3]
    assert app.pick(*app.world_to_pixel(mid)).segment == "right_forearm"
    centre = (W_ @ np.array([0, 0, 0, 1.0]))[:3]
    app.on_cursor_pos(*app.world_to_pixel(mid))
    app.on_mouse_button(MOUSE_LEFT, PRESS, MOD_CONTROL)  # CONTROL + left: rotate about x
    assert app.manipulator.joint is not None
    # crank the wheel (in the y-z plane through the elbow) a long way round
    angles = np.linspace(0, 1.8 * np.pi, 60)
    for a in angles:
        p = centre + 0.04 * np.array([0.0, -np.cos(a), np.sin(a)])
        app.on_cursor_pos(*app.world_to_pixel(p + [0.0, 0.0, 0.0]))
        app.step()
        v = joint.displacement[0]
        assert lo - 1e-12 <= v <= hi + 1e-12
    assert abs(app.manipulator.wheel_angle) > np.pi  # the wheel kept turning past the limit
    assert np.isclose(joint.displacement[0], hi) or np.isclose(joint.displacement[0], lo)
    app.on_mouse_button(MOUSE_LEFT, RELEASE, MOD_CONTROL)
    app.undo()
    assert joint.displacement[0] == 0.0


def test_default_scene_is_the_standard_human_beside_chair_and_table(renderer):
    app = make_app(renderer)
    fig = app.figure_of_interest()
    assert fig.name == "male_p50" and len(fig.segments) == 74
    assert {"chair", "worktable"} <= set(app.env.figures)
    assert fig.name in app.loops  # the behaviors drive it
    from jackpy.body.human import support_height

    assert abs(support_height(fig)) < 1e-9  # standing on the floor
    head = fig.site_world("head", "view")[:3, 3]
    assert app.pick(*app.world_to_pixel(head)).segment == "head"


def test_plain_ik_fallback_drags_the_hand_too(renderer):
    app = make_app(renderer)
    app.settings.behaviors = False
    fig, site = hand(app)
    h0 = fig.site_world(*site.split("."))[:3, 3].copy()
    target = h0 + [-0.1, 0.0, 0.0]  # the left button drags along x
    drag(app, app.world_to_pixel(h0), app.world_to_pixel(target), frames_after=60)
    assert app.last_report is None  # no behavior frame ran
    assert np.linalg.norm(fig.site_world(*site.split("."))[:3, 3] - target) < 0.01
