"""Foot motion ([SH4] §4.4.5; [PB91] "move foot"): moves a foot's toe (ball-site) goal from where
it is to an end pose along an arc.

The end is ``position`` (world m of the ball site), or ``displacement`` (m, world axes, or the
foot's own with ``local``) from the start; ``turn`` (rad) yaws the foot about world up. ``height``
(m) lifts the path: the toes rise ``height * sin(πs)`` above the straight line from start to end,
so with both ends on the floor they reach ``height`` above it halfway along the path (halfway
through the motion with a constant or symmetric velocity); 0 is a straight line (a slide).

While the motion runs the foot is held in position and orientation (mode ``hold``) with its heel
free; a foot that roots the figure hands the support to the other foot first ([SH4]: a foot motion
"is much better at moving the non-supported one"). After it the foot is planted (``pivot``, heel on
the floor) unless a heel motion is still running on it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.motion.base import Context, Motion, register
from jackpy.motion.interpolate import mean_pose, pose_lerp
from jackpy.motion.kinds.feet_common import UP, free_foot
from jackpy.peabody.transforms import rotation_matrix


@register
@dataclass
class FootMotion(Motion):
    kind = "foot"
    side: str = "left"
    position: list | None = None
    displacement: list | None = None
    local: bool = False
    turn: float = 0.0
    height: float = 0.0
    weight: float = 10.0

    @property
    def part(self) -> str:
        return f"foot.{self.side}"

    def check(self) -> None:
        super().check()
        if self.side not in ("left", "right"):
            raise ValueError(f"foot motion: side must be 'left' or 'right', not {self.side!r}")
        if not self.height >= 0.0:
            raise ValueError(f"foot motion: height must be >= 0 m, got {self.height}")

    def pre(self, ctx: Context) -> None:
        loop = ctx.loop
        spec = loop.anatomy.feet[self.side]
        free_foot(ctx, self.side)
        fs = loop.state.feet[self.side]
        start = ctx.figure.site_world(*spec.ball)
        end = start.copy()
        end[:3, :3] = rotation_matrix(UP, self.turn)[:3, :3] @ start[:3, :3]
        if self.position is not None:
            end[:3, 3] = np.asarray(self.position, dtype=float)[:3]
        elif self.displacement is not None:
            d = np.asarray(self.displacement, dtype=float)[:3]
            end[:3, 3] = start[:3, 3] + (start[:3, :3] @ d if self.local else d)
        fs.mode, fs.heel = "hold", "free"
        self.run["start"] = start.tolist()
        self.run["end"] = end.tolist()

    def sample(self, ctx: Context, s: float) -> np.ndarray:
        pose = pose_lerp(np.array(self.run["start"]), np.array(self.run["end"]), s)
        pose[:3, 3] += UP * (self.height * np.sin(np.pi * s))
        return pose

    def blend(self, values: list, weights: list[float]) -> np.ndarray:
        return mean_pose(values, weights)

    def write(self, ctx: Context, value: np.ndarray, weight: float) -> None:
        fs = ctx.loop.state.feet[self.side]
        fs.target = np.asarray(value, dtype=float).copy()
        fs.mode = "hold"
        ctx.loop.state.root_claimed = True

    def post(self, ctx: Context) -> None:
        st = ctx.loop.state
        fs = st.feet[self.side]
        if f"heel.{self.side}" not in ctx.active:
            fs.mode, fs.heel = "pivot", "floor"
            st.root_claimed = False
