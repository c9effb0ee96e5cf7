"""The IK solver: bounded Gauss-Newton steps for one-level problems (:meth:`_Run.minimise_bounded`,
many limits settled per step on the quadratic model, see :mod:`.bounded_step` and docs/ik.md), and
the book's variable-metric (BFGS) minimisation with Rosen/Goldfarb projection onto linear limits
(§3.3) for priority levels. The rest of this docstring describes the latter.

The variables are the problem's scaled variables ``z`` (see :mod:`.problem`); the limits are the box
``lower <= z <= upper`` and the joint groups' rows ``A z <= b``. The method is Goldfarb's (1969)
extension of the variable-metric method to linear inequalities:

- **Feasible iterates.** The start is clamped (and projected onto the rows); every trial point lies
  inside every limit, because steps never exceed the largest feasible step ``alpha_max``.
- **Working set and projected metric.** ``H`` is an inverse-Hessian approximation whose range is the
  null space of the active constraints (a variable at a bound has a zero row and column). Hitting a
  limit adds it (``H <- H - H a a^T H / a^T H a``); a constraint whose Lagrange multiplier is negative
  is dropped (``H <- H + P a a^T P / a^T B0 P a``), one at a time, when the projected gradient has
  become small against that multiplier.
- **Initial metric.** ``H0`` is the inverse of the Gauss-Newton matrix ``2 J^T J + mu I`` of the
  sum-of-squares potential (Woodbury, O(n^2 m)), restricted to the working set: good curvature from
  the first step. It is reset when a disjunction switches, or when ``H`` stops giving descent.
  ``mu`` in scaled variables is what makes stiffness pick among redundant solutions.
- **BFGS** inverse update after each step (skipped when ``s.y`` is not positive).
- **Line search** on ``(0, alpha_max]``: Armijo backtracking with quadratic interpolation.
- **Termination**: every goal within ``tol_position``/``tol_angle`` (achieved); a KKT point (step
  below ``tol_step`` and all multipliers non-negative) or no further decrease; the iteration cap.
"""

from __future__ import annotations

import gc
import math
import time

import numpy as np

from jackpy.errors import FigureError
from jackpy.ik.bounded_step import bounded_step
from jackpy.ik.priorities import CONDITION, RESTORE_EVALUATIONS, Manifold, minimise_levels
from jackpy.ik.problem import Compiled, Evaluation, Problem
from jackpy.ik.result import ACHIEVED, ITERATION_LIMIT, TIME_LIMIT, UNREACHABLE, GoalReport, Result

C1 = 1e-4  # Armijo constant
BOUND_TOL = 1e-12
MU_SCALE = 10.0
MU_FLOOR = 1e-3
#: relative potential decrease and largest move (scaled radians) below which an iteration creeps
CREEP, CREEP_STEP = 1e-9, 1e-8
#: damping of the bounded Gauss-Newton step: ``lambda = GN_DAMPING_FLOOR + GN_DAMPING * |F|`` (scaled units)
GN_DAMPING, GN_DAMPING_FLOOR = 0.01, 1e-4
_EMPTY = np.zeros(0)
#: restarts of a one-level bounded solve caught in a local minimum (:meth:`_Run.restarted`): the
#: fraction of the way from the start to the middle of the limits, and the damping scale; and the
#: iterations each attempt may take before the next
RESTARTS = ((0.5, 1.0), (1.0, 1.0), (0.0, 0.3))
ATTEMPT_ITERATIONS = 20
#: forward passes one iteration may spend on average (line-search trials and, with priority levels,
#: their restoration steps): a solve starts at most ``2 + EVALUATIONS_PER_ITERATION * max_iterations``
#: evaluations (the start and an arm seed), so ``max_iterations`` bounds its cost; when they are
#: spent it returns its last accepted (best feasible) iterate with status ``"iteration_limit"``
EVALUATIONS_PER_ITERATION = 4

