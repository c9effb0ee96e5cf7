"""Pelvis motion ([SH4] §4.4.3): rotates the pelvis orientation goal to its final orientation.

The end is ``rotation`` (a world 3x3 of the pelvis site) or, relative to the start, ``twist``
(about world up), ``tilt`` (about the pelvis's horizontal forward) and ``curl`` (about its left axis), radians,
right-handed, applied in that order to the start orientation. While it runs the pelvis-follows-feet
behavior (P3) is suspended, as during a user's rotate pelvis; after it the goal stays where it
ended and P3 resumes. Overlapping pelvis motions blend by weight (quaternion mean).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.motion.base import Context, Motion, register
from jackpy.motion.interpolate import mean_rotation, slerp
from jackpy.peabody.transforms import rotation_matrix

UP = np.array([0.0, 1.0, 0.0])


@register
@dataclass
class PelvisMotion(Motion):
    kind = "pelvis"
    rotation: list | None = None
    twist: float = 0.0
    tilt: float = 0.0
    curl: float = 0.0

    def pre(self, ctx: Context) -> None:
        a, fig = ctx.loop.anatomy, ctx.figure
        site = fig.site_world(a.pelvis, a.pelvis_site)
        start = site[:3, :3]
        if self.rotation is not None:
            end = np.asarray(self.rotation, dtype=float).reshape(3, 3)
        else:
            fwd = start @ (fig.site_location(a.pelvis, a.pelvis_site)[:3, :3].T @ a.pelvis_forward)
            fwd = fwd - (fwd @ UP) * UP
            fwd /= np.linalg.norm(fwd)
            left = np.cross(UP, fwd)
            r = (rotation_matrix(UP, self.twist)[:3, :3] @ rotation_matrix(fwd, self.tilt)[:3, :3]
                 @ rotation_matrix(left, self.curl)[:3, :3])
            end = r @ start
        self.run["start"] = start.tolist()
        self.run["end"] = end.tolist()

    def sample(self, ctx: Context, s: float) -> np.ndarray:
        return slerp(np.array(self.run["start"]), np.array(self.run["end"]), s)

    def blend(self, values: list, weights: list[float]) -> np.ndarray:
        return mean_rotation(values, weights)

    def write(self, ctx: Context, value: np.ndarray, weight: float) -> None:
        st = ctx.loop.state
        st.pelvis_goal = np.asarray(value, dtype=float).copy()
        st.pelvis_user = True

    def post(self, ctx: Context) -> None:
        ctx.loop.state.pelvis_user = True  # the pelvis holds where the motion left it (P3 stays off)
