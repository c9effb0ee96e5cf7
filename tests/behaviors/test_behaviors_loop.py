"""The behavior loop on the synthetic human-shaped tree: balance, feet, stepping, root, gaze,
springs, hands (behaviors.md §7 items 3, 20, 21, 27, 28, 30)."""

import numpy as np
import pytest

from jackpy.behaviors import BehaviorLoop, synthetic_anatomy
from jackpy.behaviors import manipulation as m
from jackpy.behaviors.support import floor
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import rotation, translation


@pytest.fixture
def loop() -> BehaviorLoop:
    f = human_like_tree()
    f.location = translation(0.0, 0.99, 0.0)
    lp = BehaviorLoop(f, synthetic_anatomy(f))
    for _ in range(3):
        lp.step()
    return lp


def balls(lp: BehaviorLoop) -> dict[str, np.ndarray]:
    return {s: lp.figure.site_world(*f.ball)[:3, 3] for s, f in lp.anatomy.feet.items()}


def test_com_drag_inside_polygon_keeps_feet_and_balance(loop):
    start = balls(loop)
    b0 = loop.state.balance_point.copy()
    for i in range(10):
        m.move_com(loop, np.array([b0[0] + 0.004 * i, 0.0, b0[1] + 0.005 * i]))
        r = loop.step()
        assert not r.notes or all("step" not in n for n in r.notes)
    c = floor(loop.figure.centre_of_mass())
    assert np.linalg.norm(c - loop.state.balance_point) < 2e-3
    for s, p in balls(loop).items():
        assert np.linalg.norm(p - start[s]) < 1e-3
    m.end_drag(loop)
    x, z = loop.state.balance
    loop.step()
    assert loop.state.balance == pytest.approx((x, z))


def test_forward_com_drag_steps_and_stance_foot_stays(loop):
    b0 = loop.state.balance_point.copy()
    start = balls(loop)
    stepped = None
    for i in range(40):
        m.move_com(loop, np.array([b0[0], 0.0, b0[1] + 0.01 * (i + 1)]))
        r = loop.step()
        if any("step:" in n for n in r.notes) and stepped is None:
            stepped = "left" if "left" in r.notes[-1] else "right"
            stance = {"left": "right", "right": "left"}[stepped]
        if any("landed" in n for n in r.notes):
            break
    assert stepped is not None and loop.state.steps_taken >= 1
    assert np.linalg.norm(balls(loop)[stance] - start[stance]) < 1e-3
    assert balls(loop)[stepped][2] > start[stepped][2] + 0.1


def test_root_follows_weight(loop):
    m.set_balance(loop, 0.7)
    for _ in range(3):
        loop.step()
    assert loop.state.root == "right"
    m.set_balance(loop, 0.45)
    loop.step()
    assert loop.state.root == "right"
    m.set_balance(loop, 0.3)
    for _ in range(3):
        loop.step()
    assert loop.state.root == "left"
    w = loop.figure.world_transforms()
    loop.set_root("right")
    for n, t in loop.figure.world_transforms().items():
        assert np.allclose(t, w[n], atol=1e-9)


def test_look_at_with_eyes_and_head(loop):
    a = loop.anatomy
    view = loop.figure.site_world(*a.view)[:3, 3]
    for target in (view + (0.3, 0.1, 0.9), view + (-0.6, -0.2, 0.7)):
        m.move_eyes(loop, target)
        for _ in range(15):
            loop.step()
        for seg, site in a.eyes.values():
            w = loop.figure.site_world(seg, site)
            ray = w[:3, :3] @ (loop.figure.site_location(seg, site)[:3, :3].T @ a.eye_forward)
            d = target - w[:3, 3]
            miss = np.linalg.norm(d - (d @ ray) * ray) / np.linalg.norm(d)
            assert miss < 0.01  # within 1 cm per metre


def test_knee_springs_unlock_straight_knees(loop):
    q = {j: loop.figure.joint(j).displacement[0] for j in ("knee_left", "knee_right")}
    for _ in range(5):
        loop.step()
    for j in q:
        assert loop.figure.joint(j).displacement[0] >= np.radians(9.0)


def test_hand_pass_leaves_body_goals(loop):
    for _ in range(3):
        loop.step()
    before = balls(loop), loop.figure.site_world("pelvis", "base").copy()
    m.move_hand(loop, "left", position=loop.figure.site_world("palm_left", "centre")[:3, 3] + (0.0, 0.6, 1.2))
    loop.step()
    after = balls(loop), loop.figure.site_world("pelvis", "base")
    for s in before[0]:
        assert np.linalg.norm(after[0][s] - before[0][s]) < 1e-3
    assert np.allclose(after[1][:3, :3], before[1][:3, :3], atol=1e-3)


def test_random_drags_keep_balance_limits_and_feet(loop):
    rng = np.random.default_rng(7)
    lp = loop
    fig = lp.figure
    lo, hi = fig.lower, fig.upper
    pel0 = fig.site_world("pelvis", "base")[:3, :3].copy()
    palms = {s: fig.site_world(*h.palm)[:3, 3].copy() for s, h in lp.anatomy.hands.items()}
    prev = balls(lp)
    for frame in range(200):
        kind = frame // 10 % 3
        if kind == 0:
            s = "left" if rng.random() < 0.5 else "right"
            m.move_hand(lp, s, position=palms[s] + rng.uniform((-0.2, 0.0, 0.0), (0.2, 0.5, 0.4)))
        elif kind == 1:
            ang = rng.uniform(-0.25, 0.25, 3)
            m.move_pelvis(lp, rotation=rotation("y", ang[0])[:3, :3] @ rotation("x", ang[1])[:3, :3] @ pel0)
        else:
            m.bend_torso(lp, *rng.uniform((-0.1, -0.1, -0.1), (0.4, 0.1, 0.1)))
        r = lp.step()
        q = fig.q
        assert np.all(q >= lo - 1e-9) and np.all(q <= hi + 1e-9)
        stepping = lp.behavior("stepping").step is not None or any("step" in n for n in r.notes)
        now = balls(lp)
        if not stepping:
            bf = lp.balance_frame_for({s: f.target for s, f in lp.state.feet.items()})
            assert bf.margin(floor(fig.centre_of_mass())) < 5e-3
            for s in now:
                assert np.linalg.norm(now[s] - prev[s]) < 1e-3
        prev = now
        if frame % 10 == 9:
            m.end_drag(lp)
