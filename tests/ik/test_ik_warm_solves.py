"""Warm solves: the per-solve fixed cost cut without changing results (rows shortcut of the bounded
step, the figure's q setter, one compiled FK specialisation, the cached rows over z)."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy import ik
from jackpy.errors import FigureError
from jackpy.ik.bounded_step import _box_step_compiled, bounded_step
from jackpy.peabody import kinematics_jit
from jackpy.peabody.synthetic import human_like_tree


def _model(J, lam, c, d):
    return float(c @ d + 0.5 * (np.sum((J @ d) ** 2) + lam * d @ d))


@pytest.mark.skipif(_box_step_compiled is None, reason="numba not installed")
def test_rows_shortcut_agrees_with_numpy_reference() -> None:
    rng = np.random.default_rng(11)
    shortcut = 0
    for k in range(80):
        n, m = int(rng.integers(4, 80)), int(rng.integers(2, 25))
        J, F, lam = rng.normal(size=(m, n)), rng.normal(size=m) * 3, 10.0 ** rng.uniform(-3, 0)
        lo, hi = -rng.uniform(0, 0.3, n), rng.uniform(0, 0.3, n)
        A = rng.normal(size=(4, n))
        r = rng.uniform(0, 0.2, 4) * (50.0 if k % 2 else 1.0)  # loose rows half the time
        c = J.T @ F
        a = bounded_step(J, lam, c, lo, hi, A, r)
        b = bounded_step(J, lam, c, lo, hi, A, r, compiled=False)
        assert np.all(A @ a[0] <= r + 1e-12) and np.all(a[0] >= lo) and np.all(a[0] <= hi)
        assert abs(_model(J, lam, c, a[0]) - _model(J, lam, c, b[0])) <= 1e-9 * (1 + abs(_model(J, lam, c, b[0])))
        shortcut += bool(np.all(A @ b[0] < r - 1e-9))
    assert shortcut >= 20  # the shortcut was actually exercised


def test_q_setter_copies_once_and_keeps_joints_apart() -> None:
    fig = human_like_tree()
    q = np.linspace(-0.1, 0.1, fig.ndof)
    fig.q = q
    q[:] = 0.0  # the caller's array is not aliased
    assert np.allclose(fig.q, np.linspace(-0.1, 0.1, fig.ndof))
    first, second = list(fig.joints.values())[:2]
    before = second.displacement.copy()
    first.displacement[:] = 7.0  # writing one joint in place leaves the others alone
    assert np.array_equal(second.displacement, before)
    assert np.all(fig.q[:first.ndof] == 7.0)
    with pytest.raises(FigureError, match="DOFs"):
        fig.q = np.zeros(fig.ndof + 1)


def test_warm_drag_keeps_one_compiled_fk_and_same_postures() -> None:
    fig = human_like_tree()
    p = ik.Problem(fig)
    goal = p.add(ik.Position("palm_left.tip", fig.site_world("palm_left", "tip")[:3, 3] + [0.05, 0.0, 0.0]))
    fig.location = np.asfortranarray(fig.location)  # a caller's non-contiguous frame
    ik.solve(p)
    signatures = len(kinematics_jit.forward_kernel.signatures) if kinematics_jit.AVAILABLE else 0
    compiled = p.compile()
    for _ in range(5):
        goal.target = goal.target + [0.0, 0.005, 0.0]
        r = ik.solve(p)
        assert p.compile() is compiled and np.array_equal(fig.q, r.q)
    if kinematics_jit.AVAILABLE:
        assert len(kinematics_jit.forward_kernel.signatures) == signatures
