"""Centre-of-mass motion ([SH4] §4.4.2; behaviors.md §4.5): moves the balance point.

- ``mode="relative"``: ``x`` in [0, 1] between the feet (0 = left, 1 = right; 0.3 puts 30 % of the
  weight on the right foot) and ``z`` front/back (±1 the polygon's edges; None keeps the current);
  the goal is the balance parameters, which follow the feet (P1) while they move.
- ``mode="global"``: the floor point under ``point`` (m), as a dragged centre of mass.

The start is the balance point when the motion begins. Overlapping COM motions blend their goals
by weight (the weighted mean is the optimum of their COM constraints).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from jackpy.behaviors.support import floor
from jackpy.motion.base import Context, Motion, register
from jackpy.motion.interpolate import lerp


@register
@dataclass
class COMMotion(Motion):
    kind = "com"
    mode: str = "relative"
    x: float = 0.5
    z: float | None = None
    point: list[float] = field(default_factory=lambda: [0.0, 0.0, 0.0])

    def check(self) -> None:
        super().check()
        if self.mode not in ("relative", "global"):
            raise ValueError(f"com motion: mode must be 'relative' or 'global', not {self.mode!r}")
        if self.mode == "relative" and not 0.0 <= self.x <= 1.0:
            raise ValueError(f"com motion: x must be in [0, 1] (0 left foot, 1 right), got {self.x}")

    def pre(self, ctx: Context) -> None:
        st = ctx.loop.state
        if self.mode == "relative":
            self.run["start"] = [float(st.balance[0]), float(st.balance[1])]
            self.run["end"] = [float(self.x), float(st.balance[1] if self.z is None else self.z)]
        else:
            self.run["start"] = [float(v) for v in st.balance_point]
            self.run["end"] = [float(v) for v in floor(np.asarray(self.point, dtype=float))]

    def sample(self, ctx: Context, s: float) -> np.ndarray:
        return lerp(self.run["start"], self.run["end"], s)

    def write(self, ctx: Context, value: np.ndarray, weight: float) -> None:
        st = ctx.loop.state
        if self.mode == "relative":
            st.balance = (float(value[0]), float(value[1]))
            st.com_drag = None
        else:
            st.com_drag = np.asarray(value, dtype=float)

    def post(self, ctx: Context) -> None:
        # a global move ends like a released drag: the balance parameters keep the point
        ctx.loop.state.com_drag = None
