"""The IK robustness mix: random problems on three figures, checked for NaN, limit violations and
exceptions, and timed per problem (priority problems' p99 and max are the issue's targets).

Figures: a 6-joint planar chain with a linear joint group and a cut ``A x <= b``, the synthetic
136-DOF tree stood on its left foot, and the standard human (spine and shoulder drivers, shoulder
cuts). Per problem: a random feasible start, 1-4 goals of random types (position, orientation,
position+orientation, aim, centre of mass, plane, line, a point outside a box as ``AnyOf`` of
half-spaces) on random sites, at 1-3 priority levels; targets reachable (from a random posture),
unreachable (metres away) or singular (at the chain's base, or straight along a stretched arm).
A violation is an ungrouped DOF outside its limits, a group angle outside its box, or a row
``A x > b``, by more than 1e-9; every exception counts, whatever it is.
"""

from __future__ import annotations

import time

import numpy as np

from jackpy import ik
from jackpy.bench.runner import Case, Result
from jackpy.peabody.groups import JointGroup, LinearDriver, VariableMap
from jackpy.peabody.model import Dof, Figure, Joint, Segment
from jackpy.peabody.transforms import translation

TOL = 1e-9


def _chain() -> Figure:
    f = Figure("chain")
    for i in range(7):
        s = f.add_segment(Segment(f"s{i}", mass=1.0, com=np.array([0.15, 0, 0])))
        s.add_site("base")
        s.add_site("tip", translation(0.3, 0, 0))
    for i in range(6):
        axis = (0, 0, 1) if i % 3 else (0, 1, 0)
        f.add_joint(Joint(f"j{i}", f"s{i}", "tip", f"s{i + 1}", "base", [Dof("R", axis, -1.5, 1.5)]))
    f.root = ("s0", "base")
    f.add_group(JointGroup("pair", ["j2", "j3"], ["a", "b"], LinearDriver(np.eye(2)), [-1.5, -1.5],
                           [1.5, 1.5], A=[[1.0, 1.0]], b=[0.6]))
    return f


def figures() -> list[tuple[Figure, list[str]]]:
    """(figure, end-effector sites) of the mix."""
    from jackpy.body import make_human
    from jackpy.peabody.synthetic import human_like_tree

    tree = human_like_tree()
    tree.reroot("foot_left", "tip")
    human = make_human("male", 50)
    return [(_chain(), ["s6.tip", "s4.tip"]),
            (tree, ["palm_left.tip", "palm_right.tip", "head.tip", "foot_right.tip"]),
            (human, ["left_palm.palm_centre", "right_palm.palm_centre", "head.view", "right_foot.base"])]


def _random_x(vm: VariableMap, fig: Figure, rng: np.random.Generator, fraction: float) -> np.ndarray:
    u = rng.uniform(vm.lower, vm.upper)
    for g, _, sl in vm.group_slices:
        for _ in range(200):
            if g.is_feasible(u[sl]):
                break
            u[sl] = rng.uniform(g.lower, g.upper)
        else:
            u[sl] = g.angles
    x = vm.x() * (1 - fraction) + u * fraction
    for g, _, sl in vm.group_slices:  # a group's region need not be convex (the shoulder's two
        if not g.is_feasible(x[sl]):  # pieces): a blend of two feasible points may leave it
            x[sl] = u[sl]
    return x


def violation(fig: Figure) -> float:
    """Largest excess (radians/metres) of the solver's limits: the boxes of the variables (ungrouped
    DOFs and group angles) and the groups' rows. (A grouped joint's own DOF limits are not the
    solver's: its displacements are the driver's function of the group angles.)"""
    vm = VariableMap(fig)
    x = vm.x()
    worst = float(np.max(np.maximum(vm.lower - x, x - vm.upper), initial=0.0))
    A, b = vm.linear_constraints()
    if A.shape[0]:
        worst = max(worst, float(np.max(A @ x - b, initial=0.0)))
    return worst


def _goal(fig: Figure, site: str, rng: np.random.Generator, kind: int, target: np.ndarray) -> ik.Goal:
    p, R = target[:3, 3], target
    if kind == 0:
        return ik.Position(site, p)
    if kind == 1:
        return ik.Orientation(site, R)
    if kind == 2:
        return ik.PositionOrientation(site, R, cx=ik.unit_factor(1.0, 0.01))
    if kind == 3:
        return ik.Aim(site, p + rng.normal(size=3))
    if kind == 4:
        return ik.CentreOfMass(p * (1, 0, 1))
    if kind == 5:
        return ik.Plane(site, p, rng.normal(size=3))
    if kind == 6:
        return ik.Line(site, p, rng.normal(size=3))
    lo, hi = p - 0.1, p + 0.1  # outside a 20 cm box around p
    faces = [ik.HalfSpace(site, np.where(np.arange(3) == k, (lo if s < 0 else hi)[k], 0.0), n)
             for k in range(3) for s, n in ((-1, -np.eye(3)[k]), (1, np.eye(3)[k]))]
    return ik.AnyOf(faces)


