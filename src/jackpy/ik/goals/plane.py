"""Plane goal (3.21-3.22): the site origin on the plane through ``p`` with normal ``nu``; ``P = (nu.(p - r))^2``."""

from __future__ import annotations

import numpy as np

from jackpy.ik.goals.base import Chain, Context, GoalEval, SiteGoal, point3, unit


class Plane(SiteGoal):
    """Keep the origin of ``site`` on the world plane through ``point`` with ``normal`` (an equality)."""

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
