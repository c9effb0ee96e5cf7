"""A walk plan as plain data: the footsteps a step editor edits and a document keeps (issue 13).

``{"steps": [[x, z, heading_rad, "left" | "right"], ...], "path": [[x, z], ...]}`` (world metres,
radians; σ_0, σ_1 the standing feet, see :class:`~jackpy.locomotion.walk_path.Footstep`). The
``"path"`` is optional (plans saved before the path editor, or planned to a goal, have none): the
floor points, the first where the figure stands, that the path editor's spline passes through and
the footsteps were made from. JSON-ready, so it is saved with a session and copied by undo.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from jackpy.locomotion.walk_gait import SIDES
from jackpy.locomotion.walk_path import Footstep


class PlanError(ValueError):
    """Plan data that is no walk (one line, naming the footstep)."""


Point = tuple[float, float]


def to_data(steps: list[Footstep], path: list[Point] | None = None) -> dict[str, Any]:
    """The plan of ``steps`` (and the ``path`` points they were made from, if any) as JSON-ready data."""
    out: dict[str, Any] = {"steps": [[float(s.x), float(s.z), float(s.psi), s.side] for s in steps]}
    if path is not None:
        out["path"] = [[float(x), float(z)] for x, z in path]
    return out


def _number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and bool(np.isfinite(v))


def path_from_data(data: Any, where: str = "walk plan") -> list[Point] | None:
    """The path points of plan ``data`` (None when it has none); :class:`PlanError` for a
    ``"path"`` that is not two or more ``[x, z]`` points."""
    if not isinstance(data, dict) or data.get("path") is None:
        return None
    rows = data["path"]
    if not isinstance(rows, list) or len(rows) < 2:
        raise PlanError(f"{where}: the path needs two or more [x, z] points")
    for k, row in enumerate(rows):
        if not (isinstance(row, list) and len(row) == 2 and all(_number(v) for v in row)):
            raise PlanError(f"{where}: path point {k} is not [x, z]: {row!r}")
    return [(float(x), float(z)) for x, z in rows]


def from_data(data: Any, where: str = "walk plan") -> list[Footstep]:
    """Footsteps of plan ``data``; :class:`PlanError` for anything that is not a walk (its path
    points too, :func:`path_from_data`)."""
    if not isinstance(data, dict) or not isinstance(data.get("steps"), list):
        raise PlanError(f"{where}: needs {{'steps': [[x, z, heading, side], ...]}}")
    steps = []
    for j, row in enumerate(data["steps"]):
        if not (isinstance(row, list) and len(row) == 4 and row[3] in SIDES
                and all(_number(v) for v in row[:3])):
            raise PlanError(f"{where}: footstep {j} is not [x, z, heading, 'left'|'right']: {row!r}")
        steps.append(Footstep(float(row[0]), float(row[1]), float(row[2]), row[3]))
    if len(steps) < 2 or {steps[0].side, steps[1].side} != set(SIDES):
        raise PlanError(f"{where}: a walk starts from two standing footsteps, one left and one right")
    for j in range(2, len(steps)):
        if steps[j].side == steps[j - 1].side:
            raise PlanError(f"{where}: footstep {j} is on the same side as footstep {j - 1}")
    path_from_data(data, where)
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


# ---------------------------------------------------------------------------- path points
def with_point_added(path: list[Point], k: int, x: float, z: float) -> list[Point]:
    """A copy of ``path`` with point ``(x, z)`` inserted as point ``k`` (1..len: point 0 is where
    the figure stands; ``len(path)`` appends)."""
    if not 1 <= k <= len(path):
        raise PlanError(f"path point {k}: points are added as 1..{len(path)} (0 is where the figure stands)")
    return list(path[:k]) + [(float(x), float(z))] + list(path[k:])


def with_point_moved(path: list[Point], k: int, x: float, z: float) -> list[Point]:
    """A copy of ``path`` with point ``k`` (≥ 1) at ``(x, z)``."""
    if not 1 <= k < len(path):
        raise PlanError(f"path point {k}: only points 1..{len(path) - 1} move (0 is where the figure stands)")
    out = list(path)
    out[k] = (float(x), float(z))
    return out


def with_point_deleted(path: list[Point], k: int) -> list[Point]:
    """A copy of ``path`` without point ``k`` (≥ 1); a path keeps two points at least."""
    if not 1 <= k < len(path):
        raise PlanError(f"path point {k}: only points 1..{len(path) - 1} are deleted (0 is where the figure stands)")
    if len(path) <= 2:
        raise PlanError("a path keeps two points at least (where the figure stands and one more)")
    return list(path[:k]) + list(path[k + 1:])
