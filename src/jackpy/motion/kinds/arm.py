"""Arm motion ([SH4] §4.4.7; behaviors.md §4.5): moves a hand's palm goal from where the palm is to
a target.

``target`` is a point or a site, global or relative to a segment or object (see
:func:`jackpy.motion.base.target_pose`). A relative target is re-read every step, so the hand
tracks it while the object moves; after the motion the hand is held relative to it (it keeps
following). A global target is fixed when the motion starts and the hand is held there after.
With ``orient`` the palm also turns to the site's orientation (slerp); otherwise the palm rules
(P4) choose it as the hand travels. ``waist`` lets the reach recruit the body (the hands
behavior's lean: waist bend, then a step at the edge of balance); without it the reach is confined
to the arm. Overlapping arm motions on one hand blend by weight.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from jackpy.motion.base import Context, Motion, target_pose, register
from jackpy.motion.interpolate import mean_pose, pose_lerp


@register
@dataclass
class ArmMotion(Motion):
    kind = "arm"
    side: str = "right"
    target: dict[str, Any] = field(default_factory=lambda: {"point": [0.0, 1.0, 0.5]})
    orient: bool = False
    waist: bool = False

    @property
    def part(self) -> str:
        return f"arm.{self.side}"

    def check(self) -> None:
        super().check()
        if self.side not in ("left", "right"):
            raise ValueError(f"arm motion: side must be 'left' or 'right', not {self.side!r}")
        if not isinstance(self.target, dict) or not ("point" in self.target or "site" in self.target):
            raise ValueError("arm motion: target needs 'point' [x, y, z] or 'site' name")

    def pre(self, ctx: Context) -> None:
        palm = ctx.figure.site_world(*ctx.loop.anatomy.hands[self.side].palm)
        world, frame, local = target_pose(ctx.env, self.target)
        self.run["start"] = palm.tolist()
        self.run["end"] = world.tolist()
        self.run["relative"] = frame is not None
        self.run["local"] = local.tolist()

    def _end(self, ctx: Context) -> np.ndarray:
        if self.run["relative"]:
            world, _, _ = target_pose(ctx.env, self.target)
            return world
        return np.array(self.run["end"])

    def sample(self, ctx: Context, s: float) -> np.ndarray:
        start, end = np.array(self.run["start"]), self._end(ctx)
        if not self.orient:
            end = end.copy()
            end[:3, :3] = start[:3, :3]
        return pose_lerp(start, end, s)

    def blend(self, values: list, weights: list[float]) -> np.ndarray:
        return mean_pose(values, weights)

    def write(self, ctx: Context, value: np.ndarray, weight: float) -> None:
        hs = ctx.loop.state.hands[self.side]
        if hs.goal is None or not self.orient:
            keep = None if hs.goal is None else hs.goal[:3, :3].copy()
            hs.goal = np.asarray(value, dtype=float).copy()
            if keep is not None and not self.orient:
                hs.goal[:3, :3] = keep  # the palm rules own the orientation
        else:
            hs.goal = np.asarray(value, dtype=float).copy()
        hs.local = None
        hs.orient = True
        hs.rules = not self.orient
        hs.lean = bool(self.waist)

    def post(self, ctx: Context) -> None:
        hs = ctx.loop.state.hands[self.side]
        hs.rules, hs.lean = False, False
        if self.run.get("relative"):
            _, frame, _ = target_pose(ctx.env, self.target)
            hs.local = frame
            hs.local_offset = np.linalg.inv(frame.pose) @ hs.goal
