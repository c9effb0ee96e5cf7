"""Head and eyes motion ([PB91] §7 "look over the shoulder"; behaviors.md §2.8): moves the head's
(``which="head"``, neck only) or the eyes' (``"eyes"``; the head follows when they run out) fixation
point from where the figure looks now to a target point or site, global or relative to a segment
or object (re-read every step, so a moving object is followed). The start is the point at the
target's distance along the current view direction. After the motion the fixation stays on the
end point. Overlapping head motions blend their points by weight.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from jackpy.motion.base import Context, Motion, register, target_pose
from jackpy.motion.interpolate import lerp


@register
@dataclass
class GazeMotion(Motion):
    kind = "gaze"
    which: str = "head"
    target: dict[str, Any] = field(default_factory=lambda: {"point": [0.0, 1.6, 2.0]})

    @property
    def part(self) -> str:
        return self.which

    def check(self) -> None:
        super().check()
        if self.which not in ("head", "eyes"):
            raise ValueError(f"gaze motion: which must be 'head' or 'eyes', not {self.which!r}")
        if not isinstance(self.target, dict) or not ("point" in self.target or "site" in self.target):
            raise ValueError("gaze motion: target needs 'point' [x, y, z] or 'site' name")

    def pre(self, ctx: Context) -> None:
        a = ctx.loop.anatomy
        view = ctx.figure.site_world(*a.view)
        fwd = ctx.figure.world_transforms()[a.view[0]][:3, :3] @ a.view_forward
        end = target_pose(ctx.env, self.target)[0][:3, 3]
        dist = max(float(np.linalg.norm(end - view[:3, 3])), 0.1)
        self.run["start"] = (view[:3, 3] + dist * fwd / np.linalg.norm(fwd)).tolist()

    def sample(self, ctx: Context, s: float) -> np.ndarray:
        end = target_pose(ctx.env, self.target)[0][:3, 3]
        return lerp(self.run["start"], end, s)

    def write(self, ctx: Context, value: np.ndarray, weight: float) -> None:
        st = ctx.loop.state
        if self.which == "head":
            st.head_target = np.asarray(value, dtype=float).copy()
        else:
            st.eyes_target = np.asarray(value, dtype=float).copy()
