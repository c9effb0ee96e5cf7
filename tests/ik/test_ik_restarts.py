"""Restarts of a one-level bounded solve out of local minima (``solver._Run.restarted``)."""

import numpy as np
import pytest

from jackpy import ik
from jackpy.bench import cases_mink
from jackpy.ik import solver


@pytest.fixture(scope="module")
def peer():
    """Issue 20's 91-variable floating human (palms to targets, feet held; no mink needed) and a
    full-range target set whose solve from neutral gets caught in a local minimum."""
    side = cases_mink.JackpySide()
    feet = [side.figure.site_world(*s.split(".", 1)) for s in cases_mink.FEET]
    rng = np.random.default_rng(20)
    targets = [cases_mink._palm_targets(side, rng, 1.0) + feet for _ in range(20)][-1]
    side.set_targets(targets)
    return side


def _solve(side, **kw):
    side.figure.q = side.neutral
    return ik.solve(side.problem, tol_position=cases_mink.TOL_M, tol_angle=cases_mink.TOL_DEG, apply=False, **kw)


def test_restart_escapes_the_local_minimum(peer, monkeypatch) -> None:
    monkeypatch.setattr(solver, "RESTARTS", ())
    stuck = _solve(peer)
    monkeypatch.undo()
    r = _solve(peer)
    assert stuck.status != "achieved" and r.status == "achieved"
    assert r.iterations > solver.ATTEMPT_ITERATIONS  # it took a restart
    assert r.potential < stuck.potential


def test_restarts_share_the_budgets(peer) -> None:
    r = _solve(peer, max_iterations=30)
    assert r.iterations <= 30 and r.evaluations <= 2 + solver.EVALUATIONS_PER_ITERATION * 30
    assert np.all(np.isfinite(r.q))
    t = _solve(peer, time_budget_s=0.0)
    assert t.status == "time_limit"


def test_a_settled_warm_start_is_not_restarted(monkeypatch) -> None:
    fig = cases_mink.JackpySide().figure
    problem = ik.Problem(fig)
    problem.add(ik.Position("left_palm.palm_centre", (0.0, 5.0, 3.0), chain="left_shoulder"))  # out of reach
    first = ik.solve(problem)
    calls = []
    original = solver._Run.minimise_bounded

    def counted(self, *args):
        calls.append(1)
        return original(self, *args)

    monkeypatch.setattr(solver._Run, "minimise_bounded", counted)
    again = ik.solve(problem)
    assert first.status == again.status == "unreachable"
    assert len(calls) == 1 and again.iterations < solver.ATTEMPT_ITERATIONS
