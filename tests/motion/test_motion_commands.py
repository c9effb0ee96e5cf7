"""Each motion command of the book ([SH4] §4.4; behaviors.md §4.5, §7 items 16-17), headless with
the real behaviors and IK, including the seeds' own examples."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.behaviors.support import floor, yaw_of
from jackpy.motion.bake import Baker
from jackpy.motion.kinds.arm import ArmMotion
from jackpy.motion.kinds.com import COMMotion
from jackpy.motion.kinds.foot import FootMotion
from jackpy.motion.kinds.gaze import GazeMotion
from jackpy.motion.kinds.heel import HeelMotion
from jackpy.motion.kinds.pelvis import PelvisMotion
from jackpy.motion.kinds.torso import TorsoMotion
from jackpy.motion.timeline import Timeline


def run(tl, scene, until=None, fps=30.0, each=None):
    env, loops = scene
    b = Baker(tl, loops, env, fps)
    n = b.n_frames if until is None else b.frame_at(until) + 1
    out = []
    for i in range(n):
        b.seek(i)
        if each is not None:
            out.append(each(b.time_of(i), loops["jack"]))
    return loops["jack"], out


def weight_share(loop):
    bf = loop.balance_frame_for({s: f.target for s, f in loop.state.feet.items()})
    return bf.params(floor(loop.figure.centre_of_mass()))[0]


def test_com_motion_to_x_03_puts_30_percent_on_the_right_foot(scene):
    tl = Timeline([COMMotion(figure="jack", t0=0.0, t1=1.0, x=0.3, velocity_fn="ease")])
    tl.duration = 1.5
    loop, xs = run(tl, scene, each=lambda t, lp: weight_share(lp))
    assert xs[0] == pytest.approx(0.5, abs=0.01)
    assert loop.state.balance[0] == 0.3
    # the COM is held within the loop's tolerance of the balance point 30 % of the way to the right foot
    spread = np.linalg.norm(np.subtract(*[loop.foot_reference(s, f.target) for s, f in loop.state.feet.items()]))
    assert abs(xs[-1] - 0.3) * spread <= loop.com_tolerance
    assert xs[15] == pytest.approx(0.4, abs=0.02)  # ease: halfway in time is halfway along


def test_global_com_motion_moves_the_balance_point_there(scene):
    env, loops = scene
    c0 = floor(loops["jack"].figure.centre_of_mass())
    goal = [c0[0] + 0.05, 0.9, c0[1] + 0.03]
    tl = Timeline([COMMotion(figure="jack", t0=0.0, t1=1.0, mode="global", point=goal)])
    tl.duration = 1.5
    loop, _ = run(tl, scene)
    assert np.allclose(floor(loop.figure.centre_of_mass()), [goal[0], goal[2]], atol=4e-3)


def test_foot_motion_height_10_cm_lifts_the_toes_10_cm_at_the_midpoint(scene):
    tl = Timeline([FootMotion(figure="jack", side="right", t0=0.0, t1=1.0, displacement=[0.0, 0.0, 0.3],
                              height=0.10)])
    tl.duration = 1.2
    loop, toes = run(tl, scene, each=lambda t, lp: lp.figure.site_world(*lp.anatomy.feet["right"].toe)[:3, 3])
    toes = np.array(toes)
    assert toes[15, 1] == pytest.approx(0.10, abs=1e-3)  # u = 1/2
    assert toes[:, 1].max() == pytest.approx(0.10, abs=1e-3)
    assert toes[-1, 1] == pytest.approx(0.0, abs=1e-3)
    assert toes[-1, 2] - toes[0, 2] == pytest.approx(0.3, abs=2e-3)
    assert loop.state.feet["right"].mode == "pivot" and loop.state.feet["right"].heel == "floor"
    # the other foot stayed planted
    left = loop.figure.site_world(*loop.anatomy.feet["left"].ball)[:3, 3]
    assert np.allclose(left, loop.state.feet["left"].target[:3, 3], atol=1e-3)


def test_foot_motion_height_0_slides_on_the_floor(scene):
    tl = Timeline([FootMotion(figure="jack", side="left", t0=0.0, t1=0.5, displacement=[0.1, 0.0, 0.0])])
    _, toes = run(tl, scene, each=lambda t, lp: lp.figure.site_world(*lp.anatomy.feet["left"].toe)[1, 3])
    assert np.ptp(toes) < 1e-3


def test_heel_motion_raises_and_lowers_the_heel(scene):
    tl = Timeline([COMMotion(figure="jack", t0=0.0, t1=0.5, x=0.1),
                   HeelMotion(figure="jack", side="right", t0=0.5, t1=1.0, height=0.05),
                   HeelMotion(figure="jack", side="right", t0=1.5, t1=2.0, height=0.0)])
    tl.duration = 2.2
    def heel(t, lp):
        return lp.figure.site_world(*lp.anatomy.feet["right"].heel)[1, 3]

    loop, ys = run(tl, scene, each=heel)
    base = ys[0]
    assert ys[30] - base == pytest.approx(0.05, abs=3e-3)  # t = 1.0: raised 5 cm
    assert ys[-1] - base == pytest.approx(0.0, abs=2e-3)  # back on the floor
    assert loop.state.feet["right"].heel == "floor"
    assert not [u for u in loop.user_goals if (u.key or "").startswith("motion ")]


def test_pelvis_motion_twists_the_pelvis(scene):
    tl = Timeline([PelvisMotion(figure="jack", t0=0.0, t1=1.0, twist=np.radians(15.0))])
    env, loops = scene
    a = loops["jack"].anatomy

    def yaw(t, lp):
        f = lp.figure
        r = f.site_world(a.pelvis, a.pelvis_site)[:3, :3]
        return yaw_of(r @ (f.site_location(a.pelvis, a.pelvis_site)[:3, :3].T @ a.pelvis_forward))

    loop, yaws = run(tl, scene, each=yaw)
    assert np.degrees(yaws[-1] - yaws[0]) == pytest.approx(15.0, abs=1.0)
    assert loop.state.pelvis_user is True  # the pelvis holds the end orientation (P3 stays off)


def test_torso_motion_bends_without_weight_and_turns_vertical_off(scene):
    tl = Timeline([TorsoMotion(figure="jack", t0=0.0, t1=1.0, flexion=np.radians(30.0))])
    loop, _ = run(tl, scene)
    assert loop.figure.groups["spine"].angles[0] == pytest.approx(np.radians(30.0), abs=1e-6)
    assert loop.state.torso_mode == "bend"
    with pytest.raises(ValueError, match="may not overlap"):
        tl.add(TorsoMotion(figure="jack", t0=0.5, t1=1.5, flexion=0.0))
    tl.add(TorsoMotion(figure="jack", t0=1.0, t1=1.5, flexion=0.0))  # back to back is fine


def test_arm_motion_reaches_a_point_with_the_arm_only(scene):
    env, loops = scene
    fig = loops["jack"].figure
    pelvis0 = fig.site_world("pelvis", "centre")[:3, 3].copy()
    shoulder = fig.site_world(*loops["jack"].anatomy.hands["right"].shoulder)[:3, 3]
    goal = shoulder + np.array([-0.1, -0.1, 0.45])
    tl = Timeline([ArmMotion(figure="jack", side="right", t0=0.0, t1=1.0, target={"point": goal.tolist()})])
    tl.duration = 1.3
    loop, _ = run(tl, scene)
    palm = fig.site_world(*loop.anatomy.hands["right"].palm)[:3, 3]
    assert np.linalg.norm(palm - goal) < 5e-3
    assert np.linalg.norm(fig.site_world("pelvis", "centre")[:3, 3] - pelvis0) < 0.02


def moving_object(env, name, position):
    from jackpy.peabody.model import Figure

    obj = Figure(name)
    obj.location = np.eye(4)
    obj.location[:3, 3] = position
    env.figures[name] = obj
    return obj


def test_relative_arm_target_tracks_a_moving_object(scene):
    env, loops = scene
    fig = loops["jack"].figure
    shoulder = fig.site_world(*loops["jack"].anatomy.hands["right"].shoulder)[:3, 3]
    start = shoulder + np.array([-0.1, -0.15, 0.4])
    obj = moving_object(env, "cart", start)
    tl = Timeline([ArmMotion(figure="jack", side="right", t0=0.0, t1=1.0,
                             target={"point": [0.0, 0.05, 0.0], "relative_to": "cart"})])
    tl.duration = 2.0

    def follow(t, lp):
        obj.location[:3, 3] = start + np.array([0.0, 0.0, 0.08 * t])  # the cart rolls away
        return None

    b = Baker(tl, loops, env, 30.0)
    errs = []
    for i in range(b.n_frames):
        follow(b.time_of(i), None)
        b.seek(i)
        if b.time_of(i) >= 1.0:
            palm = fig.site_world(*loops["jack"].anatomy.hands["right"].palm)[:3, 3]
            errs.append(np.linalg.norm(palm - (obj.location[:3, 3] + [0.0, 0.05, 0.0])))
    assert max(errs) < 0.012  # at the end of the reach and after it, on the moving target
    assert errs[-1] < 0.012


def test_head_motion_looks_at_the_target(scene):
    env, loops = scene
    a = loops["jack"].anatomy
    view = loops["jack"].figure.site_world(*a.view)[:3, 3]
    target = view + np.array([0.8, -0.2, 1.0])
    tl = Timeline([GazeMotion(figure="jack", which="head", t0=0.0, t1=1.0, target={"point": target.tolist()})])
    tl.duration = 1.3
    loop, _ = run(tl, scene)
    f = loop.figure
    fwd = f.world_transforms()[a.view[0]][:3, :3] @ a.view_forward
    d = target - f.site_world(*a.view)[:3, 3]
    angle = np.degrees(np.arccos(fwd @ d / np.linalg.norm(fwd) / np.linalg.norm(d)))
    assert angle < 2.0


def test_parameters_are_checked():
    with pytest.raises(ValueError, match="x must be in"):
        COMMotion(figure="jack", x=1.3)
    with pytest.raises(ValueError, match="t0 <= t1"):
        FootMotion(figure="jack", t0=2.0, t1=1.0)
    with pytest.raises(ValueError, match="side"):
        HeelMotion(figure="jack", side="middle")
    with pytest.raises(ValueError, match="weight_fn"):
        ArmMotion(figure="jack", weight_fn="spiky")
