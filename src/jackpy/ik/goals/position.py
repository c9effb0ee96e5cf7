"""Position goal (3.9-3.10): the site's origin ``r`` at the point ``p``; ``P = |p - r|^2``."""

from __future__ import annotations

import math

import numpy as np

from jackpy.ik.goals.base import Chain, Context, GoalEval, SiteGoal, point3


class Position(SiteGoal):
    """Bring the origin of ``site`` to ``target`` (world point, metres; a 4x4 gives its origin)."""

    kind = "position"
    targets = ("target",)

    def __init__(self, site: str, target: np.ndarray, chain: Chain = None, weight: float = 1.0,
                 name: str | None = None) -> None:
        super().__init__(site, chain, weight, name)
        self.target = point3(target)

    def evaluate(self, ctx: Context) -> GoalEval:
        r = ctx.site(self.seg, self.location)[:3, 3]
        f = r - self.target
        return GoalEval(f, ctx.point_jacobian(self.seg, r), metres=math.sqrt(float(f @ f)))

    def set_frame(self, frame: np.ndarray) -> None:
        """The target is the frame's origin."""
        self.target = point3(frame)