def _random_problem(fig: Figure, sites: list[str], start: np.ndarray, rng: np.random.Generator,
                    priority: bool) -> ik.Problem:
    """A random problem from a random start (see the module docstring); ``priority``: 2-4 goals on
    2-3 levels, each level used."""
    vm = VariableMap(fig)
    vm.apply(start)
    x_target = _random_x(vm, fig, rng, rng.choice([0.3, 1.0]))
    vm.apply(x_target)
    frames = {s: fig.site_world(*s.split(".", 1)) for s in sites}
    vm.apply(_random_x(vm, fig, rng, rng.uniform(0.0, 0.6)))
    p = ik.Problem(fig)
    levels = int(rng.integers(2, 4)) if priority else int(rng.integers(1, 4))
    count = int(rng.integers(levels, 5)) if priority else int(rng.integers(1, 5))
    for k in range(count):
        site = sites[int(rng.integers(len(sites)))]
        target = frames[site].copy()
        mode = rng.random()
        if mode < 0.2:  # unreachable
            target[:3, 3] += rng.normal(size=3) * 3.0
        elif mode < 0.3:  # singular: the root's own point
            target[:3, 3] = fig.location[:3, 3]
        goal = _goal(fig, site, rng, int(rng.integers(8)), target)
        p.add(goal, level=k if priority and k < levels else int(rng.integers(levels)))
    return p


def run_mix(n: int, seed: int = 0, *, priority: bool = False, time_budget_s: float | None = None) -> dict:
    """Solve ``n`` random problems (``priority``: multi-level ones only); counts of NaN, violations,
    exceptions, per-problem times (ms), evaluations and statuses of the priority solves."""
    rng = np.random.default_rng(seed)
    figs = figures()
    starts = {id(f): VariableMap(f).x() for f, _ in figs}
    nan = viol = exc = 0
    times: list[float] = []
    prio: list[float] = []
    prio_evals: list[int] = []
    statuses: dict[str, int] = {}
    worst = 0.0
    errors: list[str] = []
    for i in range(n):
        fig, sites = figs[i % len(figs)]
        p = _random_problem(fig, sites, starts[id(fig)], rng, priority)
        t0 = time.perf_counter()
        try:
            r = ik.solve(p, max_iterations=100, time_budget_s=time_budget_s)
        except Exception as e:  # noqa: BLE001 - every exception counts
            exc += 1
            errors.append(f"{type(e).__name__}: {e}")
            continue
        ms = (time.perf_counter() - t0) * 1e3
        times.append(ms)
        if len({p.level_of(g) for g in p.goals}) > 1:
            prio.append(ms)
            prio_evals.append(r.evaluations)
            statuses[r.status] = statuses.get(r.status, 0) + 1
        q = fig.q
        if not np.all(np.isfinite(q)) or any(not np.all(np.isfinite(g.angles)) for g in fig.groups.values()):
            nan += 1
        v = violation(fig)
        worst = max(worst, v)
        viol += v > TOL
    return {"n": n, "nan": nan, "violations": viol, "exceptions": exc, "worst_violation": worst,
            "times_ms": np.array(times), "priority_ms": np.array(prio), "priority_evaluations": np.array(prio_evals),
            "statuses": statuses, "errors": errors[:5]}


def _pct(a: np.ndarray, q: float) -> float:
    return float(np.percentile(a, q)) if a.size else 0.0


def robustness(quick: bool) -> Result:
    out = run_mix(300 if quick else 10_000)
    t, pr = out["times_ms"], out["priority_ms"]
    return Result("ik-robustness", float(np.median(t)), _pct(t, 90), None, {
        "n": out["n"], "nan": out["nan"], "violations": out["violations"], "exceptions": out["exceptions"],
        "priority_n": int(pr.size), "priority_p99": _pct(pr, 99), "priority_max": _pct(pr, 100),
        "max": _pct(t, 100)})


def priority_mix(quick: bool) -> Result:
    """Multi-level problems only (2-3 levels, each used), no time box: p50/p90/p99/max (ms) and
    evaluations; then the first third of them with a 20 ms box: the longest solve."""
    n = 150 if quick else 600
    run_mix(3, seed=99, priority=True)  # one problem per figure first: compiled kernels load untimed
    out = run_mix(n, seed=5, priority=True)
    t, ev = out["priority_ms"], out["priority_evaluations"]
    box = run_mix(n // 3, seed=5, priority=True, time_budget_s=0.02)
    return Result("ik-priority-mix", _pct(t, 50), _pct(t, 90), None, {
        "n": int(t.size), "p99": _pct(t, 99), "max": _pct(t, 100), "evaluations_max": int(ev.max(initial=0)),
        "evaluations_median": _pct(ev, 50), "statuses": "/".join(f"{k}:{v}" for k, v in sorted(out["statuses"].items())),
        "box20_max_ms": _pct(box["priority_ms"], 100), "box20_time_limit": box["statuses"].get(ik.TIME_LIMIT, 0),
        "nan": out["nan"] + box["nan"], "violations": out["violations"] + box["violations"],
        "exceptions": out["exceptions"] + box["exceptions"]})


CASES = [Case("ik-robustness", robustness,
              "random problems on 3 figures, 1-3 levels, unreachable/singular targets: NaN, violations, exceptions"),
         Case("ik-priority-mix", priority_mix,
              "the robustness mix's multi-level problems: p50/p90/p99/max, evaluations; 20 ms box overrun")]
