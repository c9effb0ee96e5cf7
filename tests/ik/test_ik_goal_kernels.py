"""The compiled goal loops (``ik/goals/kernels.py``) equal the numpy reference (``Context.compiled = False``)."""

import numpy as np
import pytest

from jackpy import ik
from jackpy.ik.goals.base import Context
from jackpy.ik.goals.kernels import frame_goal
from jackpy.peabody.synthetic import human_like_tree

pytestmark = pytest.mark.skipif(frame_goal is None, reason="numba not installed")


def _goals(fig, rng):
    frame = np.eye(4)
    frame[:3, 3] = rng.normal(size=3)
    return [ik.PositionOrientation("palm_left.tip", frame),
            ik.PositionOrientation("palm_right.tip", frame, position_weight=1.0, cx=2.0),
            ik.PositionOrientation("palm_right.tip", frame, cy=0.0, chain="spine1"),
            ik.PositionOrientation("palm_left.tip", frame, cx=0.0, cy=3.0),
            ik.PositionOrientation("palm_left.tip", frame, cx=0.0, cy=0.0),
            ik.Aim("head.tip", rng.normal(size=3), axis=(0.0, 1.0, 0.0), c=1.5),
            ik.CentreOfMass(rng.normal(size=3))]


def _pair(fig, kin, q, cols):
    fk = kin.forward(q, fig.location)
    fast, slow = Context(kin, fk, cols), Context(kin, fk, cols)
    slow.compiled = False
    return fast, slow


def test_compiled_goals_match_numpy_reference() -> None:
    fig = human_like_tree()
    kin = fig.kinematics()
    rng = np.random.default_rng(3)
    for trial in range(8):
        q = rng.uniform(fig.lower, fig.upper)
        cols = np.sort(rng.choice(kin.ndof, size=kin.ndof // 2, replace=False)) if trial % 2 else np.arange(kin.ndof)
        fast, slow = _pair(fig, kin, q, cols)
        assert np.allclose(fast._ang, slow._ang, rtol=0, atol=1e-14)
        assert np.allclose(fast._mom, slow._mom, rtol=0, atol=1e-14)
        c_fast, j_fast = fast.com()
        c_slow, j_slow = slow.com()
        assert np.allclose(c_fast, c_slow, rtol=0, atol=1e-13) and np.allclose(j_fast, j_slow, rtol=0, atol=1e-13)
        for goal in _goals(fig, rng):
            goal.bind(fig)
            a, b = goal.evaluate(fast), goal.evaluate(slow)
            assert a.f.shape == b.f.shape and a.J.shape == b.J.shape
            assert np.allclose(a.f, b.f, rtol=0, atol=1e-13), goal.name
            assert np.allclose(a.J, b.J, rtol=0, atol=1e-13), goal.name
            assert a.metres == pytest.approx(b.metres, abs=1e-12)
            assert a.degrees == pytest.approx(b.degrees, abs=1e-9)


def test_compiled_aim_at_its_own_site_is_zero_not_nan() -> None:
    fig = human_like_tree()
    kin = fig.kinematics()
    fast, slow = _pair(fig, kin, fig.q, np.arange(kin.ndof))
    goal = ik.Aim("head.tip", fig.site_world("head", "tip")[:3, 3])
    goal.bind(fig)
    a, b = goal.evaluate(fast), goal.evaluate(slow)
    assert np.all(a.f == 0) and np.all(a.J == 0) and np.all(b.f == 0) and a.degrees == b.degrees == 0.0


def test_compiled_and_reference_solves_reach_the_same_posture() -> None:
    fig = human_like_tree()
    rng = np.random.default_rng(8)
    q0 = fig.q
    target = fig.site_world("palm_left", "tip")
    target[:3, 3] += rng.normal(scale=0.1, size=3)
    problem = ik.Problem(fig)
    problem.add(ik.PositionOrientation("palm_left.tip", target, chain="spine1"))
    problem.add(ik.Aim("head.tip", (0.3, 1.7, 1.0), chain="spine1"))
    problem.add(ik.CentreOfMass(np.zeros(3)))
    fast = ik.solve(problem, apply=False)
    saved = Context.compiled
    try:
        Context.compiled = False
        fig.q = q0
        problem.invalidate()
        slow = ik.solve(problem, apply=False)
    finally:
        Context.compiled = saved
    assert fast.status == slow.status and fast.iterations == slow.iterations
    assert np.allclose(fast.q, slow.q, rtol=0, atol=1e-9)
