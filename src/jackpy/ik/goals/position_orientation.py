"""Position+orientation goal (3.15): ``w_p |p - r|^2 + w_o (c_x^2 |x_g - x_e|^2 + c_y^2 |y_g - y_e|^2)``.

The blend weights satisfy ``w_p + w_o = 1``; ``position_weight`` is ``w_p``.
"""

from __future__ import annotations

import math

import numpy as np

from jackpy.ik.goals.base import Chain, Context, GoalEval, SiteGoal
from jackpy.ik.goals.kernels import frame_goal
from jackpy.ik.goals.orientation import orientation_degrees


class PositionOrientation(SiteGoal):
    """Bring ``site`` onto the frame ``target`` (world 4x4): origin and x/y axes."""

    kind = "position+orientation"
    targets = ("target",)
    params = ("position_weight", "cx", "cy")

    def __init__(self, site: str, target: np.ndarray, chain: Chain = None, weight: float = 1.0,
                 position_weight: float = 0.5, cx: float = 1.0, cy: float = 1.0,
                 name: str | None = None) -> None:
        super().__init__(site, chain, weight, name)
        if not 0.0 <= position_weight <= 1.0:
            raise ValueError(f"position_weight must lie in [0, 1], not {position_weight}")
        self.target = np.asarray(target, dtype=float).reshape(4, 4).copy()
        self.position_weight = float(position_weight)
        self.cx, self.cy = float(cx), float(cy)

    def evaluate(self, ctx: Context) -> GoalEval:
        if ctx.compiled:  # the same arithmetic as one loop (goals/kernels.py)
            sp, so = math.sqrt(self.position_weight), math.sqrt(1.0 - self.position_weight)
            f, J = np.empty(9), np.empty((9, ctx.cols.size))
            metres, deg = frame_goal(ctx.fk.segments[self.seg], self.location,
                                     np.ascontiguousarray(self.target, dtype=float), sp, so * self.cx,
                                     so * self.cy, self.cx, self.cy, ctx._mom, ctx._ang,
                                     ctx.columns.moved[self.seg], f, J)
            return GoalEval(f, J, metres, deg)
        w = ctx.site(self.seg, self.location)
        sp, so = np.sqrt(self.position_weight), np.sqrt(1.0 - self.position_weight)
        weights = np.array([sp, so * self.cx, so * self.cy])
        # rows: position, x axis, y axis (the site's vs the target's), weighted; one Jacobian product
        cur = w[:3, [3, 0, 1]].T
        f = ((cur - self.target[:3, [3, 0, 1]].T) * weights[:, None]).reshape(9)
        J = ctx.stacked_jacobian(self.seg, cur, weights, point=True)
        deg = orientation_degrees(w, self.target, self.cx, self.cy)
        d = cur[0] - self.target[:3, 3]
        return GoalEval(f, J, metres=math.sqrt(float(d @ d)), degrees=deg)

    def set_frame(self, frame: np.ndarray) -> None:
        """The target is the frame."""
        self.target = np.asarray(frame, dtype=float).reshape(4, 4).copy()
