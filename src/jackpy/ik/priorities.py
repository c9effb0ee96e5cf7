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
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from jackpy.ik.problem import Evaluation

#: restoration accepts a higher-level potential this far (absolute) above the held value
RESTORE_TOL = 1e-12
#: restoration evaluations one iteration of a lower level may spend over all its line-search trials
RESTORE_EVALUATIONS = 12


class Manifold:
    """The higher levels ``hi`` held during the solve of a lower level."""

    def __init__(self, hi: list[int], held: float) -> None:
        self.hi = hi
        self.held = held

    def potential(self, ev: Evaluation) -> float:
        Fh, _ = ev.stacked(self.hi)
        return float(Fh @ Fh)

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