try:  # numpy.linalg.inv's own kernel, without its per-call checks (the matrix is positive definite)
    from numpy.linalg import _umath_linalg

    def _inv(M: np.ndarray) -> np.ndarray:
        return _umath_linalg.inv(M, signature="d->d")
except (ImportError, AttributeError):  # pragma: no cover
    _inv = np.linalg.inv


def solve(problem: Problem, *, max_iterations: int = 100, tol_position: float = 1e-4,
          tol_angle: float = 0.05, tol_step: float = 1e-10, analytic: bool = True,
          apply: bool = True, time_budget_s: float | None = None, step: str = "bounded",
          priorities: str = "bounded") -> Result:
    """Solve ``problem`` from the figure's current posture (a warm start).

    ``tol_position`` metres and ``tol_angle`` degrees decide when a goal is achieved; ``tol_step``
    (scaled radians) is the KKT step tolerance; ``max_iterations`` caps the work (an interactive
    frame budget; the posture reached is still feasible and better). ``time_budget_s`` is a promise,
    counted from this call: no evaluation starts after it has passed, and the solve returns its best
    feasible iterate with status ``"time_limit"``. The cyclic garbage collector waits until the
    solve has returned. With ``analytic`` a problem that is exactly one 6-D goal on a 7-DOF arm
    chain starts from the closed-form solution (see :mod:`.arm7`). ``step``: ``"bounded"`` (default)
    solves a one-level problem by bounded Gauss-Newton steps (many limits per step,
    :mod:`.bounded_step`); ``step="bfgs"`` uses the book's one-limit-at-a-time projected BFGS.
    ``priorities`` (with ``step="bounded"``), for problems with priority levels: ``"bounded"``
    (default) solves them by bounded tangent steps with bounded restoration
    (:func:`.priorities.minimise_levels`), ``"book"`` by the projected BFGS with restoration onto
    the higher levels (the behavior loop's passes, see docs/ik.md). With ``apply`` the result is
    written into the figure.
    """
    if step not in ("bounded", "bfgs"):
        raise ValueError(f"step must be 'bounded' or 'bfgs', not {step!r}")
    if priorities not in ("bounded", "book"):
        raise ValueError(f"priorities must be 'bounded' or 'book', not {priorities!r}")
    started = time.perf_counter()
    if not gc.isenabled():
        return _solve(problem, started, max_iterations, tol_position, tol_angle, tol_step, analytic, apply,
                      time_budget_s, step, priorities)
    # the cyclic garbage collector waits until the solve has returned: the solve's own garbage has
    # no cycles and goes by reference counting, but a collection that falls inside it scans the
    # whole process (a full one of the bench's process took 128 ms, six 20 ms boxes; unboxed, one
    # 8-evaluation priority solve of the mix took 174 ms)
    gc.disable()
    try:
        return _solve(problem, started, max_iterations, tol_position, tol_angle, tol_step, analytic, apply,
                      time_budget_s, step, priorities)
    finally:
        gc.enable()


