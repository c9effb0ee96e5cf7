"""Priority levels solved with the bounded step (:func:`jackpy.ik.priorities.minimise_levels`): the
higher levels are never worsened, the restoration work of an iteration is bounded (counted in
evaluations), and the time box is kept (no evaluation starts after it; the result says it stopped)."""

from __future__ import annotations

import gc
from collections import Counter

import numpy as np
import pytest

from jackpy import ik
from jackpy.ik import priorities, solver
from jackpy.peabody.synthetic import human_like_tree

SITES = ("palm_left.tip", "palm_right.tip", "head.tip")


def _problems(n: int, seed: int):
    """2-3 level problems on the tree stood on its left foot: the right foot held at level 0, hands
    and head below it with reachable, unreachable (metres away) or root targets."""
    rng = np.random.default_rng(seed)
    fig = human_like_tree()
    fig.reroot("foot_left", "tip")
    neutral = fig.q
    for _ in range(n):
        fig.q = neutral
        foot = fig.site_world("foot_right", "tip")
        fig.q = np.clip(neutral + rng.normal(0, 0.4, neutral.size), fig.lower, fig.upper)
        frames = {s: fig.site_world(*s.split(".")) for s in SITES}
        fig.q = np.clip(neutral + rng.normal(0, 0.2, neutral.size), fig.lower, fig.upper)
        p = ik.Problem(fig)
        p.add(ik.PositionOrientation("foot_right.tip", foot, chain="ankle_left"), level=0)
        levels = int(rng.integers(2, 4))
        for k, site in enumerate(rng.choice(SITES, size=int(rng.integers(2, 4)), replace=False)):
            t = frames[site].copy()
            mode = rng.random()
            if mode < 0.3:
                t[:3, 3] += rng.normal(size=3) * 3.0
            elif mode < 0.4:
                t[:3, 3] = fig.location[:3, 3]
            goal = ik.PositionOrientation(site, t) if rng.random() < 0.5 else ik.Position(site, t)
            p.add(goal, level=min(k + 1, levels - 1))
        yield fig, p


class EvaluationClock:
    """The solver's clock in a test: time advances by ``step`` seconds per evaluation only, so what
    a time box stops does not depend on the machine's load."""

    def __init__(self, step: float = 0.001) -> None:
        self.now, self.step = 0.0, step

    def perf_counter(self) -> float:
        return self.now

    def tick(self) -> None:
        self.now += self.step


def _run(problem: ik.Problem, max_iterations: int = 100, time_budget_s: float | None = None):
    """A solve's state as :func:`jackpy.ik.solve` sets it up, with every evaluation recorded as
    (start time, iterations done when it started)."""
    run = solver._Run(problem.compile(), 1e-4, 0.05, 1e-10)
    run.max_evaluations = 2 + solver.EVALUATIONS_PER_ITERATION * max_iterations
    if time_budget_s is not None:
        run.deadline = run.started + time_budget_s
    log: list[tuple[float, int]] = []
    evaluate = run.evaluate

    def recorded(z):
        log.append((solver.time.perf_counter(), run.iterations))
        if isinstance(solver.time, EvaluationClock):
            solver.time.tick()
        return evaluate(z)

    run.evaluate = recorded
    return run, log


def _solve(problem: ik.Problem, levels: list[int] | None = None, **kw):
    run, log = _run(problem, **kw)
    ev = run.evaluate(run.z)
    ev, status = priorities.minimise_levels(run, ev, levels or run.comp.levels, kw.get("max_iterations", 100))
    return run, ev, status, log


def test_higher_levels_are_never_worsened_by_lower_ones() -> None:
    lower_moved = 0
    for fig, p in _problems(8, seed=4):
        start = fig.q
        _, ev1, _, _ = _solve(p, levels=[0, 1])  # the same iterates as the full solve up to level 1
        fig.q = start
        _, ev0, _, _ = _solve(p, levels=[0])
        fig.q = start
        run, ev, status, _ = _solve(p)
        tol = lambda g: priorities.HOLD_TOL + priorities.RESTORE_REL * g  # noqa: E731
        assert ev.potential(0) <= ev0.potential(0) + tol(ev0.potential(0))
        assert ev1.potential(0) <= ev0.potential(0) + tol(ev0.potential(0))
        if 2 in run.comp.levels:
            assert ev.potential(1) <= ev1.potential(1) + tol(ev1.potential(1))
        assert np.all(np.isfinite(ev.z)) and np.all(ev.z >= run.lo) and np.all(ev.z <= run.hi)
        lower_moved += float(np.max(np.abs(ev.z - ev0.z))) > 1e-3
    assert lower_moved >= 4  # the lower levels did move the figure


