"""Priority solves have bounded cost: ``max_iterations`` bounds the evaluations (forward passes)."""

import numpy as np
import pytest

from jackpy import ik
from jackpy.ik import solver
from jackpy.peabody.synthetic import human_like_tree

SITES = ("palm_left.tip", "palm_right.tip", "head.tip", "foot_right.tip")


def _problems(n: int, seed: int):
    """Random 2-3 level problems on the tree stood on its left foot: the right foot held at level 0,
    hands and head at lower levels, targets reachable, far away (unreachable) or at the root."""
    rng = np.random.default_rng(seed)
    fig = human_like_tree()
    fig.reroot("foot_left", "tip")
    neutral = fig.q
    for _ in range(n):
        fig.q = neutral
        foot = fig.site_world("foot_right", "tip")
        fig.q = np.clip(neutral + rng.normal(0, 0.4, neutral.size), fig.lower, fig.upper)
        frames = {s: fig.site_world(*s.split(".")) for s in SITES}
        fig.q = neutral
        p = ik.Problem(fig)
        p.add(ik.PositionOrientation("foot_right.tip", foot, chain="ankle_left"), level=0)
        levels = int(rng.integers(2, 4))
        for site in rng.choice(SITES[:3], size=int(rng.integers(1, 4)), replace=False):
            t = frames[site].copy()
            mode = rng.random()
            if mode < 0.3:
                t[:3, 3] += rng.normal(size=3) * 3.0  # unreachable
            elif mode < 0.4:
                t[:3, 3] = fig.location[:3, 3]  # at the root
            goal = ik.PositionOrientation(site, t, chain="ankle_left") if rng.random() < 0.5 else \
                ik.Position(site, t, chain="ankle_left")
            p.add(goal, level=int(rng.integers(1, levels)))
        yield fig, p


@pytest.mark.parametrize("per_iteration", [solver.EVALUATIONS_PER_ITERATION, 1])
def test_priority_evaluations_are_bounded_by_max_iterations(monkeypatch, per_iteration):
    """With the shipped budget and with a budget of one evaluation per iteration (which must then
    end some solves early, as ``"iteration_limit"``, feasible and finite)."""
    monkeypatch.setattr(solver, "EVALUATIONS_PER_ITERATION", per_iteration)
    capped = 0
    for max_iterations in (2, 8, 40):
        for fig, p in _problems(10, seed=max_iterations):
            r = ik.solve(p, max_iterations=max_iterations)
            assert r.iterations <= max_iterations
            assert r.evaluations <= 2 + per_iteration * max_iterations, (r.evaluations, r.iterations)
            q = fig.q
            assert np.all(np.isfinite(q))
            assert np.all(q >= fig.lower - 1e-9) and np.all(q <= fig.upper + 1e-9)
            capped += r.status == ik.ITERATION_LIMIT and r.iterations < max_iterations
    if per_iteration == 1:
        assert capped > 0


def test_spent_evaluations_return_the_best_feasible_iterate():
    fig, p = next(_problems(1, seed=3))
    r1 = ik.solve(p, max_iterations=1, apply=False)
    assert r1.evaluations <= 2 + solver.EVALUATIONS_PER_ITERATION
    assert r1.status in (ik.ITERATION_LIMIT, ik.ACHIEVED, ik.UNREACHABLE)
    # the held level is never worse than at the start (only restored trials are accepted)
    start = ik.solve(p, max_iterations=0, apply=False)
    assert r1.goals[0].potential <= start.goals[0].potential + 1e-9
