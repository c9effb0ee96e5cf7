"""Point reach: can this hand reach this point, and if not, how far short is it (IK, book §3.2).

A position goal on the hand's reference site is solved over the arm chain (from the clavicle: the
torso, pelvis and feet stay where they are, so the feet stay planted) or over a longer chain given
by ``start_joint`` (e.g. the lowest spine joint to let the torso bend). The IK ends at the target
or, when the target is out of reach, at the constrained minimum of the distance: the arm stretched
towards it (book §3.4.1: a target outside the reach ends on the envelope). The remaining distance is
the shortfall. Stepping is not modelled here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy import ik
from jackpy.analysis.parts import figure_parts
from jackpy.peabody.model import Figure

#: a hand within this distance of the target has reached it (metres)
REACH_TOLERANCE = 0.005


@dataclass
class PointReach:
    """Outcome of one reach: ``shortfall`` metres between the hand and ``target`` after the solve,
    ``reached`` when that is within the tolerance, the hand's final world ``position`` and the
    posture ``q`` that got there (IK ``status``)."""

    target: np.ndarray
    reached: bool
    shortfall: float
    position: np.ndarray
    q: np.ndarray
    status: str

    def describe(self) -> str:
        """One line for a report: ``reached (2 mm)`` or ``short by ~10 cm``."""
        if self.reached:
            return f"reached ({self.shortfall * 1e3:.0f} mm)"
        return f"short by ~{self.shortfall * 100:.0f} cm"


def point_reach(figure: Figure, target: np.ndarray, hand: str = "right", start_joint: str | None = None,
                tolerance: float = REACH_TOLERANCE, keep_posture: bool = False,
                max_iterations: int = 300) -> PointReach:
    """Reach for world point ``target`` (metres) with ``hand`` (``"right"``/``"left"``) from the
    figure's current posture; the chain starts at ``start_joint`` (default: the arm's clavicle).
    The figure's posture is restored afterwards unless ``keep_posture``."""
    h = figure_parts(figure).hands[hand]
    target = np.asarray(target, dtype=float).reshape(3)
    q0 = figure.q
    problem = ik.Problem(figure)
    problem.add(ik.Position(f"{h.segment}.{h.site}", target, chain=start_joint or h.start_joint))
    result = ik.solve(problem, max_iterations=max_iterations, tol_position=tolerance / 5)
    position = figure.site_world(h.segment, h.site)[:3, 3].copy()
    shortfall = float(np.linalg.norm(position - target))
    q = figure.q
    if not keep_posture:
        figure.q = q0
    return PointReach(target, shortfall <= tolerance, shortfall, position, q, result.status)
