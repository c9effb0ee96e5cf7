"""Line goal (3.19-3.20): the site origin on the line ``p + t nu``; ``P = |(I - nu nu^T)(p - r)|^2``."""

from __future__ import annotations

import numpy as np

from jackpy.ik.goals.base import Chain, Context, GoalEval, SiteGoal, point3, unit


class Line(SiteGoal):
    """Keep the origin of ``site`` on the world line through ``point`` along ``direction``."""

    kind = "line"
    targets = ("point", "direction")

    def __init__(self, site: str, point: np.ndarray, direction: np.ndarray, chain: Chain = None,
                 weight: float = 1.0, name: str | None = None) -> None:
        super().__init__(site, chain, weight, name)
        self.point = point3(point)
        self.direction = unit(direction, "line direction")

    def evaluate(self, ctx: Context) -> GoalEval:
        r = ctx.site(self.seg, self.location)[:3, 3]
        P = np.eye(3) - np.outer(self.direction, self.direction)
        f = P @ (r - self.point)
        return GoalEval(f, P @ ctx.point_jacobian(self.seg, r), metres=float(np.linalg.norm(f)))

    def set_frame(self, frame: np.ndarray) -> None:
        """Through the frame's origin along the frame's y axis."""
        f = np.asarray(frame, dtype=float)
        self.point = point3(f)
        self.direction = unit(f[:3, 1], "line direction")

    @classmethod
    def placement(cls, site_world: np.ndarray, params: dict) -> np.ndarray:
        """Through the site, vertical."""
        out = np.eye(4)
        out[:3, 3] = np.asarray(site_world, dtype=float)[:3, 3]
        return out
