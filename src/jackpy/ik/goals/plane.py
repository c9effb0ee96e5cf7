"""Plane goal (3.21-3.22): the site origin on the plane through ``p`` with normal ``nu``; ``P = (nu.(p - r))^2``."""

from __future__ import annotations

import numpy as np

from jackpy.ik.goals.base import Chain, Context, GoalEval, SiteGoal, point3, unit


class Plane(SiteGoal):
    """Keep the origin of ``site`` on the world plane through ``point`` with ``normal`` (an equality)."""

    kind = "plane"
    targets = ("point", "normal")

    def __init__(self, site: str, point: np.ndarray, normal: np.ndarray, chain: Chain = None,
                 weight: float = 1.0, name: str | None = None) -> None:
        super().__init__(site, chain, weight, name)
        self.point = point3(point)
        self.normal = unit(normal, "plane normal")

    def evaluate(self, ctx: Context) -> GoalEval:
        r = ctx.site(self.seg, self.location)[:3, 3]
        s = float(self.normal @ (r - self.point))
        J = self.normal @ ctx.point_jacobian(self.seg, r)
        return GoalEval(np.array([s]), J[None, :], metres=abs(s))

    def set_frame(self, frame: np.ndarray) -> None:
        """Through the frame's origin, normal along the frame's y axis."""
        f = np.asarray(frame, dtype=float)
        self.point = point3(f)
        self.normal = unit(f[:3, 1], "plane normal")

    @classmethod
    def placement(cls, site_world: np.ndarray, params: dict) -> np.ndarray:
        """Through the site, normal world up."""
        out = np.eye(4)
        out[:3, 3] = np.asarray(site_world, dtype=float)[:3, 3]
        return out
