"""Orientation ("frame") goal (3.12-3.14): ``P = c_x^2 |x_g - x_e|^2 + c_y^2 |y_g - y_e|^2``.

``x_e, y_e`` are the site's x and y axes in the world, ``x_g, y_g`` the target's. ``c_x, c_y`` are the
orientation unit factors (3.11, see :func:`~jackpy.ik.goals.base.unit_factor`); ``c_y = 0`` leaves
rotation about ``x`` free (the book's "direction" goal).
"""

from __future__ import annotations

import math

import numpy as np

from jackpy.ik.goals.base import (
    Chain,
    Context,
    GoalEval,
    SiteGoal,
    angle_deg,
    rotation3,
)


def orientation_terms(ctx: Context, seg: int, w: np.ndarray, target: np.ndarray, cx: float,
                      cy: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Residual ``[c_x (x_e - x_g); c_y (y_e - y_g)]``, its Jacobian and the angle error (degrees).

    The angle is the full rotation angle when both axes count, else that of the counted axis.
    """
    xe, ye = w[:3, 0], w[:3, 1]
    xg, yg = target[:3, 0], target[:3, 1]
    f = np.concatenate([cx * (xe - xg), cy * (ye - yg)])
    J = ctx.stacked_jacobian(seg, w[:3, :2].T, (cx, cy))
    return f, J, orientation_degrees(w, target, cx, cy)


def orientation_degrees(w: np.ndarray, target: np.ndarray, cx: float, cy: float) -> float:
    """Angle error (degrees) between the site rotation ``w[:3, :3]`` and ``target`` (see above)."""
    if cx > 0 and cy > 0:
        c = (float(np.vdot(target[:3, :3], w[:3, :3])) - 1.0) / 2.0  # trace(target^T R)
        return math.degrees(math.acos(min(max(c, -1.0), 1.0)))
    if cx > 0:
        return angle_deg(w[:3, 0], target[:3, 0])
    return angle_deg(w[:3, 1], target[:3, 1]) if cy > 0 else 0.0


class Orientation(SiteGoal):
    """Align the axes of ``site`` with ``target`` (3x3 or 4x4 world rotation)."""

    kind = "orientation"
    targets = ("target",)
    params = ("cx", "cy")

    def __init__(self, site: str, target: np.ndarray, chain: Chain = None, weight: float = 1.0,
                 cx: float = 1.0, cy: float = 1.0, name: str | None = None) -> None:
        super().__init__(site, chain, weight, name)
        self.target = rotation3(target)
        self.cx, self.cy = float(cx), float(cy)

    def evaluate(self, ctx: Context) -> GoalEval:
        w = ctx.site(self.seg, self.location)
        f, J, deg = orientation_terms(ctx, self.seg, w, self.target, self.cx, self.cy)
        return GoalEval(f, J, degrees=deg)

    def set_frame(self, frame: np.ndarray) -> None:
        """The target is the frame's rotation."""
        self.target = rotation3(frame)