def _solve(problem: Problem, started: float, max_iterations: int, tol_position: float, tol_angle: float,
           tol_step: float, analytic: bool, apply: bool, time_budget_s: float | None, step: str,
           priorities: str) -> Result:
    """:func:`solve`, its time box counted from ``started`` (``perf_counter`` at its call)."""
    comp = problem.compile()
    run = _Run(comp, tol_position, tol_angle, tol_step)
    run.max_evaluations = 2 + EVALUATIONS_PER_ITERATION * max(int(max_iterations), 0)
    if time_budget_s is not None:
        run.deadline = started + max(0.0, float(time_budget_s))
    result = ev = None
    if analytic and comp.arm is not None:
        z = comp.arm.seed(comp, run.x_base, run.z)
        if z is not None:
            run.z = z
            ev = run.evaluate(z)
            if run.achieved(ev, comp.levels[-1]):
                result = run.result(ev, ACHIEVED, 0, analytic=True)
    if result is None and step == "bounded" and priorities == "bounded" and len(comp.levels) > 1:
        ev, status = minimise_levels(run, run.evaluate(run.z), list(comp.levels), max_iterations)
        if status not in (ITERATION_LIMIT, TIME_LIMIT):
            status = ACHIEVED if run.achieved(ev, comp.levels[-1]) else UNREACHABLE
        run.z = ev.z
        result = run.result(ev, status, run.iterations, analytic=comp.arm is not None and analytic)
    if result is None:
        ev = run.evaluate(run.z)
        status = ACHIEVED
        for i, level in enumerate(comp.levels):
            manifold = None
            if i:
                hi = comp.levels[:i]
                manifold = Manifold(hi, float(sum(ev.potential(k) for k in hi)))
            if step == "bounded" and len(comp.levels) == 1:
                ev, status = run.restarted(ev, level, max_iterations)
            else:
                ev, status = run.minimise(ev, level, manifold, max_iterations - run.iterations)
            if status in (ITERATION_LIMIT, TIME_LIMIT):
                break
        if status not in (ITERATION_LIMIT, TIME_LIMIT):
            status = ACHIEVED if run.achieved(ev, comp.levels[-1]) else UNREACHABLE
        result = run.result(ev, status, run.iterations, analytic=comp.arm is not None and analytic)
    if apply:
        known = ev.posture() if ev is not None and ev.z is run.z else None
        if known is not None:  # the last evaluation's posture: no drivers, no copies
            comp.apply(known[0], q=known[1])
        else:
            comp.apply(comp.x_of(run.x_base, run.z), run.q_base)
    return result


def _creeping(G: float, G_new: float, moved: float) -> bool:
    """An iteration that no longer makes progress: the potential fell by under ``CREEP`` of itself
    or the largest variable moved under ``CREEP_STEP`` (scaled units); three in a row end a level
    as stationary (an unreachable goal is then reported at its closest posture)."""
    return G - G_new <= CREEP * G + 1e-18 or moved <= CREEP_STEP


