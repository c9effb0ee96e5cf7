"""Half-space goal (3.23-3.24): the site origin on the side of a plane that ``nu`` points into.

``P = 0`` when ``(p - r).nu < 0`` (inside), else ``((p - r).nu)^2``: C1 across the plane, no pull
inside (an inequality).
"""

from __future__ import annotations

import numpy as np

from jackpy.ik.goals.base import Chain, Context, GoalEval, SiteGoal, point3, unit


class HalfSpace(SiteGoal):
    """Keep the origin of ``site`` where ``normal . (r - point) >= 0`` (world, metres)."""

    kind = "half-space"
    targets = ("point", "normal")

    def __init__(self, site: str, point: np.ndarray, normal: np.ndarray, chain: Chain = None,
                 weight: float = 1.0, name: str | None = None) -> None:
        super().__init__(site, chain, weight, name)
        self.point = point3(point)
        self.normal = unit(normal, "half-space normal")

    def evaluate(self, ctx: Context) -> GoalEval:
        r = ctx.site(self.seg, self.location)[:3, 3]
        depth = float(self.normal @ (self.point - r))  # > 0: outside the allowed side
        if depth <= 0.0:
            return GoalEval(np.zeros(1), np.zeros((1, ctx.cols.size)))
        J = -(self.normal @ ctx.point_jacobian(self.seg, r))
        return GoalEval(np.array([depth]), J[None, :], metres=depth)

    def set_frame(self, frame: np.ndarray) -> None:
        """Through the frame's origin, normal along the frame's y axis."""
        f = np.asarray(frame, dtype=float)
        self.point = point3(f)
        self.normal = unit(f[:3, 1], "half-space normal")

    @classmethod
    def placement(cls, site_world: np.ndarray, params: dict) -> np.ndarray:
        """Through the site, normal world up."""
        out = np.eye(4)
        out[:3, 3] = np.asarray(site_world, dtype=float)[:3, 3]
        return out
