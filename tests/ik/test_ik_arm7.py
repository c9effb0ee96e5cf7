"""Analytic 7-DOF arm: FK round trips over thousands of postures, limits, the singular erratum."""

import numpy as np

from jackpy import ik
from jackpy.ik.arm7 import Q_OF_THETA, Arm7, _zxz, arm7_figure
from jackpy.peabody.transforms import rotation


def test_round_trip_thousands_of_postures():
    arm = Arm7()
    rng = np.random.default_rng(7)
    for _ in range(2000):
        th = rng.uniform(arm.lower, arm.upper)
        T = arm.fk(th)
        sols = arm.solve(T, arm.swivel(th))
        assert sols.size, th
        assert np.any(np.all(np.abs(sols - th) < 1e-7, axis=1))
        assert np.abs(arm.fk(sols) - T).max() <= 1e-9
        assert np.all((sols >= arm.lower - 1e-12) & (sols <= arm.upper + 1e-12))


def test_all_solutions_at_other_swivels_reproduce_target():
    arm = Arm7()
    rng = np.random.default_rng(8)
    for _ in range(200):
        T = arm.fk(rng.uniform(arm.lower, arm.upper))
        sols = arm.solve(T, np.linspace(-np.pi, np.pi, 12), limits=False)
        assert np.abs(arm.fk(sols) - T).max() <= 1e-9


def test_figure_matches_chain_and_out_of_reach():
    arm = Arm7()
    f = arm7_figure(arm)
    th = np.radians([10, 20, 30, 40, 50, 60, 70])
    q = np.zeros(7)
    q[Q_OF_THETA] = th
    f.q = q
    assert np.allclose(f.site_world("hand", "base"), arm.fk(th), atol=1e-12)
    T = np.eye(4)
    T[:3, 3] = (0, 0, arm.d3 + arm.a4 + 0.01)
    assert arm.solve(T, 0.0).shape == (0, 7)


def test_singular_shoulder_uses_corrected_formula():
    for t2 in (0.0, np.pi):
        R = (rotation("z", 0.7) @ rotation("x", t2) @ rotation("z", 0.0))[:3, :3][None]
        for t1, tt2, t3 in _zxz(R):
            back = rotation("z", t1[0]) @ rotation("x", tt2[0]) @ rotation("z", t3[0])
            assert np.allclose(back[:3, :3], R[0], atol=1e-12)
        printed = np.arctan2(R[0, 1, 0], -R[0, 0, 0])
        wrong = rotation("z", printed) @ rotation("x", t2)
        assert not np.allclose(wrong[:3, :3], R[0], atol=1e-3)


def test_solver_fast_path_on_arm_chain():
    arm = Arm7()
    f = arm7_figure(arm)
    rng = np.random.default_rng(9)
    p = ik.Problem(f)
    goal = p.add(ik.PositionOrientation("hand.base", np.eye(4)))
    assert p.compile().arm is not None
    for _ in range(50):
        q = np.zeros(7)
        q[Q_OF_THETA] = rng.uniform(arm.lower, arm.upper)
        f.q = q
        goal.target = f.site_world("hand", "base")
        f.q = np.zeros(7)
        r = ik.solve(p)
        assert r.achieved and r.analytic
        assert np.abs(f.site_world("hand", "base") - goal.target).max() < 1e-9
        assert np.all((f.q >= f.lower) & (f.q <= f.upper))
