"""Aiming-at goal (3.16-3.18): the site's axis ``v`` points at ``p``; ``P = c^2 |u - v|^2``.

``u = (p - r)/|p - r|`` with ``r`` the site origin. Both ``r`` and ``v`` move with the chain. The
Jacobian of ``u`` is ``-(I - u u^T)/|p - r|``, which gives the corrected gradient of §3.6-B:
``grad_r P = (2c^2/|p - r|)(v - u (u.v))`` (cubic denominator, not the printed square).
Within 1e-9 m of the target ``u`` is taken as ``v``: no NaN, zero pull.
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
    point3,
    unit,
)
from jackpy.ik.goals.kernels import aim_goal


def aim_gradient_r(p: np.ndarray, r: np.ndarray, v: np.ndarray, c: float = 1.0) -> np.ndarray:
    """``grad_r P`` of the aim potential (corrected eq. 3.17, cubic denominator)."""
    d = p - r
    n = np.linalg.norm(d)
    return 2.0 * c * c * (n * n * v - (d @ v) * d) / n ** 3


class Aim(SiteGoal):
    """Point the site axis ``axis`` (site frame, default +z) at the world point ``target``."""

    kind = "aim"
    targets = ("target",)
    params = ("axis", "c")
    LOOK_DISTANCE = 1.0
    """A new aim goal's target lies this far (m) along the site's axis."""

    def __init__(self, site: str, target: np.ndarray, axis: np.ndarray = (0.0, 0.0, 1.0),
                 chain: Chain = None, weight: float = 1.0, c: float = 1.0, name: str | None = None) -> None:
        super().__init__(site, chain, weight, name)
        self.target = point3(target)
        self.axis = unit(axis, "aim axis")
        self.c = float(c)

    def evaluate(self, ctx: Context) -> GoalEval:
        if ctx.compiled:  # the same arithmetic as one loop (goals/kernels.py)
            f, J = np.empty(3), np.empty((3, ctx.cols.size))
            deg = aim_goal(ctx.fk.segments[self.seg], self.location, self.axis,
                           np.ascontiguousarray(self.target, dtype=float), self.c, ctx._mom, ctx._ang,
                           ctx.columns.moved[self.seg], f, J)
            return GoalEval(f, J, degrees=deg)
        w = ctx.site(self.seg, self.location)
        r = w[:3, 3]
        v = w[:3, :3] @ self.axis
        d = self.target - r
        n = math.sqrt(float(d @ d))
        Jrv = ctx.stacked_jacobian(self.seg, np.stack([r, v]), (1.0, 1.0), point=True)
        Jr, Jv = Jrv[:3], Jrv[3:]
        if n < 1e-9:
            return GoalEval(np.zeros(3), np.zeros_like(Jv))
        u = d / n
        Ju = -(Jr - np.outer(u, u @ Jr)) / n
        return GoalEval(self.c * (u - v), self.c * (Ju - Jv), degrees=angle_deg(u, v))

    def set_frame(self, frame: np.ndarray) -> None:
        """The target point is the frame's origin."""
        self.target = point3(frame)

    @classmethod
    def check_param(cls, name: str, value: object) -> object:
        return unit(value, "aim axis") if name == "axis" else super().check_param(name, value)

    @classmethod
    def placement(cls, site_world: np.ndarray, params: dict) -> np.ndarray:
        """The site's frame moved :attr:`LOOK_DISTANCE` along the aimed axis (where it points now)."""
        axis = unit(params.get("axis", (0.0, 0.0, 1.0)), "aim axis")
        out = np.array(site_world, dtype=float)
        out[:3, 3] += cls.LOOK_DISTANCE * (out[:3, :3] @ axis)
        return out
