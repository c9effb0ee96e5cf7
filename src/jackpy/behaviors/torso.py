"""Torso: keep vertical, hold global orientation, or bent by the spine sliders ([SH4] §4.1.1
Table 4.3, §4.2.3; [PB91] §4.4; behaviors.md §2.6).

Modes (``state.torso_mode``):

- ``"vertical"`` (default): a direction constraint turns the chest's up to world up; rotation about
  the vertical (twist) stays free. The spine's variables (the spine joint group's flexion, lateral
  bend and axial twist on the standard human) are free in the body pass, so a tilted pelvis is
  compensated over the whole spine with the group's weighting, never vertebra by vertebra.
- ``"hold"``: the chest's full global orientation is held (``state.torso_goal``); position floats.
- ``"bend"``: the spine is set by :func:`bend_spine` (forward kinematics, as Jack's bend torso) and
  locked in the body pass; balance then moves the hips back.

The constraint acts on the chest, not the head, so the neck stays free for gaze.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.anatomy import Anatomy
from jackpy.behaviors.base import BehaviorBase, param
from jackpy.ik.goals import Orientation
from jackpy.peabody.model import Figure

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame

UP = np.array([0.0, 1.0, 0.0])
MODES = ("vertical", "hold", "bend")


@dataclass
class TorsoParams:
    weight: float = param(0.3, "weight of the chest constraint", "", (0.0, 1e4))
    level: int = param(1, "priority level of the chest constraint", "", (0, 3))


def bend_spine(figure: Figure, anatomy: Anatomy, flexion: float, lateral: float, axial: float) -> np.ndarray:
    """Set the spine to total angles (rad; forward flexion, lateral bend, axial twist), clamped to
    what the spine allows; returns the angles applied.

    With a spine joint group (standard human) its angles are set (its driver spreads them over the
    vertebrae); otherwise [proposal] each vertebral joint takes an equal share of each total
    (DOF axes x = flexion, z = lateral, y = axial), clamped to its limits.
    """
    target = np.array([flexion, lateral, axial], dtype=float)
    if anatomy.spine_group is not None:
        g = figure.groups[anatomy.spine_group]
        theta = np.clip(target, g.lower, g.upper)
        for _ in range(30):
            if g.is_feasible(theta):
                break
            theta *= 0.95
        g.set_angles(figure, theta)
        return theta
    n = len(anatomy.spine_joints)
    applied = np.zeros(3)
    for jn in anatomy.spine_joints:
        j = figure.joint(jn)
        for k, d in enumerate(j.dofs):
            axis = int(np.argmax(np.abs(d.axis)))
            which = {0: 0, 2: 1, 1: 2}[axis]
            v = float(np.clip(target[which] / n * np.sign(d.axis[axis]), d.lower, d.upper))
            j.displacement[k] = v
            applied[which] += v * np.sign(d.axis[axis])
    return applied


class Torso(BehaviorBase):
    """Keeps the chest vertical (default), holds its orientation, or leaves a bent spine locked."""

    name = "torso"
    order = 60

    def __init__(self, params: TorsoParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or TorsoParams(), enabled)

    def update(self, frame: "Frame") -> None:
        st, a, p = frame.state, frame.anatomy, self.params
        if st.torso_mode == "bend":
            frame.spine_free = False
            return
        if st.torso_mode == "hold":
            if st.torso_goal is None:
                st.torso_goal = frame.site(*a.chest)[:3, :3].copy()
            frame.body.append((Orientation(f"{a.chest[0]}.{a.chest[1]}", st.torso_goal, weight=p.weight,
                                           name="chest"), p.level))
            return
        frame.body.append((frame.keep_direction(*a.chest, a.chest_up, UP, p.weight, "chest up"), p.level))
