"""A walk plan as plain data: the footsteps a step editor edits and a document keeps (issue 13).

``{"steps": [[x, z, heading_rad, "left" | "right"], ...]}`` (world metres, radians; σ_0, σ_1 the
standing feet, see :class:`~jackpy.locomotion.walk_path.Footstep`). JSON-ready, so it is saved
with a session and copied by undo.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from jackpy.locomotion.walk_gait import SIDES
from jackpy.locomotion.walk_path import Footstep


class PlanError(ValueError):
    """Plan data that is no walk (one line, naming the footstep)."""


def to_data(steps: list[Footstep]) -> dict[str, Any]:
    """The plan of ``steps`` as JSON-ready data."""
    return {"steps": [[float(s.x), float(s.z), float(s.psi), s.side] for s in steps]}


def from_data(data: Any, where: str = "walk plan") -> list[Footstep]:
    """Footsteps of plan ``data``; :class:`PlanError` for anything that is not a walk."""
    if not isinstance(data, dict) or not isinstance(data.get("steps"), list):
        raise PlanError(f"{where}: needs {{'steps': [[x, z, heading, side], ...]}}")
    steps = []
    for j, row in enumerate(data["steps"]):
        if not (isinstance(row, list) and len(row) == 4 and row[3] in SIDES
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v) for v in row[:3])):
            raise PlanError(f"{where}: footstep {j} is not [x, z, heading, 'left'|'right']: {row!r}")
        steps.append(Footstep(float(row[0]), float(row[1]), float(row[2]), row[3]))
    if len(steps) < 2 or {steps[0].side, steps[1].side} != set(SIDES):
        raise PlanError(f"{where}: a walk starts from two standing footsteps, one left and one right")
    for j in range(2, len(steps)):
        if steps[j].side == steps[j - 1].side:
            raise PlanError(f"{where}: footstep {j} is on the same side as footstep {j - 1}")
    return steps


def moved(steps: list[Footstep], j: int, x: float, z: float, psi: float) -> list[Footstep]:
    """A copy of ``steps`` with footstep ``j`` (≥ 2: the standing feet are where the figure stands)
    at ``(x, z)`` heading ``psi``."""
    if not 2 <= j < len(steps):
        raise PlanError(f"footstep {j}: only footsteps 2..{len(steps) - 1} move (0 and 1 are the standing feet)")
    out = [Footstep(s.x, s.z, s.psi, s.side) for s in steps]
    out[j] = Footstep(float(x), float(z), float(psi), steps[j].side)
    return out


def _angle_mid(a: float, b: float) -> float:
    return a + 0.5 * ((b - a + np.pi) % (2.0 * np.pi) - np.pi)


def with_stride_added(steps: list[Footstep], j: int) -> list[Footstep]:
    """A copy of ``steps`` with one stride (a footstep of each side) added after footstep ``j``:
    the new ones lie halfway between their side's neighbours (j − 1 and j + 1, j and j + 2), so the
    feet still alternate and the steps there are halved."""
    if not 2 <= j <= len(steps) - 3:
        raise PlanError(f"footstep {j}: a stride is added after footsteps 2..{len(steps) - 3} "
                        "(between a walking footstep and the standing feet at the end)")

    def mid(a: Footstep, b: Footstep) -> Footstep:
        return Footstep(0.5 * (a.x + b.x), 0.5 * (a.z + b.z), _angle_mid(a.psi, b.psi), a.side)

    out = [Footstep(s.x, s.z, s.psi, s.side) for s in steps]
    return out[:j + 1] + [mid(steps[j - 1], steps[j + 1]), mid(steps[j], steps[j + 2])] + out[j + 1:]


def with_stride_deleted(steps: list[Footstep], j: int) -> list[Footstep]:
    """A copy of ``steps`` without footsteps ``j`` and ``j + 1`` (one stride: the feet still
    alternate); the standing feet at both ends stay."""
    if not 2 <= j <= len(steps) - 4:
        raise PlanError(f"footstep {j}: a stride deleted starts at footsteps 2..{len(steps) - 4} "
                        "(the standing feet at both ends stay)")
    out = [Footstep(s.x, s.z, s.psi, s.side) for s in steps]
    return out[:j] + out[j + 2:]
