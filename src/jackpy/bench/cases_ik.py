"""IK benchmarks: the 7-DOF arm, the synthetic 136-DOF tree and the standard human (137 DOFs, joint
groups: 78 variables), cold and dragged, against scipy L-BFGS-B.

Success means every goal within 1 mm and 0.5 deg. The baseline minimises the same potential with
the same analytic gradient (one forward pass per call) from the same start, with the same box
limits, and stops at the same success test (a callback), so both sides solve the same problem
(except that L-BFGS-B only knows the box: the standard human's shoulder cuts ``A z <= b`` are ours alone).
"""

from __future__ import annotations

import time

import numpy as np
from scipy.optimize import minimize

from jackpy import ik
from jackpy.bench.runner import Case, Result
from jackpy.ik.arm7 import Q_OF_THETA, Arm7, arm7_figure
from jackpy.peabody.groups import VariableMap
from jackpy.peabody.model import Figure
from jackpy.peabody.synthetic import human_like_tree

TOL_M, TOL_DEG = 1e-3, 0.5


def _scipy(problem: ik.Problem) -> tuple[bool, float]:
    """(success, milliseconds) of L-BFGS-B on the problem's potential from the figure's posture."""
    comp = problem.compile()
    x, z0, _, _ = comp.start()
    q0 = comp.figure.q
    t0 = time.perf_counter()
    cache: dict[str, object] = {}

    def fun(z: np.ndarray) -> tuple[float, np.ndarray]:
        ev = comp.evaluate(x, q0, z)
        cache["ev"] = ev
        F, J = ev.stacked(comp.levels)
        return float(F @ F), 2.0 * J.T @ F

    def done(ev) -> bool:
        return all(e.metres <= TOL_M and e.degrees <= TOL_DEG for e in ev.goal_evals)

    def callback(intermediate_result) -> None:
        if done(cache["ev"]):
            raise StopIteration

    res = minimize(fun, z0, jac=True, method="L-BFGS-B", bounds=list(zip(comp.lower, comp.upper)),
                   callback=callback, options={"maxiter": 1000, "ftol": 1e-15, "gtol": 1e-12})
    ms = (time.perf_counter() - t0) * 1e3
    return done(comp.evaluate(x, q0, res.x)), ms


def _ours(problem: ik.Problem) -> tuple[bool, float, int]:
    t0 = time.perf_counter()
    r = ik.solve(problem, apply=False)
    ms = (time.perf_counter() - t0) * 1e3
    ok = all(g.metres <= TOL_M and g.degrees <= TOL_DEG for g in r.goals)
    return ok, ms, r.iterations


def _row(name: str, ours: list[tuple[bool, float, int]], base: list[tuple[bool, float]]) -> Result:
    t = np.array([o[1] for o in ours])
    tb = np.array([b[1] for b in base])
    return Result(name, float(np.median(t)), float(np.percentile(t, 90)), float(np.median(tb)), {
        "n": len(ours), "success": float(np.mean([o[0] for o in ours])),
        "base_success": float(np.mean([b[0] for b in base])),
        "iters": float(np.median([o[2] for o in ours]))})


# ----- arm ------------------------------------------------------------------------------------------
def arm_cold(quick: bool) -> Result:
    arm = Arm7()
    fig = arm7_figure(arm)
    rng = np.random.default_rng(1)
    problem = ik.Problem(fig)
    goal = problem.add(ik.PositionOrientation("hand.base", np.eye(4), cx=ik.unit_factor(1.0, 0.01)))
    ours, base, numeric = [], [], []
    for _ in range(50 if quick else 1000):
        q = np.zeros(7)
        q[Q_OF_THETA] = rng.uniform(arm.lower, arm.upper)
        fig.q = q
        goal.target = fig.site_world("hand", "base")
        fig.q = np.zeros(7)
        ours.append(_ours(problem))
        base.append(_scipy(problem))
        t0 = time.perf_counter()
        r = ik.solve(problem, analytic=False, apply=False)
        numeric.append((all(g.metres <= TOL_M and g.degrees <= TOL_DEG for g in r.goals),
                        (time.perf_counter() - t0) * 1e3))
    row = _row("ik-arm-cold", ours, base)
    row.extra["numeric_success"] = float(np.mean([n[0] for n in numeric]))
    row.extra["numeric_ms"] = float(np.median([n[1] for n in numeric]))
    return row


# ----- body -----------------------------------------------------------------------------------------
SITES = ("palm_left.tip", "palm_right.tip")


def body_problem() -> tuple[Figure, ik.Problem, list[ik.Goal]]:
    """Both hands position+orientation, head aim, centre of mass over a point (136-DOF tree)."""
    fig = human_like_tree()
    p = ik.Problem(fig)
    goals = [p.add(ik.PositionOrientation(s, np.eye(4), chain="spine1", cx=ik.unit_factor(1.0, 0.01)))
             for s in SITES]
    goals.append(p.add(ik.Aim("head.tip", (0.0, 1.8, 1.0), chain="spine1")))
    goals.append(p.add(ik.CentreOfMass(np.zeros(3))))
    return fig, p, goals


def set_targets(fig: Figure, goals: list[ik.Goal], q: np.ndarray) -> None:
    """Goals reproducing posture ``q`` (hand frames, a point 1 m along the head's +z, the COM)."""
    saved = fig.q
    fig.q = q
    for g, s in zip(goals, SITES):
        g.target = fig.site_world(*s.split("."))
    head = fig.site_world("head", "tip")
    goals[2].target = head[:3, 3] + head[:3, 2]
    goals[3].point = fig.centre_of_mass()
    fig.q = saved


