"""Solver behaviour: feasibility, active set, unreachable targets, OR/half-space/plane, priorities."""

import numpy as np

from jackpy import ik
from jackpy.peabody.groups import JointGroup, LinearDriver
from jackpy.peabody.model import Dof, Figure, Joint, Segment
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import translation


def planar_chain(n: int = 4, limit: float = 1.5, length: float = 0.3) -> Figure:
    f = Figure("chain")
    for i in range(n + 1):
        s = Segment(f"s{i}", mass=1.0, com=np.array([length / 2, 0, 0]))
        s.add_site("base")
        s.add_site("tip", translation(length, 0, 0))
        f.add_segment(s)
    for i in range(n):
        f.add_joint(Joint(f"j{i}", f"s{i}", "tip", f"s{i + 1}", "base", [Dof("R", (0, 0, 1), -limit, limit)]))
    f.root = ("s0", "base")
    return f


def test_iterates_respect_limits_on_random_problems():
    rng = np.random.default_rng(0)
    f = planar_chain(5, limit=0.8)
    lo, hi = f.lower, f.upper
    seen = []
    orig = f.kinematics().forward

    def spy(q, loc):
        seen.append(q.copy())
        return orig(q, loc)

    f.kinematics().forward = spy
    for _ in range(300):
        f.q = rng.uniform(lo, hi)
        p = ik.Problem(f)
        p.add(ik.Position("s5.tip", rng.uniform(-2, 2, 3) * (1, 1, 0)))
        r = ik.solve(p, max_iterations=30)
        assert np.all(np.isfinite(r.q))
    qs = np.array(seen)
    assert np.all(qs >= lo - 1e-12) and np.all(qs <= hi + 1e-12)


def test_group_rows_never_violated():
    rng = np.random.default_rng(1)
    f = planar_chain(4, limit=1.5)
    f.add_group(JointGroup("pair", ["j1", "j2"], ["a", "b"], LinearDriver(np.eye(2)), [-1.5, -1.5],
                           [1.5, 1.5], A=[[1.0, 1.0]], b=[0.6]))
    for _ in range(100):
        p = ik.Problem(f)
        p.add(ik.Position("s4.tip", rng.uniform(-1.3, 1.3, 3) * (1, 1, 0)))
        ik.solve(p, max_iterations=40)
        ang = f.groups["pair"].angles
        assert ang.sum() <= 0.6 + 1e-9
        assert np.all(np.abs(f.q) <= 1.5 + 1e-12)


def test_reachable_and_unreachable_targets():
    f = planar_chain(3, limit=2.5)
    p = ik.Problem(f)
    goal = p.add(ik.Position("s3.tip", (0.5, 0.4, 0.0)))
    r = ik.solve(p)
    assert r.status == ik.ACHIEVED and r.goals[0].metres < 1e-4
    goal.target = np.array([3.0, 0.0, 0.0])  # beyond reach: 4 x 0.3 m
    r = ik.solve(p)
    assert r.status == ik.UNREACHABLE and r.converged
    tip = f.site_world("s3", "tip")[:3, 3]
    assert np.allclose(tip, (1.2, 0, 0), atol=1e-4)  # fully extended towards it
    assert abs(r.goals[0].metres - 1.8) < 1e-4


def test_active_set_holds_limit_and_releases_it():
    f = planar_chain(2, limit=0.3)
    p = ik.Problem(f)
    goal = p.add(ik.Position("s2.tip", (0.0, 0.9, 0.0)))
    ik.solve(p)
    assert np.isclose(f.q[0], 0.3) and np.isclose(f.q[1], 0.3)  # both pinned at the upper limit
    goal.target = np.array([0.895, -0.03, 0.0])
    r = ik.solve(p)
    assert r.achieved and np.all(f.q < 0.3)


def test_weighted_conflict_gives_weighted_mean():
    f = planar_chain(3, limit=2.5)
    p = ik.Problem(f)
    a, b = np.array([0.5, 0.3, 0]), np.array([0.4, -0.2, 0])
    p.add(ik.Position("s3.tip", a, weight=1.0))
    p.add(ik.Position("s3.tip", b, weight=3.0))
    ik.solve(p)
    assert np.allclose(f.site_world("s3", "tip")[:3, 3], (a + 3 * b) / 4, atol=1e-5)


