"""Balance: the centre of mass held above a balance point ([SH4] §4.1.2, §4.2.2; [PB91] §4.2-4.3).

The balance point is stored as the parameters (x, z) of :mod:`jackpy.behaviors.support` (x = weight
share on the right foot, z front/back, ±1 on the polygon's edges). Each frame:

- while the user drags the COM (``state.com_drag``), the balance point is the dragged floor point
  and (x, z) are recomputed from it, so it stays put relative to the feet after release;
- otherwise, with **balance point follows feet** (P1, on by default) the point is recomputed from
  the stored (x, z) and the feet's current goals, so moving a foot keeps the weight distribution;
  with it off the point stays fixed in the world and (x, z) follow it.

The loop turns ``frame.com_goal`` into a :class:`~jackpy.ik.goals.CentreOfMass` goal (a vertical
line, so the COM height floats) on the body pass, and re-solves while the COM is off the line.
With the figure rooted through the lower torso (seated) there is no standing balance.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame


@dataclass
class BalanceParams:
    follow_feet: bool = param(True, "balance point follows feet (P1): keep (x, z) when the feet move")
    weight: float = param(1.0, "weight of the COM constraint", "", (0.0, 1e4))
    level: int = param(1, "priority level of the COM constraint", "", (0, 3))


class Balance(BehaviorBase):
    """Keeps the COM over the balance point."""

    name = "balance"
    order = 40

    def __init__(self, params: BalanceParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or BalanceParams(), enabled)

    def update(self, frame: "Frame") -> None:
        st = frame.state
        bf = frame.balance_frame()
        if st.com_drag is not None:
            b = np.asarray(st.com_drag, dtype=float)
            st.balance = bf.params(b)
        elif self.params.follow_feet:
            b = bf.point(*st.balance)
        else:
            b = st.balance_point
            st.balance = bf.params(b)
        st.balance_point = b
        if st.root != "pelvis":
            frame.com_goal = np.array([b[0], 0.0, b[1]])
            frame.com_weight = self.params.weight
            frame.com_level = self.params.level
