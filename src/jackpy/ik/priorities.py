"""Strict priority levels: a lexicographic solve with Rosen's projection onto the higher levels.

Level 0 is solved first, alone. Level ``k`` is then minimised *on the manifold where the higher
levels keep the residual they reached*, the nonlinear form of Rosen's gradient projection:

1. **Tangent step.** The search direction is projected onto the null space of the higher levels'
   stacked Jacobian ``Jh`` (as well as of the active joint limits): ``Jh d = 0``, so to first order
   the step does not disturb them. Rows are taken from an SVD of ``Jh`` (rank-revealing, so redundant
   or singular higher-level rows do no harm).
2. **Restoration.** After each trial step, Gauss-Newton corrections ``dz = -Jh^+ Fh`` on the free
   variables (clipped to the limits) bring the higher levels back to the residual they had, to
   ``1e-12`` in potential (1 micrometre), before the trial is judged by the Armijo test on level ``k``.

So a lower level is satisfied as well as it can be without disturbing the higher ones: with the feet
at level 0, an unreachable hand at level 1 cannot move them. When a higher level is itself
unreachable it is held at the least-squares compromise it reached. Goals on one level trade off by
weight as in the book; one level (the default) is exactly the book's weighted sum.

That is the book-step form (:meth:`Manifold.tangent_rows` and :meth:`Manifold.restore`, used by the
projected BFGS of ``step="bfgs"``). The default, :meth:`Manifold.minimise`, takes the same two
moves with the box-bounded Gauss-Newton step of :mod:`.bounded_step`, at bounded cost:

- **Tangent step over the box.** ``min |Fk + Jk d|^2 + HOLD_WEIGHT^2 |Jh d|^2 + lambda |d|^2`` over
  the box and the group rows: the penalty keeps ``Jh d`` near zero (the null-space step as its
  limit), and the box QP binds or frees any number of limits at once. Bounds that the higher levels
  press against (at the bound, their gradient pointing out) are frozen: freeing one would worsen
  them to first order.
- **Restoration over the box.** A trial whose higher levels rose above their held value (plus
  ``HOLD_TOL`` absolute and ``RESTORE_REL`` relative) is pulled back by bounded Gauss-Newton steps
  on ``Fh`` alone; only restored trials are judged (Armijo on level ``k``) and accepted, so every
  accepted iterate is feasible and never worse for the higher levels.
- **Bounded work.** One iteration spends at most ``LINE_TRIALS`` trial evaluations and
  ``RESTORE_EVALUATIONS`` restoration evaluations (counted, not timed); a failed search raises the
  damping and counts as an iteration, so ``max_iterations`` bounds the evaluations. No evaluation
  starts once the solve's time box or evaluation budget has run out: the last accepted iterate is
  returned with the stop status (``"time_limit"`` or ``"iteration_limit"``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Protocol

import numpy as np

from jackpy.ik.bounded_step import bounded_step
from jackpy.ik.problem import Evaluation
from jackpy.ik.result import ACHIEVED, ITERATION_LIMIT, TIME_LIMIT

#: restoration accepts a higher-level potential this far (absolute) above the held value
RESTORE_TOL = 1e-12
#: ... and this far relative to it (an unreachable higher level held at its compromise)
RESTORE_REL = 1e-6
#: with the bounded step each held level may rise this far (absolute; 10 micrometres of residual,
#: a tenth of the default ``tol_position``) above its held value (plus ``RESTORE_REL``): most trial
#: steps then need no restoration evaluation (at ``RESTORE_TOL`` nearly every one did)
HOLD_TOL = 1e-10
#: restoration evaluations one iteration of a lower level may spend over all its line-search trials
RESTORE_EVALUATIONS = 12
#: ... with the bounded step (:meth:`Manifold.minimise`)
BOUNDED_RESTORE_EVALUATIONS = 6
#: trial points (evaluations before restoration) of one iteration's line search (bounded step)
LINE_TRIALS = 4
#: a level ends as stationary when its potential fell by less than ``STALL_REL`` of itself over the
#: last ``STALL_ITERATIONS`` iterations (it creeps along the held levels' curved manifold)
STALL_REL, STALL_ITERATIONS = 1e-3, 5
#: weight of the higher levels' linearised residual ``Jh d`` in the tangent step's model
HOLD_WEIGHT = 300.0
#: Armijo constant of the line search on the lower level
ARMIJO = 1e-4
#: damping of the tangent step ``lambda = (DAMPING_FLOOR + DAMPING |Fk|) * boost`` (scaled units)
DAMPING, DAMPING_FLOOR = 0.01, 1e-4
#: the least damping relative to ``|J|_F^2`` (the QP's m x m factor stays positive definite in floating point)
CONDITION = 1e-12
#: the tangent step's damping after a full step (divided) and after a shortened one (multiplied)
RELAX, TIGHTEN = 2.0, 4.0
#: damping of a restoration step: ``RESTORE_DAMPING_FLOOR (1 + |Jh|_F^2) + RESTORE_DAMPING |Fh|``
RESTORE_DAMPING, RESTORE_DAMPING_FLOOR = 1e-3, 1e-8


class SolveState(Protocol):
    """What :meth:`Manifold.minimise` needs of a running solve (``solver._Run``)."""

    lo: np.ndarray
    hi: np.ndarray
    A: np.ndarray
    b: np.ndarray
    z: np.ndarray
    iterations: int
    tol_step: float

    def evaluate(self, z: np.ndarray) -> Evaluation: ...

    def expired(self) -> bool: ...

    def stop_status(self) -> str: ...

    def achieved(self, ev: Evaluation, up_to: int) -> bool: ...


def minimise_levels(run: SolveState, ev: Evaluation, levels: list[int], budget: int) -> tuple[Evaluation, str]:
    """The lexicographic solve with the bounded step: each level in turn by :meth:`Manifold.minimise`
    holding the levels before it (level 0 holds nothing); at most ``budget`` iterations in all.
    (final evaluation, status of the last level run); stops at the iteration cap or the time box."""
    status = ACHIEVED
    end = run.iterations + budget
    for i, level in enumerate(levels):
        hi = levels[:i]
        per_level = {k: ev.potential(k) for k in hi}
        manifold = Manifold(hi, float(sum(per_level.values())), per_level)
        ev, status = manifold.minimise(run, ev, level, end - run.iterations)
        if status in (ITERATION_LIMIT, TIME_LIMIT):
            break
    return ev, status


class Manifold:
    """The higher levels ``hi`` held during the solve of a lower level."""

    def __init__(self, hi: list[int], held: float, per_level: dict[int, float] | None = None) -> None:
        self.hi = hi
        self.held = held
        #: each held level's own potential to keep (the bounded step holds each level, not only their sum)
        self.per_level = per_level if per_level is not None else {}
        #: restoration evaluations spent, and the most spent in one iteration (bounded step)
        self.restorations = 0
        self.most_restorations = 0

    def bound(self) -> float:
        """The largest higher-level potential an accepted iterate may have."""
        return self.held + RESTORE_TOL + RESTORE_REL * self.held

    def holds(self, ev: Evaluation) -> bool:
        """Whether ``ev`` keeps every held level within its bound (the sum's without ``per_level``)."""
        if not self.per_level:
            return self.potential(ev) <= self.bound()
        return all(ev.potential(k) <= v + HOLD_TOL + RESTORE_REL * v for k, v in self.per_level.items())

    def potential(self, ev: Evaluation) -> float:
        Fh, _ = self.stacked(ev)
        return float(Fh @ Fh)

    def stacked(self, ev: Evaluation) -> tuple[np.ndarray, np.ndarray]:
        """The held levels' residuals and Jacobian (no rows when nothing is held)."""
        if not self.hi:
            return np.zeros(0), np.zeros((0, ev.z.size))
        return ev.stacked(self.hi)

    def tangent_rows(self, ev: Evaluation, free: np.ndarray) -> np.ndarray:
        """Orthonormal rows spanning ``Jh`` on the free variables (fixed columns zero)."""
        _, Jh = ev.stacked(self.hi)
        Jf = Jh * free
        if not Jf.size:
            return Jf
        _, s, vt = np.linalg.svd(Jf, full_matrices=False)
        keep = s > 1e-9 * max(s[0], 1e-300) if s.size else s > 0
        return vt[keep]

    def restore(self, ev: Evaluation, free: np.ndarray, step_limit: Callable[[np.ndarray, np.ndarray], float],
                evaluate: Callable[[np.ndarray], Evaluation], rows: np.ndarray,
                max_steps: int = 6, expired: Callable[[], bool] | None = None) -> Evaluation | None:
        """Gauss-Newton back onto the held manifold from ``ev``; ``None`` if it cannot get there.

        ``step_limit(z, dz)`` is the largest feasible fraction of ``dz``; ``rows`` are active linear
        limits the correction must not leave; at most ``max_steps`` evaluations, none once
        ``expired()`` (the solve's time box) is true.
        """
        for _ in range(max_steps):
            if expired is not None and expired():
                break
            Fh, Jh = ev.stacked(self.hi)
            if Fh @ Fh <= self.held + RESTORE_TOL:
                return ev
            Jf = Jh * free
            JJ = Jf @ Jf.T
            lam = 1e-12 * max(np.trace(JJ), 1e-300)
            dz = -Jf.T @ np.linalg.solve(JJ + lam * np.eye(JJ.shape[0]), Fh)
            if rows.size:
                dz -= rows.T @ np.linalg.lstsq(rows @ rows.T, rows @ dz, rcond=None)[0]
            beta = min(1.0, step_limit(ev.z, dz))
            if beta <= 0.0 or not np.all(np.isfinite(dz)):
                return None
            ev = evaluate(ev.z + beta * dz)
        Fh, _ = ev.stacked(self.hi)
        return ev if Fh @ Fh <= self.held + RESTORE_TOL else None

    # ----- the bounded step (default) ------------------------------------------------------------
    def minimise(self, run: SolveState, ev: Evaluation, level: int, budget: int) -> tuple[Evaluation, str]:
        """Minimise level ``level`` from ``ev`` holding the higher levels, by bounded tangent steps
        and bounded restoration; (final evaluation, status) as ``solver._Run.minimise_bounded``.

        At most ``budget`` iterations, each at most ``LINE_TRIALS + RESTORE_EVALUATIONS``
        evaluations; none starts once ``run.expired()``.
        """
        z = ev.z
        F, J = ev.levels[level]
        G = float(F @ F)
        end = run.iterations + budget
        rows = run.A.shape[0] > 0
        boost = 1.0
        history = [G]
        held = None
        while run.iterations < end:
            if run.achieved(ev, level):
                return ev, ACHIEVED
            if run.expired():
                return ev, run.stop_status()
            Fh, Jh = self.stacked(ev)
            if self.hi and run.achieved(ev, self.hi[-1]):
                # the held levels are met: their gradient is a residual inside the tolerance, not a
                # compromise's multiplier, and restoration keeps them; freezing bounds on it would
                # lock joints for nothing (a knee at its limit while the hand reached 40 cm down)
                lower, upper = run.lo - z, run.hi - z
            else:
                lower, upper = self._frozen(run, z, 2.0 * (Jh.T @ Fh))
            c = J.T @ F
            Jm = np.vstack([HOLD_WEIGHT * Jh, J]) if self.hi else J
            lam = max((DAMPING_FLOOR + DAMPING * math.sqrt(G)) * boost, CONDITION * float(np.sum(Jm * Jm)))
            d, held, _ = bounded_step(Jm, lam, c, lower, upper,
                                      run.A if rows else None, np.maximum(run.b - run.A @ z, 0.0) if rows else None, held=held)
            dmax = float(np.max(np.abs(d), initial=0.0))
            gd = 2.0 * float(c @ d)
            if dmax <= run.tol_step or gd >= 0.0 or not math.isfinite(gd):
                return ev, "stationary"
            new = self._line_search(run, ev, d, G, gd, level, dmax)
            run.iterations += 1
            if new is None:
                if run.expired():
                    return ev, run.stop_status()
                if boost >= 1e2:
                    return ev, "stationary"
                boost *= 10.0
                continue
            ev_new, alpha = new
            boost = max(1.0, boost / RELAX) if alpha >= 1.0 else boost * TIGHTEN
            F, J = ev_new.levels[level]
            ev, z, G = ev_new, ev_new.z, float(F @ F)
            run.z = z
            history.append(G)
            if len(history) > STALL_ITERATIONS and history[-1 - STALL_ITERATIONS] - G <= STALL_REL * G + 1e-18:
                return ev, "stationary"
        return ev, ITERATION_LIMIT

    @staticmethod
    def _frozen(run: SolveState, z: np.ndarray, gh: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The step's box ``lo - z <= d <= hi - z``, closed (``d_i = 0``) on the bounds the higher
        levels press against: at the bound with their gradient ``gh`` pointing out of the box."""
        lower, upper = run.lo - z, run.hi - z
        eps = 1e-9 * (1.0 + float(np.max(np.abs(gh), initial=0.0)))
        press = ((lower >= -1e-12) & (gh > eps)) | ((upper <= 1e-12) & (gh < -eps))
        if press.any():
            lower, upper = np.where(press, 0.0, lower), np.where(press, 0.0, upper)
        return lower, upper

    def _line_search(self, run: SolveState, ev: Evaluation, d: np.ndarray, G: float, gd: float,
                     level: int, dmax: float) -> tuple[Evaluation, float] | None:
        """Armijo backtracking from ``alpha = 1``, each trial restored before it is judged; at most
        ``LINE_TRIALS`` trials and ``RESTORE_EVALUATIONS`` restoration evaluations."""
        alpha, left = 1.0, BOUNDED_RESTORE_EVALUATIONS
        spent = 0
        try:
            for _ in range(LINE_TRIALS):
                if run.expired():
                    return None
                trial = run.evaluate(ev.z + alpha * d)
                before = left
                trial, left = self._restore_bounded(run, trial, left, alpha * dmax)
                spent += before - left
                if trial is not None:
                    Ft = trial.levels[level][0]
                    Gt = float(Ft @ Ft)
                    if math.isfinite(Gt) and Gt <= G + ARMIJO * alpha * gd:
                        return trial, alpha
                    denom = 2.0 * (Gt - G - gd * alpha) if math.isfinite(Gt) else 0.0
                    a_q = -gd * alpha * alpha / denom if denom > 0 else 0.1 * alpha
                    alpha = min(max(a_q, 0.1 * alpha), 0.5 * alpha)
                else:
                    alpha *= 0.25
                if alpha * dmax < 1e-14:
                    return None
            return None
        finally:
            self.restorations += spent
            self.most_restorations = max(self.most_restorations, spent)

    def _restore_bounded(self, run: SolveState, ev: Evaluation, left: int,
                         reach: float) -> tuple[Evaluation | None, int]:
        """Bounded Gauss-Newton steps on the higher levels alone (over the box and the rows) until
        they are within their bounds (:meth:`holds`); (restored evaluation or ``None``, evaluations left).
        A correction larger than ``reach`` (the trial step's largest move) fails: the trial left the
        region where the higher levels' linearisation holds, and a shorter trial is tried."""
        rows = run.A.shape[0] > 0
        while True:
            if self.holds(ev):
                return ev, left
            Fh, Jh = self.stacked(ev)
            Gh = float(Fh @ Fh)
            if left <= 0 or not math.isfinite(Gh):
                return None, left
            z = ev.z
            lam = RESTORE_DAMPING_FLOOR * (1.0 + float(np.sum(Jh * Jh))) + RESTORE_DAMPING * math.sqrt(Gh)
            e, _, _ = bounded_step(Jh, lam, Jh.T @ Fh, run.lo - z, run.hi - z, run.A if rows else None,
                                   np.maximum(run.b - run.A @ z, 0.0) if rows else None)
            size = float(np.max(np.abs(e), initial=0.0))
            if not math.isfinite(size) or size <= 1e-15 or size > reach or run.expired():
                return None, left
            ev = run.evaluate(z + e)
            left -= 1