def test_or_goal_takes_nearest_alternative_outside_box():
    f = planar_chain(3, limit=2.5)
    f.q = np.array([0.2, 0.1, 0.1])
    tip = f.site_world("s3", "tip")[:3, 3]
    lo, hi = tip - (0.05, 0.2, 0.2), tip + (0.1, 0.2, 0.2)  # the tip is inside; nearest face: +x
    faces = [ik.HalfSpace("s3.tip", hi, (1, 0, 0)), ik.HalfSpace("s3.tip", lo, (-1, 0, 0)),
             ik.HalfSpace("s3.tip", hi, (0, 1, 0)), ik.HalfSpace("s3.tip", lo, (0, -1, 0))]
    p = ik.Problem(f)
    outside = p.add(ik.AnyOf(faces))
    r = ik.solve(p)
    new = f.site_world("s3", "tip")[:3, 3]
    assert r.achieved and outside.selected == 1
    assert new[0] <= lo[0] + 1e-4


def test_half_space_inequality_and_plane_equality():
    f = planar_chain(3, limit=2.5)
    f.q = np.array([0.3, 0.2, 0.1])
    before = f.q.copy()
    p = ik.Problem(f)
    p.add(ik.HalfSpace("s3.tip", (0.0, -5.0, 0.0), (0, 1, 0)))  # already satisfied: no motion
    r = ik.solve(p)
    assert r.achieved and r.iterations == 0 and np.array_equal(f.q, before)
    p = ik.Problem(f)
    p.add(ik.HalfSpace("s3.tip", (0.0, 0.5, 0.0), (0, 1, 0)))
    p.add(ik.Plane("s3.tip", (0.3, 0.0, 0.0), (1, 0, 0)))
    r = ik.solve(p)
    tip = f.site_world("s3", "tip")[:3, 3]
    assert r.achieved and tip[1] >= 0.5 - 1e-4 and abs(tip[0] - 0.3) < 1e-4


def test_stiffness_reduces_share_and_zero_freezes():
    moves = []
    for s in (1.0, 0.5, 0.1, 0.0):
        f = planar_chain(4, limit=2.5)
        f.q = np.full(4, 0.2)
        p = ik.Problem(f)
        p.set_scale("j1", s)
        p.add(ik.Position("s4.tip", (0.9, 0.6, 0.0)))
        assert ik.solve(p).achieved
        moves.append(abs(f.q[1] - 0.2))
    assert moves[0] > moves[1] > moves[2] > moves[3] == 0.0


def test_root_and_locked_joints_untouched():
    f = human_like_tree()
    loc = f.location.copy()
    p = ik.Problem(f)
    p.lock("elbow_left")
    p.add(ik.Position("palm_left.tip", (0.3, 1.2, 0.3), chain="spine10"))
    ik.solve(p)
    assert np.array_equal(f.location, loc)
    assert np.all(f.joint("elbow_left").displacement == 0.0)


def _standing() -> Figure:
    f = human_like_tree()
    f.reroot("foot_left", "tip")
    return f


def test_priority_feet_stay_planted_when_hand_unreachable():
    f = _standing()
    foot = f.site_world("foot_right", "tip")
    p = ik.Problem(f)
    p.add(ik.PositionOrientation("foot_right.tip", foot, chain="ankle_left"), level=0)
    p.add(ik.Position("palm_right.tip", (-3.0, 1.5, 2.0), chain="ankle_left"), level=1)
    r = ik.solve(p, max_iterations=200)
    assert r.goals[0].metres < 1e-5 and r.goals[0].degrees < 1e-3
    assert r.status == ik.UNREACHABLE or not r.converged
    reach = np.linalg.norm(f.site_world("palm_right", "tip")[:3, 3] - (-3.0, 1.5, 2.0))
    # the same goals on one level: the hand drags the right foot away
    g = _standing()
    q = ik.Problem(g)
    q.add(ik.PositionOrientation("foot_right.tip", foot, chain="ankle_left"))
    q.add(ik.Position("palm_right.tip", (-3.0, 1.5, 2.0), chain="ankle_left"))
    r1 = ik.solve(q, max_iterations=200)
    assert r1.goals[0].metres > 100 * r.goals[0].metres + 1e-5
    assert reach < 3.5


def test_priority_lower_level_still_achieved_when_possible():
    f = _standing()
    foot = f.site_world("foot_right", "tip")
    hand = f.site_world("palm_right", "tip")[:3, 3] + (0.05, 0.1, 0.1)
    p = ik.Problem(f)
    p.add(ik.PositionOrientation("foot_right.tip", foot, chain="ankle_left"), level=0)
    p.add(ik.Position("palm_right.tip", hand, chain="ankle_left"), level=1)
    r = ik.solve(p, max_iterations=200)
    assert r.achieved, r
