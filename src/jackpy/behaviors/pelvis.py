"""Pelvis: orientation constraint, following the feet ([SH4] §4.1.1-4.1.2, §4.2.4; [PB91] §4.5).

The pelvis constraint is orientation only; its position is governed by the balance constraint.
``state.pelvis_goal`` (world 3x3 of the pelvis site) is held every frame. With **pelvis follows
feet orientation** (P3, on by default) its yaw turns towards the circular mean of the two feet's
yaws, at most ``max_rate`` per frame, keeping its tilt and curl, so the legs (rotational springs of
a little more than 90° range) are relieved; while the user rotates the pelvis
(``state.pelvis_user``) P3 is suspended and the user's goal wins.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param
from jackpy.behaviors.support import mean_yaw, wrap, yaw_of
from jackpy.ik.goals import Orientation
from jackpy.peabody.transforms import rotation_matrix

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame

Y = np.array([0.0, 1.0, 0.0])


@dataclass
class PelvisParams:
    follow_feet: bool = param(True, "pelvis follows feet orientation (P3)")
    max_rate: float = param(np.radians(3.0), "largest yaw change of the pelvis goal per frame", "deg",
                            (0.0, np.pi))
    weight: float = param(0.3, "weight of the pelvis orientation constraint", "", (0.0, 1e4))
    level: int = param(1, "priority level of the pelvis constraint", "", (0, 3))


def feet_yaw(frame: "Frame") -> float:
    """Circular mean (rad) of the yaws of the two feet's goals."""
    yaws = [yaw_of(f.target[:3, :3] @ (frame.figure.site_location(*frame.anatomy.feet[s].ball)[:3, :3].T
                                       @ frame.anatomy.feet[s].forward))
            for s, f in frame.state.feet.items()]
    return mean_yaw(yaws[0], yaws[1])


def pelvis_yaw(frame: "Frame", rot: np.ndarray) -> float:
    """Yaw (rad) of a pelvis-site world rotation ``rot``."""
    a = frame.anatomy
    site = frame.figure.site_location(a.pelvis, a.pelvis_site)
    return yaw_of(rot @ (site[:3, :3].T @ a.pelvis_forward))


class Pelvis(BehaviorBase):
    """Holds the pelvis orientation goal; P3 turns it with the feet."""

    name = "pelvis"
    order = 30

    def __init__(self, params: PelvisParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or PelvisParams(), enabled)

    def update(self, frame: "Frame") -> None:
        st, a, p = frame.state, frame.anatomy, self.params
        if st.pelvis_goal is None:
            st.pelvis_goal = frame.site(a.pelvis, a.pelvis_site)[:3, :3].copy()
        if p.follow_feet and not st.pelvis_user:
            d = wrap(feet_yaw(frame) - pelvis_yaw(frame, st.pelvis_goal))
            d = float(np.clip(d, -p.max_rate, p.max_rate))
            st.pelvis_goal = rotation_matrix(Y, d) @ st.pelvis_goal
        frame.body.append((Orientation(f"{a.pelvis}.{a.pelvis_site}", st.pelvis_goal, weight=p.weight,
                                       name="pelvis"), p.level))
