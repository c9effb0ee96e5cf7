"""The timeline: step order, overlap blending by weight, timed behaviors reverting, key tracks."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.motion.bake import Baker
from jackpy.motion.keyframes import KeyTrack
from jackpy.motion.kinds.com import COMMotion
from jackpy.motion.kinds.foot import FootMotion
from jackpy.motion.kinds.pelvis import PelvisMotion
from jackpy.motion.kinds.torso import TorsoMotion
from jackpy.motion.timed import TimedBehavior
from jackpy.motion.timeline import Timeline
from jackpy.peabody.transforms import rotation_matrix, rotation_angle_between

UP = np.array([0.0, 1.0, 0.0])


def test_overlapping_motions_on_one_part_blend_by_their_weights(scene):
    env, loops = scene
    loop = loops["jack"]
    tl = Timeline([COMMotion(figure="jack", t0=0.0, t1=1.0, x=0.2, weight=1.0),
                   COMMotion(figure="jack", t0=0.0, t1=1.0, x=0.8, weight=3.0)])
    tl.apply(0.0, loops, env)  # pre-actions: both start at x = 0.5
    tl.apply(1.0, loops, env)  # both at their ends, weights 1 and 3
    assert loop.state.balance[0] == pytest.approx((0.2 * 1 + 0.8 * 3) / 4)


def test_blending_follows_the_weight_functions(scene):
    env, loops = scene
    loop = loops["jack"]
    tl = Timeline([COMMotion(figure="jack", t0=0.0, t1=1.0, x=0.2, weight_fn="decrease", velocity_fn="ease"),
                   COMMotion(figure="jack", t0=0.0, t1=1.0, x=0.8, weight_fn="increase", velocity_fn="ease")])
    tl.apply(0.0, loops, env)
    got = []
    for t in (0.25, 0.5, 0.75):
        tl.apply(t, loops, env)
        s = 0.5 * (1 - np.cos(np.pi * t))
        x0 = tl.motions[0].run["start"][0]
        a, b = x0 + s * (0.2 - x0), x0 + s * (0.8 - x0)
        got.append((loop.state.balance[0], (1 - t) * a + t * b))
    for have, want in got:
        assert have == pytest.approx(want)
    # the earlier one decays: at the end only the second counts
    tl.apply(1.0, loops, env)
    assert loop.state.balance[0] == pytest.approx(0.8)


def test_overlapping_pelvis_motions_blend_rotations(scene):
    env, loops = scene
    loop = loops["jack"]
    tl = Timeline([PelvisMotion(figure="jack", t0=0.0, t1=1.0, twist=np.radians(20)),
                   PelvisMotion(figure="jack", t0=0.0, t1=1.0, twist=np.radians(-10))])
    tl.apply(0.0, loops, env)
    start = np.array(tl.motions[0].run["start"])
    tl.apply(1.0, loops, env)
    want = rotation_matrix(UP, np.radians(5))[:3, :3] @ start
    assert rotation_angle_between(loop.state.pelvis_goal, want) < 1e-6


def test_order_is_motion_then_post_then_pre(scene):
    """A foot motion that ends when the next begins: the first plants the foot (post) before the
    second starts from the pose the first reached (pre), all within one step."""
    env, loops = scene
    loop = loops["jack"]
    a = FootMotion(figure="jack", side="right", t0=0.0, t1=0.5, displacement=[0, 0, 0.1])
    b = FootMotion(figure="jack", side="right", t0=0.6, t1=1.0, displacement=[0, 0, 0.1])
    tl = Timeline([a, b])
    baker = Baker(tl, loops, env, 10)
    baker.seek(5)  # t = 0.5: a's last step
    assert a.run["phase"] == "active" and b.run == {}
    baker.seek(6)  # t = 0.6: a's post, then b's pre
    assert a.run["phase"] == "done" and b.run["phase"] == "active"
    assert np.allclose(np.array(b.run["start"])[:3, 3], np.array(a.run["end"])[:3, 3], atol=1e-3)


def test_start_goal_is_the_pose_at_run_time_not_at_authoring(scene):
    env, loops = scene
    loop = loops["jack"]
    tl = Timeline([FootMotion(figure="jack", side="left", t0=0.0, t1=0.3, displacement=[0.1, 0, 0]),
                   FootMotion(figure="jack", side="left", t0=0.4, t1=0.7, displacement=[0, 0, 0.1])])
    tl.duration = 0.9
    Baker(tl, loops, env, 10).bake()
    end = np.array(tl.motions[1].run["end"])[:3, 3]
    start0 = np.array(tl.motions[0].run["start"])[:3, 3]
    assert np.allclose(end - start0, [0.1, 0.0, 0.1], atol=2e-3)


def test_timed_torso_control_reverts_at_the_end(scene):
    """behaviors.md §7 item 17: keep vertical, a timed hold over [1, 2] s, keep vertical again after."""
    env, loops = scene
    loop = loops["jack"]
    tl = Timeline(timed=[TimedBehavior("jack", "torso", "hold", 1.0, 2.0)])
    modes = {}
    for t in (0.5, 1.0, 1.5, 2.0, 2.5):
        tl.apply(t, loops, env)
        modes[t] = loop.state.torso_mode
    assert modes == {0.5: "vertical", 1.0: "hold", 1.5: "hold", 2.0: "vertical", 2.5: "vertical"}


def test_after_a_torso_motion_vertical_torso_is_off(scene):
    env, loops = scene
    tl = Timeline([TorsoMotion(figure="jack", t0=0.0, t1=0.5, flexion=0.2)],
                  [TimedBehavior("jack", "torso", "vertical", 1.0, 1.5)])
    tl.duration = 2.0
    b = Baker(tl, loops, env, 10)
    b.seek(8)
    assert loops["jack"].state.torso_mode == "bend"
    b.seek(12)
    assert loops["jack"].state.torso_mode == "vertical"
    b.seek(20)
    assert loops["jack"].state.torso_mode == "bend"  # reverted to what it was at t0


@pytest.mark.parametrize("control,value,read", [
    ("support", "left", lambda lp: lp.state.root),
    ("balance", False, lambda lp: lp.behavior("balance").enabled),
    ("foot.right", {"mode": "hold", "heel": "free"}, lambda lp: (lp.state.feet["right"].mode, lp.state.feet["right"].heel)),
    ("head", [0.0, 1.6, 2.0], lambda lp: None if lp.state.head_target is None else lp.state.head_target.tolist()),
    ("hand.right", "hold", lambda lp: lp.state.hands["right"].goal is not None),
    ("behavior.pelvis.follow_feet", False, lambda lp: lp.behavior("pelvis").params.follow_feet),
])
def test_timed_behaviors_set_then_revert(scene, control, value, read):
    env, loops = scene
    loop = loops["jack"]
    before = read(loop)
    tl = Timeline(timed=[TimedBehavior("jack", control, value, 0.5, 1.0)])
    tl.apply(0.0, loops, env)
    assert read(loop) == before
    tl.apply(0.5, loops, env)
    during = read(loop)
    assert during != before
    tl.apply(1.0, loops, env)
    assert read(loop) == before


def test_timed_attachment_carries_an_object_then_leaves_it(scene):
    from jackpy.peabody.model import Figure

    env, loops = scene
    loop = loops["jack"]
    box = Figure("box")
    box.location = loop.figure.site_world(*loop.anatomy.hands["right"].palm).copy()
    env.figures["box"] = box
    shoulder = loop.figure.site_world(*loop.anatomy.hands["right"].shoulder)[:3, 3]
    from jackpy.motion.kinds.arm import ArmMotion

    tl = Timeline([ArmMotion(figure="jack", side="right", t0=0.2, t1=1.0,
                             target={"point": (shoulder + [-0.1, -0.1, 0.45]).tolist()})],
                  [TimedBehavior("jack", "attach.right", "box", 0.1, 1.2)])
    tl.duration = 1.5
    b = Baker(tl, loops, env, 10)
    b.seek(11)
    palm = loop.figure.site_world(*loop.anatomy.hands["right"].palm)
    assert np.allclose(box.location[:3, 3], palm[:3, 3], atol=1e-2)  # carried (it moved ~0.4 m)
    b.seek(15)
    assert not loop.state.hands["right"].attached  # released at 1.2 s


def test_key_tracks_interpolate_goals(scene):
    env, loops = scene
    loop = loops["jack"]
    p0 = np.eye(4)
    p0[:3, 3] = [0.0, 1.0, 0.3]
    p1 = np.eye(4)
    p1[:3, :3] = rotation_matrix(UP, np.radians(40.0))[:3, :3]
    p1[:3, 3] = [0.2, 1.2, 0.4]
    tr = KeyTrack("jack", "hand.right", [(0.0, p0), (1.0, p1)])
    mid = tr.value(0.5)
    assert np.allclose(mid[:3, 3], [0.1, 1.1, 0.35])
    assert rotation_angle_between(mid[:3, :3], rotation_matrix(UP, np.radians(20.0))[:3, :3]) < 1e-9
    # cubic passes through every key and differs from linear between uneven keys
    pts = KeyTrack("jack", "head", [(0.0, [0, 1.6, 1]), (1.0, [1, 1.6, 1]), (2.0, [1, 1.6, 3])], "cubic")
    assert np.allclose(pts.value(1.0), [1, 1.6, 1]) and np.allclose(pts.value(2.0), [1, 1.6, 3])
    lin = KeyTrack("jack", "head", pts.keys, "linear")
    assert not np.allclose(pts.value(0.5), lin.value(0.5))
    # apply writes the goal only within the track's span
    tl = Timeline(tracks=[tr])
    tl.apply(0.5, loops, env)
    assert np.allclose(loop.state.hands["right"].goal, mid)


def test_joint_angle_keys_set_one_joint_clamped(scene):
    env, loops = scene
    loop = loops["jack"]
    j = loop.figure.joint("left_eye")
    tr = KeyTrack("jack", "joint:left_eye", [(0.0, np.zeros(j.ndof)), (1.0, np.full(j.ndof, 10.0))])
    Timeline(tracks=[tr]).apply(1.0, loops, env)
    assert np.allclose(j.displacement, j.upper)


def test_set_key_captures_the_current_target(scene):
    env, loops = scene
    loop = loops["jack"]
    tl = Timeline()
    tr = tl.set_key(loop, "foot.left", 0.5)
    assert np.allclose(tr.keys[0][1], loop.figure.site_world(*loop.anatomy.feet["left"].ball))
    tl.set_key(loop, "com", 1.0)
    assert [k.part for k in tl.tracks] == ["foot.left", "com"]
    assert tl.duration == 1.0
