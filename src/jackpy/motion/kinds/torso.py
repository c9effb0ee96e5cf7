"""Torso motion ([SH4] §4.4.4): bends the spine to totals ``flexion``, ``lateral``, ``axial``
(radians, as bend torso) by forward kinematics through the spine's joint group.

No constraint is used, so a torso motion has a velocity function but **no weight**, and two torso
motions of one figure may not overlap (the timeline refuses it). While it runs and **after it ends
the vertical torso behavior is off** (the torso keeps its bend; a timed torso control or
``set_torso_behavior`` turns it back on). Do not combine it with an arm motion with waist bend.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.behaviors.torso import bend_spine
from jackpy.motion.base import Context, Motion, register
from jackpy.motion.interpolate import lerp


@register
@dataclass
class TorsoMotion(Motion):
    kind = "torso"
    weighted = False
    flexion: float = 0.0
    lateral: float = 0.0
    axial: float = 0.0

    def pre(self, ctx: Context) -> None:
        a = ctx.loop.anatomy
        if a.spine_group is not None:
            start = ctx.figure.groups[a.spine_group].angles
        else:
            start = np.zeros(3)
        self.run["start"] = [float(v) for v in start]
        self.run["end"] = [float(self.flexion), float(self.lateral), float(self.axial)]

    def sample(self, ctx: Context, s: float) -> np.ndarray:
        return lerp(self.run["start"], self.run["end"], s)

    def write(self, ctx: Context, value: np.ndarray, weight: float) -> None:
        ctx.loop.state.torso_mode = "bend"
        bend_spine(ctx.figure, ctx.loop.anatomy, *[float(v) for v in value])

    def post(self, ctx: Context) -> None:
        ctx.loop.state.torso_mode = "bend"
