"""What a solve returns: status, counts, final potential and each goal's residual."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

#: every goal within tolerance
ACHIEVED = "achieved"
#: a constrained minimum (KKT point) with some goal unmet: the closest reachable posture
UNREACHABLE = "unreachable"
#: the iteration cap was hit first (warm-start again next frame)
ITERATION_LIMIT = "iteration_limit"
#: the time budget ran out: the posture is the best feasible iterate reached (warm-start again)
TIME_LIMIT = "time_limit"


@dataclass
class GoalReport:
    """One goal's state after the solve: unweighted potential, error in metres and degrees."""

    name: str
    level: int
    potential: float
    metres: float
    degrees: float
    achieved: bool


@dataclass
class Result:
    """Outcome of :func:`jackpy.ik.solve`. ``q`` are the joint displacements (radians/metres)."""

    status: str
    iterations: int
    evaluations: int
    potential: float
    goals: list[GoalReport] = field(default_factory=list)
    q: np.ndarray = field(default_factory=lambda: np.zeros(0))
    analytic: bool = False

    @property
    def converged(self) -> bool:
        """True at a solution or a constrained minimum; False when stopped by the iteration cap or
        the time budget."""
        return self.status not in (ITERATION_LIMIT, TIME_LIMIT)

    @property
    def achieved(self) -> bool:
        return self.status == ACHIEVED

    def __str__(self) -> str:
        head = (f"{self.status}: {self.iterations} iterations, {self.evaluations} evaluations, "
                f"potential {self.potential:.3g}")
        lines = [head]
        for g in self.goals:
            note = "" if g.achieved else "  (not achieved)"
            lines.append(f"  [{g.level}] {g.name}: {g.metres * 1e3:.3f} mm, {g.degrees:.3f} deg{note}")
        return "\n".join(lines)