def test_restoration_evaluations_per_iteration_are_bounded() -> None:
    most, restored = 0, 0
    for _, p in _problems(8, seed=9):
        run, _, _, log = _solve(p)
        per_iteration = Counter(it for _, it in log)
        del per_iteration[0]  # the start's evaluation
        most = max(most, max(per_iteration.values(), default=0))
        restored += sum(v > 1 for v in per_iteration.values())
    assert most <= priorities.LINE_TRIALS + priorities.BOUNDED_RESTORE_EVALUATIONS
    assert restored > 0  # restoration (or backtracking) did run


def test_the_time_box_stops_a_priority_solve_at_its_best_feasible_iterate(monkeypatch) -> None:
    """On a clock that advances 1 ms per evaluation (the wall clock under load made this a race
    between the solver's check and the evaluation's start), a 4 ms box allows the evaluations that
    start before it and none after."""
    monkeypatch.setattr(solver, "time", EvaluationClock(0.001))
    stopped = 0
    for fig, p in _problems(6, seed=2):
        start = fig.q
        box = 0.004
        run, ev, status, log = _solve(p, time_budget_s=box)
        # (the first is the start's, which every solve evaluates)
        assert all(t < run.deadline for t, _ in log[1:]), "an evaluation started after the time box"
        if status == ik.TIME_LIMIT:
            stopped += 1
            # the returned iterate was accepted: feasible, the held foot no worse than at the start
            fig.q = start
            g = _solve(p, max_iterations=0)[1].potential(0)
            assert ev.potential(0) <= g + priorities.HOLD_TOL + priorities.RESTORE_REL * g
            assert np.all(ev.z >= run.lo) and np.all(ev.z <= run.hi)
        fig.q = start
    assert stopped > 0


def test_time_limit_is_reported_by_solve() -> None:
    fig, p = next(_problems(1, seed=2))
    r = ik.solve(p, time_budget_s=0.0, apply=False)
    assert r.status == ik.TIME_LIMIT and not r.converged
    assert r.evaluations <= 1
    assert np.all(np.isfinite(r.q))


def test_the_time_box_counts_from_the_call(monkeypatch) -> None:
    """Compiling the problem is part of the box: on a clock that compile() advances by 1 s, a
    0.5 s box has passed before the first iteration."""
    clock = EvaluationClock(0.0)
    monkeypatch.setattr(solver, "time", clock)
    fig, p = next(_problems(1, seed=2))
    compile_ = p.compile

    def slow_compile():
        clock.now += 1.0
        return compile_()

    monkeypatch.setattr(p, "compile", slow_compile)
    r = ik.solve(p, time_budget_s=0.5, apply=False)
    assert r.status == ik.TIME_LIMIT and r.iterations == 0 and r.evaluations <= 1
    assert ik.solve(p, time_budget_s=2.0, apply=False).iterations > 0


def test_a_solve_pauses_the_cyclic_collector(monkeypatch) -> None:
    """No full collection of the process can fall inside a solve, boxed or not (it resumes after
    the solve); a caller that has switched the collector off keeps it off."""
    fig, p = next(_problems(1, seed=2))
    comp = p.compile()
    seen: list[bool] = []
    evaluate = comp.evaluate

    def recorded(*args):
        seen.append(gc.isenabled())
        return evaluate(*args)

    monkeypatch.setattr(comp, "evaluate", recorded)
    start = fig.q
    ik.solve(p, time_budget_s=10.0)
    assert seen and not any(seen) and gc.isenabled()
    seen.clear()
    fig.q = start
    ik.solve(p)
    assert seen and not any(seen) and gc.isenabled()
    seen.clear()
    fig.q = start
    gc.disable()
    try:
        ik.solve(p)
        assert seen and not gc.isenabled()
    finally:
        gc.enable()


def test_solve_dispatches_priority_levels_to_the_bounded_step_unless_asked_for_the_books(monkeypatch) -> None:
    fig, p = next(iter(_problems(1, seed=7)))
    start = fig.q
    calls = []
    real = priorities.minimise_levels

    def spy(*a, **kw):
        calls.append(1)
        return real(*a, **kw)

    monkeypatch.setattr(solver, "minimise_levels", spy)
    bounded = ik.solve(p, max_iterations=30)
    assert calls and len({p.level_of(g) for g in p.goals}) > 1
    after_bounded = fig.q
    fig.q = start
    calls.clear()
    book = ik.solve(p, max_iterations=30, priorities="book")
    assert not calls  # the book's projected BFGS with restoration
    assert bounded.evaluations <= 2 + solver.EVALUATIONS_PER_ITERATION * 30
    assert np.all(np.isfinite(after_bounded)) and np.all(np.isfinite(fig.q)) and book.iterations >= 0
    with pytest.raises(ValueError, match="priorities"):
        ik.solve(p, priorities="fast")
