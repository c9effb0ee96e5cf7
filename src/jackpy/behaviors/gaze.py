"""Head and eyes: fixation on a point ([SH4] §4.1.1 Table 4.4, §4.2.5; behaviors.md §2.8).

- **fixate eyes** (``state.eyes_target``): each eye's aim constraint rotates only its eyeball (two
  DOFs within the eye's limits) so its forward axis points at the target;
- **fixate head** (``state.head_target``): an aim constraint on the between-the-eyes view site
  moved by the neck only.

Head-eye coupling is a gap in the book; [proposal] the eyes take the target first, and when the
target lies more than ``eye_range`` off the head's view direction (the eyes would run out) the
head aims at it too, and keeps following until the target is back within ``eye_range / 2``. With
the head on the target the eyes re-centre. Both re-aim every frame, so fixation holds while the
body moves. They are solved in the head pass (neck and eyes) after the body.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param
from jackpy.ik.goals import Aim

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame


@dataclass
class GazeParams:
    eye_range: float = param(np.radians(20.0), "eye deflection beyond which the head follows", "deg",
                             (0.0, np.radians(60.0)))
    head_follows: bool = param(True, "the head turns when the eyes run out of range")
    weight: float = param(1.0, "weight of the head and eye aim constraints", "", (0.0, 1e4))


class Gaze(BehaviorBase):
    """Aims the eyes (and the head when needed, or when fixated) at their targets."""

    name = "gaze"
    order = 70

    def __init__(self, params: GazeParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or GazeParams(), enabled)
        self.following = False

    def update(self, frame: "Frame") -> None:
        st, a, p = frame.state, frame.anatomy, self.params
        head_target = st.head_target
        if st.eyes_target is not None:
            target = np.asarray(st.eyes_target, dtype=float)
            for side, (seg, site) in a.eyes.items():
                loc = frame.figure.site_location(seg, site)
                frame.head.append((Aim(f"{seg}.{site}", target, axis=loc[:3, :3].T @ a.eye_forward,
                                       chain=[a.eye_joints[side]], weight=p.weight, name=f"eye {side}"), 0))
            if p.head_follows and head_target is None:
                view = frame.site(*a.view)
                fwd = frame.segment(a.view[0])[:3, :3] @ a.view_forward
                d = target - view[:3, 3]
                off = np.arccos(np.clip(fwd @ d / max(np.linalg.norm(d), 1e-9), -1.0, 1.0))
                if off > p.eye_range:
                    self.following = True
                elif off < p.eye_range / 2:
                    self.following = False
                if self.following:
                    head_target = target
        if head_target is not None:
            loc = frame.figure.site_location(*a.view)
            frame.head.append((Aim(f"{a.view[0]}.{a.view[1]}", np.asarray(head_target, dtype=float),
                                   axis=loc[:3, :3].T @ a.view_forward, chain=list(a.neck_joints),
                                   weight=p.weight, name="head"), 0))