class _Run:
    """State of one solve: bases, limits, counters."""

    def __init__(self, comp: Compiled, tol_position: float, tol_angle: float, tol_step: float,
                 memory: int = 5) -> None:
        self.comp = comp
        self.tol_position, self.tol_angle, self.tol_step = tol_position, tol_angle, tol_step
        self.q_base = comp.figure.q
        self.x_base, z, self.A, self.b = comp.start(self.q_base)
        self.lo, self.hi = comp.lower, comp.upper
        self.z = self._feasible(z)
        self._all_rows = np.arange(self.A.shape[0])
        self.iterations = 0
        self.memory = memory
        self.evaluations = 0
        self.started = time.perf_counter()
        self.deadline = math.inf
        self.max_evaluations = math.inf
        self.damping = 1.0  # scale of the bounded step's damping (restarts, :data:`RESTART_DAMPING`)

    # ----- helpers ----------------------------------------------------------------------------------
    def _feasible(self, z: np.ndarray) -> np.ndarray:
        """Clamp into the box and, if rows are violated, project (Dykstra) onto box and rows."""
        z = np.clip(z, self.lo, self.hi)
        if not self.A.shape[0] or np.all(self.A @ z <= self.b + 1e-12):
            return z
        y, p, qr = z.copy(), np.zeros_like(z), np.zeros_like(z)
        for _ in range(500):
            w = np.clip(y + p, self.lo, self.hi)
            p = y + p - w
            v = w + qr
            viol = self.A @ v - self.b
            for i in np.flatnonzero(viol > 0):
                a = self.A[i]
                v = v - max(0.0, a @ v - self.b[i]) / (a @ a) * a
            qr = w + qr - v
            y = v
            if np.all(self.A @ y <= self.b + 1e-12) and np.all((y >= self.lo - 1e-12) & (y <= self.hi + 1e-12)):
                break
        y = np.clip(y, self.lo, self.hi)
        if np.any(self.A @ y > self.b + 1e-9):
            raise FigureError("the joint groups' linear limits cannot be met within the joint limits")
        return y

    def expired(self) -> bool:
        """True once the time budget has passed or the evaluations are spent (then no further
        evaluation is started)."""
        return self.evaluations >= self.max_evaluations or (
            self.deadline != math.inf and time.perf_counter() >= self.deadline)

    def stop_status(self) -> str:
        """Why :meth:`expired`: the time box, else the evaluation budget (part of the iteration cap)."""
        return ITERATION_LIMIT if self.evaluations >= self.max_evaluations else TIME_LIMIT

    def evaluate(self, z: np.ndarray) -> Evaluation:
        self.evaluations += 1
        return self.comp.evaluate(self.x_base, self.q_base, np.minimum(np.maximum(z, self.lo), self.hi))

    def achieved(self, ev: Evaluation, up_to: int) -> bool:
        for (g, lv), e in zip(self.comp.entries, ev.goal_evals):
            if lv <= up_to and (e.metres > self.tol_position or e.degrees > self.tol_angle):
                return False
        return True

    def step_limit(self, z: np.ndarray, d: np.ndarray, rows: np.ndarray | None = None) -> float:
        """Largest ``alpha`` with ``z + alpha d`` inside the box and the (inactive) rows."""
        return self._ratio(z, d, np.ones(z.size, dtype=bool), rows)[0]

    def _ratio(self, z: np.ndarray, d: np.ndarray, free: np.ndarray,
               inactive_rows: np.ndarray | None) -> tuple[float, int, int]:
        """(alpha_max, blocking variable or -1, blocking row or -1)."""
        alpha, var, row = math.inf, -1, -1
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(free & (d > 0), (self.hi - z) / d, np.where(free & (d < 0), (self.lo - z) / d, np.inf))
            if r.size:
                var = int(np.argmin(r))
                alpha = max(float(r[var]), 0.0)
            if self.A.shape[0]:
                rows = np.arange(self.A.shape[0]) if inactive_rows is None else inactive_rows
                if rows.size:
                    Ad = self.A[rows] @ d
                    rr = np.full(rows.size, np.inf)
                    pos = Ad > 1e-15
                    rr[pos] = (self.b[rows][pos] - self.A[rows][pos] @ z) / Ad[pos]
                    k = int(np.argmin(rr))
                    if rr[k] < alpha:
                        alpha, var, row = max(float(rr[k]), 0.0), -1, int(rows[k])
        if not math.isfinite(alpha):
            var = -1
        return alpha, var, row

    # ----- the metric -------------------------------------------------------------------------------
    def minimise(self, ev: Evaluation, level: int, manifold: Manifold | None,
                 budget: int) -> tuple[Evaluation, str]:
        """Minimise level ``level`` from ``ev`` (holding ``manifold``); (final evaluation, status)."""
        z = ev.z
        F, J = ev.levels[level]
        G, g = float(F @ F), 2.0 * J.T @ F
        at_lo, at_hi = z <= self.lo + BOUND_TOL, z >= self.hi - BOUND_TOL
        fixed = (at_lo & (g > 0)) | (at_hi & (g < 0)) | (self.lo == self.hi)
        side = np.where(at_hi, 1.0, -1.0)
        rows = [int(i) for i in np.flatnonzero(self.A @ z >= self.b - 1e-10)] if self.A.shape[0] else []
        metric = Metric(self.memory)
        small = 0
        end = self.iterations + budget
        held: set[tuple[int, int]] = set()  # added at this iterate with a zero step: not dropped again
        no_rows = np.zeros((0, z.size))
        for _ in range(budget * 4 + 2 * z.size + 8):
            if self.iterations >= end:
                break
            if self.achieved(ev, level):
                return ev, ACHIEVED
            if self.expired():
                return ev, self.stop_status()
            free = ~fixed
            N = manifold.tangent_rows(ev, free) if manifold else no_rows
            C = np.vstack([self.A[rows] * free, N]) if rows else N
            metric.seed(J, free, G)
            d = -metric.project(g, C)
            if rows:  # exactly along the active rows: projected together with the held levels'
                # rows (pinv, rcond 1e-12) ``d`` kept a part across a row that walked 3e-8 out of it
                Ar = self.A[rows] * free
                d = d - Ar.T @ np.linalg.lstsq(Ar @ Ar.T, Ar @ d, rcond=None)[0]
            # multipliers of the working set: drop the most negative when it dominates
            lam_b, lam_r, pg = self._multipliers(g, free, side, rows, N)
            fixed_idx = np.flatnonzero(fixed) if held or lam_b.size else None
            for kind, idx in held:
                if kind == 0:
                    lam_b[np.searchsorted(fixed_idx, idx)] = np.inf
                elif idx in rows:
                    lam_r[rows.index(idx)] = np.inf
            worst_b = int(np.argmin(lam_b)) if lam_b.size else -1
            worst_r = int(np.argmin(lam_r)) if lam_r.size else -1
            lb = float(lam_b[worst_b]) if worst_b >= 0 else 0.0
            lr = float(lam_r[worst_r]) if worst_r >= 0 else 0.0
            dmax = float(np.max(np.abs(d), initial=0.0))
            stationary = dmax <= self.tol_step
            if min(lb, lr) < -1e-12 and (stationary or -min(lb, lr) >= 0.5 * pg):
                if lb <= lr:
                    fixed[int(fixed_idx[worst_b])] = False
                else:
                    rows.pop(worst_r)
                continue
            if stationary:
                return ev, "stationary"
            gd = float(g @ d)
            if gd >= 0.0:
                if not metric.pairs:
                    return ev, "stationary"
                metric.clear()
                continue
            if rows:
                inactive = np.ones(self.A.shape[0], dtype=bool)
                inactive[rows] = False
                inactive = np.flatnonzero(inactive)
            else:
                inactive = self._all_rows
            alpha_max, var, row = self._ratio(z, d, free, inactive)
            if alpha_max <= 1e-15 and (var >= 0 or row >= 0):
                fixed, side, rows = self._add(fixed, side, rows, var, row, d)
                held.add((0, var) if var >= 0 else (1, row))
                continue
            new = self._line_search(ev, z, d, G, gd, min(1.0, alpha_max), level, manifold, free, rows, dmax)
            self.iterations += 1
            if new is None:
                if self.expired():
                    return ev, self.stop_status()
                if not metric.pairs:
                    return ev, "stationary"
                metric.clear()
                continue
            ev_new, alpha = new
            held.clear()
            z_new = ev_new.z
            F_new, J_new = ev_new.levels[level]
            G_new, g_new = float(F_new @ F_new), 2.0 * J_new.T @ F_new
            if ev_new.selection != ev.selection:
                metric.clear()
            else:
                metric.push(z_new - z, g_new - g)
            if alpha >= alpha_max and (var >= 0 or row >= 0):
                fixed, side, rows = self._add(fixed, side, rows, var, row, d)
                if var >= 0:
                    z_new = z_new.copy()
                    z_new[var] = self.hi[var] if d[var] > 0 else self.lo[var]
                    ev_new.z = z_new
            small = small + 1 if _creeping(G, G_new, alpha * dmax) else 0
            ev, z, J, G, g = ev_new, z_new, J_new, G_new, g_new
            self.z = z
            if small >= 3:
                return ev, "stationary"
        return ev, ITERATION_LIMIT

    def restarted(self, ev: Evaluation, level: int, max_iterations: int) -> tuple[Evaluation, str]:
        """:meth:`minimise_bounded` from ``ev`` with restarts out of local minima.

        A first attempt that has not converged within :data:`ATTEMPT_ITERATIONS` (its path through
        the limits got caught; a solve that settles on a compromise sooner, such as a warm start
        near an unreachable target, is not restarted) is followed by the attempts of
        :data:`RESTARTS`, each as long, from the start moved a fraction of the way to the middle of
        the limits and with the damping scaled; the lowest potential wins, and the rest of the
        iterations continue from it at the normal damping. Stops as soon as the goals are
        achieved, the iterations are spent or the time box has passed. Deterministic."""
        start = ev
        best, status = self.minimise_bounded(ev, level, min(max_iterations - self.iterations, ATTEMPT_ITERATIONS))
        if status != ITERATION_LIMIT or self.iterations >= max_iterations:
            return best, status  # achieved, settled (a compromise), out of time or of iterations
        middle = np.where(np.isfinite(self.lo + self.hi), 0.5 * (self.lo + self.hi), start.z)
        for toward, scale in RESTARTS + ((None, 1.0),):
            left = max_iterations - self.iterations
            if left <= 0 or self.expired():
                break
            self.damping = scale
            if toward is None:  # the rest of the iterations from the best attempt
                origin = best
            elif toward:
                origin = self.evaluate(self._feasible(start.z + toward * (middle - start.z)))
            else:
                origin = start
            ev, st = self.minimise_bounded(origin, level, left if toward is None else min(left, ATTEMPT_ITERATIONS))
            if st == ACHIEVED or ev.potential(level) < best.potential(level):
                best, status = ev, st
            if st in (ACHIEVED, TIME_LIMIT):
                status = st
                break
        self.damping = 1.0
        if status not in (ACHIEVED, TIME_LIMIT):
            if self.expired():
                status = self.stop_status()
            else:
                status = ITERATION_LIMIT if self.iterations >= max_iterations else "stationary"
        self.z = best.z
        return best, status

    def minimise_bounded(self, ev: Evaluation, level: int, budget: int) -> tuple[Evaluation, str]:
        """Minimise level ``level`` (no higher level to hold) by bounded Gauss-Newton steps.

        Each iteration solves ``min |F + J d|^2 + lambda |d|^2`` over the box and the rows
        (:func:`.bounded_step.bounded_step`, many limits bound or freed in one step), then an Armijo
        backtracking search along ``d`` (the segment stays feasible: the feasible set is convex).
        ``lambda = GN_DAMPING_FLOOR + GN_DAMPING |F|`` in scaled variables (stiffness still decides
        among redundant solutions), raised tenfold after a failed search and relaxed after full steps.
        """
        z = ev.z
        F, J = ev.levels[level]
        G = float(F @ F)
        end = self.iterations + budget
        n = z.size
        small, boost = 0, 1.0
        rows = self.A.shape[0] > 0
        held = None
        while self.iterations < end:
            if self.achieved(ev, level):
                return ev, ACHIEVED
            if self.expired():
                return ev, self.stop_status()
            lam = max((GN_DAMPING_FLOOR + GN_DAMPING * math.sqrt(G)) * boost * self.damping,
                      CONDITION * float(np.vdot(J, J)))  # the QP's m x m factor stays positive definite
            c = J.T @ F
            d, held, _ = bounded_step(J, lam, c, self.lo - z, self.hi - z, self.A if rows else None,
                                      self.b - self.A @ z if rows else None, held=held)
            dmax = float(np.max(np.abs(d), initial=0.0))
            if dmax <= self.tol_step:
                return ev, "stationary"
            gd = 2.0 * float(c @ d)
            if gd >= 0.0:
                return ev, "stationary"
            new = self._line_search(ev, z, d, G, gd, 1.0, level, None, None, [], dmax)
            self.iterations += 1
            if new is None:
                if self.expired():
                    return ev, self.stop_status()
                if boost >= 1e6:
                    return ev, "stationary"
                boost *= 10.0
                continue
            ev_new, alpha = new
            boost = max(1.0, boost / 10.0) if alpha >= 1.0 else boost * 2.0
            F, J = ev_new.levels[level]
            G_new = float(F @ F)
            small = small + 1 if _creeping(G, G_new, alpha * dmax) else 0
            ev, z, G = ev_new, ev_new.z, G_new
            self.z = z
            if small >= 3:
                return ev, "stationary"
        return ev, ITERATION_LIMIT

    def _multipliers(self, g: np.ndarray, free: np.ndarray, side: np.ndarray, rows: list[int],
                     N: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(bound multipliers, row multipliers, inf-norm of the projected gradient)."""
        E = np.vstack([self.A[rows] * free, N]) if rows else N
        r = g
        lam_r = _EMPTY
        if E.shape[0]:
            lam = np.linalg.lstsq(E[:, free].T, -g[free], rcond=None)[0]
            r = g + E.T @ lam
            lam_r = lam[:len(rows)]
        fixed = ~free
        lam_b = -side[fixed] * r[fixed]
        pg = float(np.max(np.abs(r[free] if fixed.any() else r), initial=0.0))
        return lam_b, lam_r, pg

    @staticmethod
    def _add(fixed: np.ndarray, side: np.ndarray, rows: list[int], var: int, row: int,
             d: np.ndarray) -> tuple[np.ndarray, np.ndarray, list[int]]:
        """Add the blocking bound ``var`` or row ``row`` to the working set."""
        if var >= 0:
            fixed, side = fixed.copy(), side.copy()
            fixed[var] = True
            side[var] = 1.0 if d[var] > 0 else -1.0
        else:
            rows = rows + [row]
        return fixed, side, rows

    def _line_search(self, ev: Evaluation, z: np.ndarray, d: np.ndarray, G: float, gd: float,
                     alpha: float, level: int, manifold: Manifold | None, free: np.ndarray,
                     rows: list[int], dmax: float) -> tuple[Evaluation, float] | None:
        """Armijo backtracking on ``(0, alpha]``; with a manifold each trial is restored first.

        ``dmax`` is ``max |d|``.
        """
        active_rows = (self.A[rows] * free if rows else np.zeros((0, z.size))) if manifold is not None else None
        restorations = RESTORE_EVALUATIONS  # restoration evaluations this iteration may spend
        for _ in range(30):
            if self.expired():
                return None
            trial: Evaluation | None = self.evaluate(z + alpha * d)
            if manifold is not None:
                if restorations <= 0:
                    return None
                before = self.evaluations
                trial = manifold.restore(trial, free, lambda zz, dz: self._ratio(zz, dz, free, None)[0],
                                         self.evaluate, active_rows, max_steps=min(6, restorations),
                                         expired=self.expired)
                restorations -= self.evaluations - before
            if trial is not None:
                Ft = trial.levels[level][0]
                Gt = float(Ft @ Ft)
                finite = math.isfinite(Gt)
                if finite and Gt <= G + C1 * alpha * gd:
                    return trial, alpha
                denom = 2.0 * (Gt - G - gd * alpha) if finite else 0.0
                a_q = -gd * alpha * alpha / denom if denom > 0 else 0.1 * alpha
                alpha = min(max(a_q, 0.1 * alpha), 0.5 * alpha)
            else:
                alpha *= 0.25
            if alpha * dmax < 1e-14:
                return None
        return None

    # ----- result -----------------------------------------------------------------------------------
    def result(self, ev: Evaluation, status: str, iterations: int, analytic: bool) -> Result:
        self.z = ev.z
        reports = []
        for (g, lv), e in zip(self.comp.entries, ev.goal_evals):
            ok = e.metres <= self.tol_position and e.degrees <= self.tol_angle
            reports.append(GoalReport(g.name, lv, float(e.f @ e.f), e.metres, e.degrees, ok))
        total = float(sum(g.weight * r.potential for (g, _), r in zip(self.comp.entries, reports)))
        return Result(status, iterations, self.evaluations, total, reports, ev.q.copy(), analytic)


class Metric:
    """Limited-memory BFGS inverse metric seeded with the current Gauss-Newton inverse.

    ``H0 = (2 J^T J + mu I)^-1`` on the free variables (zero on fixed ones), applied by Woodbury in
    O(n m); the last ``memory`` steps ``(s, y)`` update it by BFGS (two-loop recursion). Projection on
    active rows ``C`` (Rosen/Goldfarb): ``Hp = H - H C^T (C H C^T)^+ C H``.

    The pairs restricted to the free variables, their ``s.y`` and the curvature test are worked out
    once per :meth:`seed` (the first :meth:`apply` after it), not on every application.
    """

    def __init__(self, memory: int) -> None:
        self.memory = memory
        self.pairs: list[tuple[np.ndarray, np.ndarray]] = []
        self._dots: list[tuple[float, float, float]] = []  # (s.y, |s|, |y|) of each pair, unmasked
        self._used: list[tuple[np.ndarray, np.ndarray, float]] | None = None
        self.all_free = False

    def clear(self) -> None:
        self.pairs.clear()
        self._dots.clear()
        self._used = None

    def push(self, s: np.ndarray, y: np.ndarray) -> None:
        self.pairs.append((s, y))
        self._dots.append((float(s @ y), math.sqrt(float(s @ s)), math.sqrt(float(y @ y))))
        del self.pairs[:-self.memory], self._dots[:-self.memory]
        self._used = None

    def seed(self, J: np.ndarray, free: np.ndarray, G: float) -> None:
        all_free = bool(free.all())
        if not (all_free and self.all_free):  # the free pairs stay valid while nothing is fixed
            self._used = None
        self.free, self.all_free = free, all_free
        self.Jf = J if all_free else J * free
        self.mu = MU_SCALE * math.sqrt(max(G, 0.0)) + MU_FLOOR
        M = self.Jf @ self.Jf.T
        M.flat[::M.shape[0] + 1] += 0.5 * self.mu
        self.K = _inv(M)

    def _pairs(self) -> list[tuple[np.ndarray, np.ndarray, float]]:
        """Newest first: the pairs on the free variables that pass the curvature test, with ``s.y``."""
        used = []
        free, all_free = self.free, self.all_free
        for (s, y), (sy, ns, ny) in zip(reversed(self.pairs), reversed(self._dots)):
            if not all_free:
                s, y = s * free, y * free
                sy = float(s @ y)
                if sy <= 0.0:
                    continue
                ns, ny = math.sqrt(float(s @ s)), math.sqrt(float(y @ y))
            if sy <= 1e-12 * ns * ny or sy <= 0.0:
                continue
            used.append((s, y, sy))
        self._used = used
        return used

    def _h0(self, V: np.ndarray) -> np.ndarray:
        """``H0 @ V`` for ``V`` already zero on the fixed variables."""
        Jf = self.Jf
        return (V - Jf.T @ (self.K @ (Jf @ V))) / self.mu

    def apply(self, V: np.ndarray) -> np.ndarray:
        """``H @ V`` for a vector or an (n, k) block (two-loop recursion)."""
        used = self._pairs() if self._used is None else self._used
        if V.ndim == 2:
            q = V if self.all_free else V * self.free[:, None]
            stack = []
            for s, y, sy in used:
                a = (s @ q) / sy
                q = q - np.multiply.outer(y, a)
                stack.append(a)
            r = self._h0(q)
            for (s, y, sy), a in zip(reversed(used), reversed(stack)):
                b = (y @ r) / sy
                r = r + np.multiply.outer(s, a - b)
            return r
        q = V if self.all_free else V * self.free
        coef = []
        for s, y, sy in used:
            a = float(s @ q) / sy
            q = q - a * y
            coef.append(a)
        r = self._h0(q)
        for (s, y, sy), a in zip(reversed(used), reversed(coef)):
            b = float(y @ r) / sy
            r = r + (a - b) * s
        return r

    def project(self, g: np.ndarray, C: np.ndarray) -> np.ndarray:
        """Projected ``H g`` with the rows ``C`` held (``C d = 0``)."""
        Hg = self.apply(g)
        if not C.shape[0]:
            return Hg
        HC = self.apply(C.T)
        return Hg - HC @ (np.linalg.pinv(C @ HC, rcond=1e-12) @ (C @ Hg))
