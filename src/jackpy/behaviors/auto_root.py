"""P5, automatic figure root ([SH4] §4.1.2 "The Figure Root"; behaviors.md §2.5 P5).

Rules:

1. Root through a foot when more than ``foot_share`` (60%) of the weight is on it: balance
   parameter ``x > 0.6`` → right foot, ``x < 0.4`` → left foot. In between the current foot root is
   kept (hysteresis), so a swaying figure does not flip its root.
2. Root through the lower torso (pelvis) when the COM is less than ``seated_fraction`` (70%) of the
   leg length above the feet; [proposal] go back to a foot root only above ``standing_fraction``
   (75%), a second hysteresis band.

Re-rooting uses :meth:`Figure.reroot`, which keeps every global transform. While an active
behavior (a step) has claimed the root, this behavior leaves it alone.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from jackpy.behaviors.base import BehaviorBase, param

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame

LEFT, RIGHT, PELVIS = "left", "right", "pelvis"


@dataclass
class AutoRootParams:
    foot_share: float = param(0.6, "weight share on a foot above which it becomes the root", "", (0.5, 1.0))
    seated_fraction: float = param(0.7, "root through the lower torso when COM height < this x leg length",
                                   "", (0.0, 1.0))
    standing_fraction: float = param(0.75, "back to a foot root when COM height > this x leg length",
                                     "", (0.0, 1.2))


def select_root(current: str, x: float, com_height: float, leg_length: float,
                p: AutoRootParams | None = None) -> str:
    """The root (``"left"``, ``"right"`` or ``"pelvis"``) for balance parameter ``x`` (weight share
    on the right foot) and COM height above the feet ``com_height`` (m), given the ``current`` one."""
    p = p or AutoRootParams()
    if current == PELVIS:
        if com_height >= p.standing_fraction * leg_length:
            return RIGHT if x >= 0.5 else LEFT
        return PELVIS
    if com_height < p.seated_fraction * leg_length:
        return PELVIS
    if x > p.foot_share:
        return RIGHT
    if x < 1.0 - p.foot_share:
        return LEFT
    return current


class AutoRoot(BehaviorBase):
    """Roots the figure through the loaded foot (60% rule) or the lower torso (70% rule)."""

    name = "automatic root"
    order = 10

    def __init__(self, params: AutoRootParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or AutoRootParams(), enabled)

    def update(self, frame: "Frame") -> None:
        st = frame.state
        if st.root_claimed:
            return
        x, _ = frame.balance_params()
        height = frame.com[1] - frame.feet_height()
        new = select_root(st.root, x, height, frame.anatomy.leg_length, self.params)
        if new != st.root:
            frame.set_root(new)
            frame.note(f"root -> {new}")