def _cold(name: str, problem: ik.Problem, new_targets, reset, quick: bool) -> Result:
    """Solve ``problem`` from the neutral posture for 300 (quick: 50) target sets, scipy on the
    first 100 (quick: 20): ``new_targets()`` draws a target set, ``reset()`` restores the start."""
    ours, base = [], []
    for i in range(50 if quick else 300):
        new_targets()
        reset()
        ours.append(_ours(problem))
        if i < (20 if quick else 100):
            base.append(_scipy(problem))
    return _row(name, ours, base)


def body_cold(quick: bool) -> Result:
    fig, problem, goals = body_problem()
    rng = np.random.default_rng(2)
    q0 = fig.q

    def reset() -> None:
        fig.q = q0

    return _cold("ik-body-cold", problem,  # targets from postures at half the range of motion
                 lambda: set_targets(fig, goals, rng.uniform(fig.lower, fig.upper) * 0.5), reset, quick)


def body_drag(quick: bool) -> Result:
    fig, problem, goals = body_problem()
    rng = np.random.default_rng(3)
    set_targets(fig, goals, rng.uniform(fig.lower, fig.upper) * 0.3)
    ik.solve(problem)
    return _drag("ik-body-drag", problem, goals, 50 if quick else 200)


def _drag(name: str, problem: ik.Problem, goals: list[ik.Goal], frames: int) -> Result:
    """Drag the first goal's frame 5 mm per frame out and back along a line, solving each frame."""
    step = np.array([0.6, 0.48, 0.64]) * 0.005 / np.linalg.norm([0.6, 0.48, 0.64])  # 5 mm per frame
    times, ok, iters = [], 0, []
    for k in range(frames):
        target = goals[0].target.copy()
        target[:3, 3] += step if (k // 50) % 2 == 0 else -step  # out and back along a line
        goals[0].target = target
        t0 = time.perf_counter()
        r = ik.solve(problem)
        times.append((time.perf_counter() - t0) * 1e3)
        ok += all(g.metres <= TOL_M and g.degrees <= TOL_DEG for g in r.goals)
        iters.append(r.iterations)
    t = np.array(times)
    return Result(name, float(np.median(t)), float(np.percentile(t, 90)), None,
                  {"frames": frames, "success": ok / frames, "iters": float(np.median(iters))})


# ----- the standard human ----------------------------------------------------------------------------
HUMAN_SITES = ("left_palm.palm_centre", "right_palm.palm_centre")
HUMAN_HEAD = "head.view"


def human_problem() -> tuple[Figure, ik.Problem, list[ik.Goal]]:
    """The standard 50th-percentile male (root ``pelvis.centre``): both palms position+orientation,
    head aim (line of sight), centre of mass over a point; every chain from the root (78 variables)."""
    from jackpy.body import make_human

    fig = make_human("male", 50)
    p = ik.Problem(fig)
    goals = [p.add(ik.PositionOrientation(s, np.eye(4), cx=ik.unit_factor(1.0, 0.01))) for s in HUMAN_SITES]
    goals.append(p.add(ik.Aim(HUMAN_HEAD, (0.0, 1.7, 1.0))))
    goals.append(p.add(ik.CentreOfMass(np.zeros(3))))
    return fig, p, goals


def human_posture(fig: Figure, rng: np.random.Generator, fraction: float) -> np.ndarray:
    """Variables ``fraction`` of the way from the current posture to a random feasible one (every
    variable uniform in its box; group angles redrawn until their linear limits hold)."""
    vm = VariableMap(fig)
    x0 = vm.x()
    u = rng.uniform(vm.lower, vm.upper)
    for g, _, sl in vm.group_slices:
        while not g.is_feasible(u[sl]):
            u[sl] = rng.uniform(g.lower, g.upper)
    return x0 + fraction * (u - x0)  # convex: inside the box and the rows when x0 and u are


def set_human_targets(fig: Figure, goals: list[ik.Goal], x: np.ndarray) -> None:
    """Goals reproducing variables ``x`` (palm frames, a point 1 m along the line of sight, the COM)."""
    vm = VariableMap(fig)
    saved = vm.x()
    vm.apply(x)
    for g, s in zip(goals, HUMAN_SITES):
        g.target = fig.site_world(*s.split("."))
    head = fig.site_world(*HUMAN_HEAD.split("."))
    goals[2].target = head[:3, 3] + head[:3, 2]
    goals[3].point = fig.centre_of_mass()
    vm.apply(saved)


def human_cold(quick: bool) -> Result:
    fig, problem, goals = human_problem()
    rng = np.random.default_rng(4)
    vm = VariableMap(fig)
    x0 = vm.x()
    return _cold("ik-human-cold", problem,  # targets from postures at half the range of motion
                 lambda: set_human_targets(fig, goals, human_posture(fig, rng, 0.5)),
                 lambda: vm.apply(x0), quick)


def human_drag(quick: bool) -> Result:
    fig, problem, goals = human_problem()
    rng = np.random.default_rng(5)
    set_human_targets(fig, goals, human_posture(fig, rng, 0.3))
    ik.solve(problem)
    return _drag("ik-human-drag", problem, goals, 50 if quick else 200)


CASES = [
    Case("ik-arm-cold", arm_cold, "7-DOF arm, random 6-D targets from neutral (analytic seed + BFGS)"),
    Case("ik-body-cold", body_cold, "136-DOF tree: 2 hand frames, head aim, COM; from neutral"),
    Case("ik-body-drag", body_drag, "same goals, one hand dragged 5 mm/frame, warm start"),
    Case("ik-human-cold", human_cold, "standard human (78 variables, groups): palms, head aim, COM; from neutral"),
    Case("ik-human-drag", human_drag, "same goals, one palm dragged 5 mm/frame, warm start"),
]
