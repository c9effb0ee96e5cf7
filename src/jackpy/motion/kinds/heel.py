"""Heel motion ([SH4] §4.4.5; [PB91] "raise/lower heel"): a point-to-plane constraint holding the
heel site ``height`` (m) above its height with the sole level (0 = on the floor).

While it runs the foot keeps only its toe position (mode ``free``: the foot turns about the ball)
and the heel is left to this motion's plane goal, a user goal of the behavior loop of weight
``weight`` x the weight function; a foot that roots the figure hands the support to the other
foot. After it the plane goal is removed; a heel that ended on the floor goes back to the feet
behavior (heel on floor, sole flat), a raised one stays free.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.ik.goals import Plane
from jackpy.motion.base import Context, Motion, register
from jackpy.motion.kinds.feet_common import UP, free_foot, level

#: a heel at most this high (m) at the end is back on the floor
ON_FLOOR = 1e-3


@register
@dataclass
class HeelMotion(Motion):
    kind = "heel"
    side: str = "left"
    height: float = 0.0
    weight: float = 10.0

    @property
    def part(self) -> str:
        return f"heel.{self.side}"

    def check(self) -> None:
        super().check()
        if self.side not in ("left", "right"):
            raise ValueError(f"heel motion: side must be 'left' or 'right', not {self.side!r}")
        if not self.height >= 0.0:
            raise ValueError(f"heel motion: height must be >= 0 m, got {self.height}")

    def _key(self) -> str:
        return f"motion heel {self.figure} {self.side}"

    def pre(self, ctx: Context) -> None:
        loop = ctx.loop
        spec = loop.anatomy.feet[self.side]
        free_foot(ctx, self.side)
        fs = loop.state.feet[self.side]
        base = float(loop.heel_point(self.side, level(loop, self.side, fs.target))[1])
        start = float(ctx.figure.site_world(*spec.heel)[1, 3])
        fs.heel = "free"
        if f"foot.{self.side}" not in ctx.active:
            fs.mode = "free"
        self.run["start"] = start
        self.run["end"] = base + float(self.height)
        self.run["base"] = base

    def sample(self, ctx: Context, s: float) -> np.ndarray:
        return np.array([(1.0 - s) * self.run["start"] + s * self.run["end"]])

    def write(self, ctx: Context, value: np.ndarray, weight: float) -> None:
        loop = ctx.loop
        spec = loop.anatomy.feet[self.side]
        point = np.array([0.0, float(value[0]), 0.0])
        try:
            u = loop.user_goal(self._key())
            u.goal.point = point
            loop.set_user_goal(u, weight=max(weight, 1e-6))
        except KeyError:
            goal = Plane(f"{spec.heel[0]}.{spec.heel[1]}", point, UP, weight=max(weight, 1e-6),
                         name=f"heel motion {self.side}")
            loop.add_user_goal(goal, 0, key=self._key(), part="body")
        loop.state.root_claimed = True

    def post(self, ctx: Context) -> None:
        loop = ctx.loop
        try:
            loop.remove_user_goal(self._key())
        except KeyError:
            pass
        fs = loop.state.feet[self.side]
        if self.run["end"] - self.run["base"] <= ON_FLOOR:
            fs.heel = "floor"
            if f"foot.{self.side}" not in ctx.active:
                fs.mode = "pivot"
                loop.state.root_claimed = False
