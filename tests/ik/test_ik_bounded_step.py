"""The bounded Gauss-Newton step: its QP against scipy, many limits per step, time box, bounded
restoration, analytic shoulder derivatives."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import lsq_linear, minimize

from jackpy import ik
from jackpy.body.shoulder import SHOULDER_LOWER, SHOULDER_UPPER, ShoulderDriver
from jackpy.ik.bounded_step import bounded_step
from jackpy.ik.priorities import RESTORE_EVALUATIONS
from jackpy.peabody.model import Dof, Figure, Joint, Segment
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import translation


def _model(J, lam, c, d):
    return float(c @ d + 0.5 * (np.sum((J @ d) ** 2) + lam * d @ d))


@pytest.mark.parametrize("seed", range(4))
def test_box_qp_matches_bounded_least_squares(seed: int) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(25):
        n, m = int(rng.integers(3, 91)), int(rng.integers(2, 25))
        J, F, lam = rng.normal(size=(m, n)), rng.normal(size=m) * 3, 10.0 ** rng.uniform(-3, 0)
        lo, hi = -rng.uniform(0, 0.3, n), rng.uniform(0, 0.3, n)
        lo[rng.random(n) < 0.2] = 0.0  # some variables start at a bound
        c = J.T @ F
        d, held, _ = bounded_step(J, lam, c, lo, hi)
        assert np.all(d >= lo) and np.all(d <= hi)
        ref = lsq_linear(np.vstack([J, np.sqrt(lam) * np.eye(n)]), np.concatenate([-F, np.zeros(n)]),
                         bounds=(lo, hi), method="bvls", tol=1e-14)
        assert _model(J, lam, c, d) <= _model(J, lam, c, ref.x) + 1e-10 * (1 + abs(_model(J, lam, c, ref.x)))


def test_qp_with_rows_matches_slsqp_and_stays_feasible() -> None:
    rng = np.random.default_rng(7)
    for _ in range(60):
        n, m = int(rng.integers(4, 30)), int(rng.integers(2, 10))
        J, F, lam = rng.normal(size=(m, n)), rng.normal(size=m) * 3, 1e-3
        lo, hi = -rng.uniform(0, 0.5, n), rng.uniform(0, 0.5, n)
        A, r = rng.normal(size=(4, n)), rng.uniform(0, 0.2, 4)
        r[0] = 0.0  # one row active at the start
        c = J.T @ F
        d, _, _ = bounded_step(J, lam, c, lo, hi, A, r)
        assert np.all(A @ d <= r + 1e-12) and np.all(d >= lo) and np.all(d <= hi)
        H = J.T @ J + lam * np.eye(n)
        ref = minimize(lambda x: (c @ x + 0.5 * x @ H @ x, c + H @ x), np.zeros(n), jac=True,
                       bounds=list(zip(lo, hi)), method="SLSQP", options={"ftol": 1e-15, "maxiter": 1000},
                       constraints=[{"type": "ineq", "fun": lambda x: r - A @ x, "jac": lambda x: -A}])
        if ref.success and np.all(A @ ref.x <= r + 1e-9):
            assert _model(J, lam, c, d) <= _model(J, lam, c, ref.x) + 1e-8


def _chain(n: int, limit: float) -> Figure:
    f = Figure("chain")
    for i in range(n + 1):
        s = f.add_segment(Segment(f"s{i}", mass=1.0, com=np.array([0.05, 0, 0])))
        s.add_site("base")
        s.add_site("tip", translation(0.1, 0, 0))
    for i in range(n):
        f.add_joint(Joint(f"j{i}", f"s{i}", "tip", f"s{i + 1}", "base", [Dof("R", (0, 0, 1), -limit, limit)]))
    f.root = ("s0", "base")
    return f


def test_one_step_settles_many_limits() -> None:
    """A target that puts all 12 joints at their limit: the book's step adds one limit per iteration,
    the bounded step binds them together."""
    results = {}
    for step in ("bounded", "bfgs"):
        f = _chain(12, 0.2)
        f.q = np.full(12, 0.3)  # a curl tighter than the limits allow: the nearest is every joint at +0.2
        target = f.site_world("s12", "tip")[:3, 3]
        f.q = np.zeros(12)
        p = ik.Problem(f)
        p.add(ik.Position("s12.tip", target))
        results[step] = ik.solve(p, step=step, max_iterations=200)
        assert np.allclose(f.q, 0.2, atol=1e-6), step
    assert results["bounded"].iterations <= 4 < 12 <= results["bfgs"].iterations


def test_bounded_and_bfgs_agree_on_reachable_problems() -> None:
    rng = np.random.default_rng(3)
    f = human_like_tree()
    q0 = f.q
    for _ in range(10):
        f.q = rng.uniform(f.lower, f.upper) * 0.4
        t = f.site_world("palm_left", "tip")
        f.q = q0
        p = ik.Problem(f)
        p.add(ik.PositionOrientation("palm_left.tip", t, chain="spine1"))
        r = ik.solve(p)
        assert r.achieved and np.all(f.q >= f.lower) and np.all(f.q <= f.upper)


def test_time_budget_returns_best_feasible_iterate_and_says_so() -> None:
    f = human_like_tree()
    f.reroot("foot_left", "tip")
    p = ik.Problem(f)
    p.add(ik.PositionOrientation("foot_right.tip", f.site_world("foot_right", "tip"), chain="ankle_left"))
    p.add(ik.Position("palm_right.tip", (-3.0, 1.5, 2.0), chain="ankle_left"), level=1)
    q0 = f.q
    r = ik.solve(p, time_budget_s=0.0)
    assert r.status == ik.TIME_LIMIT and not r.converged and r.evaluations == 1
    assert np.array_equal(f.q, q0)  # nothing better was found in no time: the start stands
    r = ik.solve(p, time_budget_s=10.0, max_iterations=50)
    assert r.status != ik.TIME_LIMIT


def test_restoration_is_bounded_per_iteration() -> None:
    f = human_like_tree()
    f.reroot("foot_left", "tip")
    p = ik.Problem(f)
    p.add(ik.PositionOrientation("foot_right.tip", f.site_world("foot_right", "tip"), chain="ankle_left"))
    p.add(ik.Position("palm_right.tip", (-3.0, 1.5, 2.0), chain="ankle_left"), level=1)
    r = ik.solve(p, max_iterations=60)
    assert r.goals[0].metres < 1e-5
    # per iteration: line-search trials plus at most RESTORE_EVALUATIONS restoration evaluations
    assert r.evaluations <= (2 * RESTORE_EVALUATIONS + 2) * (r.iterations + 2)


def test_shoulder_jacobian_is_analytic_and_matches_finite_differences() -> None:
    d = ShoulderDriver()
    rng = np.random.default_rng(5)
    for _ in range(200):
        th = rng.uniform(SHOULDER_LOWER, SHOULDER_UPPER)
        if min(abs(np.degrees(th[0]) - 131.4), abs(np.degrees(th[0]) - 130.0)) < 1e-3:
            continue  # a breakpoint of Otani's allocation: one-sided there
        assert np.allclose(d.jacobian(th), d.numerical_jacobian(th, 1e-6), atol=1e-7)


def test_compiled_box_step_equals_numpy_reference() -> None:
    rng = np.random.default_rng(9)
    for _ in range(40):
        n, m = int(rng.integers(3, 91)), int(rng.integers(2, 25))
        J, F, lam = rng.normal(size=(m, n)), rng.normal(size=m) * 3, 10.0 ** rng.uniform(-3, 0)
        lo, hi = -rng.uniform(0, 0.3, n), rng.uniform(0, 0.3, n)
        c = J.T @ F
        a = bounded_step(J, lam, c, lo, hi)
        b = bounded_step(J, lam, c, lo, hi, compiled=False)
        assert np.all(a[0] >= lo) and np.all(a[0] <= hi) and np.array_equal(a[1], b[1]) and a[2] == b[2]
        assert abs(_model(J, lam, c, a[0]) - _model(J, lam, c, b[0])) <= 1e-10 * (1 + abs(_model(J, lam, c, b[0])))


def test_compiled_row_step_equals_numpy_reference() -> None:
    """Rows that bind (the compiled box minimiser misses them): the compiled row loop reaches the
    numpy reference's model value, inside the box and every row."""
    rng = np.random.default_rng(5)
    binding = equal = 0
    for _ in range(60):
        n, m = int(rng.integers(4, 80)), int(rng.integers(2, 12))
        J, F, lam = rng.normal(size=(m, n)), rng.normal(size=m) * 3, 10.0 ** rng.uniform(-4, 0)
        lo, hi = -rng.uniform(0, 0.5, n), rng.uniform(0, 0.5, n)
        lo[rng.random(n) < 0.2] = 0.0
        k = int(rng.integers(1, 6))
        A, r = rng.normal(size=(k, n)), rng.uniform(0, 0.2, k)
        r[0] = 0.0
        c = J.T @ F
        a = bounded_step(J, lam, c, lo, hi, A, r)
        b = bounded_step(J, lam, c, lo, hi, A, r, compiled=False)
        assert np.all(A @ a[0] <= r + 1e-12) and np.all(a[0] >= lo) and np.all(a[0] <= hi)
        qa, qb = _model(J, lam, c, a[0]), _model(J, lam, c, b[0])
        assert qa <= qb + 1e-10 * (1 + abs(qb))  # (the reference may stop short at its iteration cap)
        equal += abs(qa - qb) <= 1e-10 * (1 + abs(qb))
        binding += bool(np.any(A @ b[0] >= r - 1e-12))
    assert binding >= 30 and equal >= 55  # rows did bind: the row loop ran, not the box shortcut
