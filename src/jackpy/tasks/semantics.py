"""Object semantics: the sidecar ``NAME.semantics.json`` next to a scene (one per CAD object, named
after the object) and the knowledge base that resolves task names to geometry ([SH6] §6.1.4,
§6.2.3, §6.3.1; digest task-commands.md §2.7, §5.7). See docs/tasks.md for the format.

Everything is in the object frame, metres, y up, unless a site says ``"unit": "cm"``. Names fold
case and treat ``-`` and ``_`` alike (the book writes ``twf-1``, ``twF-1`` and ``twf_1``).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from jackpy.errors import JackpyError, ParseError

UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001}


class TaskError(JackpyError):
    """A task cannot be grounded or carried out (unknown name, not a control, does not fit …)."""

    exit_code = 2


def fold(name: str) -> str:
    """The canonical form of a task name: lower case, ``-`` as ``_``."""
    return name.strip().lower().replace("-", "_")


@dataclass
class Control:
    """A manually operated control: its site, DOF axis (object frame), limits and named states
    (degrees of the DOF), and its current state."""

    name: str
    kind: str
    site: str
    axis: np.ndarray
    states: dict[str, float]
    limits: tuple[float, float]
    state: str
    width_cm: float = 1.0
    angle_deg: float = 0.0

    def value_of(self, state: str) -> float:
        if state not in self.states:
            raise TaskError(f"control {self.name!r} has no state {state!r} (states: {', '.join(self.states)})")
        return self.states[state]


@dataclass
class Semantics:
    """The parsed sidecar of one object."""

    name: str
    aliases: dict[str, str] = field(default_factory=dict)
    sites: dict[str, np.ndarray] = field(default_factory=dict)
    controls: dict[str, Control] = field(default_factory=dict)
    handles: list[dict[str, Any]] = field(default_factory=list)
    support_surfaces: list[dict[str, Any]] = field(default_factory=list)
    self_supporting_faces: list[dict[str, Any]] = field(default_factory=list)
    container: dict[str, Any] | None = None
    longitudinal_axis: np.ndarray | None = None
    articulations: list[dict[str, Any]] = field(default_factory=list)
    stands: dict[str, dict[str, Any]] = field(default_factory=dict)


def _vec(v: Any, n: int, where: str) -> np.ndarray:
    a = np.asarray(v, dtype=float)
    if a.shape != (n,) or not np.all(np.isfinite(a)):
        raise ValueError(f"{where}: expected {n} finite numbers")
    return a


def parse(d: dict[str, Any], name: str) -> Semantics:
    """Check and convert a sidecar dict (``ValueError`` with the key path on bad content)."""
    if d.get("jackpy_semantics") != 1:
        raise ValueError("jackpy_semantics: expected version 1")
    s = Semantics(str(d.get("name", name)))
    s.aliases = {fold(k): fold(v) for k, v in d.get("aliases", {}).items()}
    for k, v in d.get("sites", {}).items():
        unit = v.get("unit", "m")
        if unit not in UNITS:
            raise ValueError(f"sites.{k}.unit: expected one of m, cm, mm")
        s.sites[fold(k)] = _vec(v.get("position"), 3, f"sites.{k}.position") * UNITS[unit]
    for k, v in d.get("controls", {}).items():
        where = f"controls.{k}"
        states = {str(sk): float(sv) for sk, sv in v.get("states", {}).items()}
        if not states:
            raise ValueError(f"{where}.states: a control needs named states")
        site = fold(v.get("site", k))
        if site not in s.sites:
            raise ValueError(f"{where}.site: no site {site!r}")
        lim = v.get("limits", [min(states.values()), max(states.values())])
        state = str(v.get("state", next(iter(states))))
        if state not in states:
            raise ValueError(f"{where}.state: {state!r} is not one of its states")
        axis = _vec(v.get("axis", [1, 0, 0]), 3, f"{where}.axis")
        c = Control(fold(k), str(v.get("kind", "control")), site, axis / np.linalg.norm(axis), states,
                    (float(lim[0]), float(lim[1])), state, float(v.get("width_cm", 1.0)), states[state])
        for sv in states.values():
            if not c.limits[0] <= sv <= c.limits[1]:
                raise ValueError(f"{where}.states: {sv}° outside the limits {c.limits}")
        s.controls[c.name] = c
    s.handles = list(d.get("handles", []))
    for i, h in enumerate(s.handles):
        if fold(h.get("site", "")) not in s.sites:
            raise ValueError(f"handles[{i}].site: no site {h.get('site')!r}")
    s.support_surfaces = [dict(x) for x in d.get("support_surfaces", [])]
    for i, x in enumerate(s.support_surfaces):
        x["point"] = _vec(x.get("point"), 3, f"support_surfaces[{i}].point")
        x["normal"] = _vec(x.get("normal", [0, 1, 0]), 3, f"support_surfaces[{i}].normal")
        x["polygon"] = np.asarray(x.get("polygon"), dtype=float).reshape(-1, 2)
    s.self_supporting_faces = [dict(x) for x in d.get("self_supporting_faces", [])]
    for i, x in enumerate(s.self_supporting_faces):
        x["normal"] = _vec(x.get("normal"), 3, f"self_supporting_faces[{i}].normal")
        x.setdefault("salience", 1.0)
    if "container" in d:
        c = dict(d["container"])
        c["min"] = _vec(c.get("interior", {}).get("min"), 3, "container.interior.min")
        c["max"] = _vec(c.get("interior", {}).get("max"), 3, "container.interior.max")
        c["up"] = _vec(c.get("up", [0, 1, 0]), 3, "container.up")
        s.container = c
    if "longitudinal_axis" in d:
        s.longitudinal_axis = _vec(d["longitudinal_axis"], 3, "longitudinal_axis")
    s.articulations = list(d.get("articulations", []))
    s.stands = {k: dict(v) for k, v in d.get("stands", {}).items()}
    return s


def load(path: str | os.PathLike) -> Semantics:
    """Read one sidecar; ParseError with file:line:col on bad JSON, the key path on bad content."""
    p = Path(path)
    text = p.read_text(encoding="utf-8")
    try:
        d = json.loads(text)
    except json.JSONDecodeError as e:
        raise ParseError(f"expected JSON: {e.msg}", str(p), e.lineno, e.colno) from None
    try:
        return parse(d, p.name.split(".")[0])
    except (ValueError, TypeError, AttributeError) as e:
        raise ParseError(str(e), str(p)) from None


def suggest(mesh_vertices: np.ndarray, mesh_faces: np.ndarray, up: np.ndarray = np.array([0.0, 1.0, 0.0]),
            max_faces: int = 6) -> dict[str, Any]:
    """Proposals for the author to confirm: self-supporting faces (trimesh stable poses: the face
    normal that points down in each pose, with its probability), upward support surfaces (facets
    within 10° of up) and the longitudinal axis (longest axis of the oriented bounding box)."""
    import trimesh

    m = trimesh.Trimesh(mesh_vertices, mesh_faces, process=True)
    faces = []
    if m.is_watertight:
        poses, probs = trimesh.poses.compute_stable_poses(m, n_samples=1)
        for T, pr in list(zip(poses, probs))[:max_faces]:
            down = T[:3, :3].T @ np.array([0.0, 0.0, -1.0])  # trimesh rests poses on z = 0
            faces.append({"normal": np.round(down, 6).tolist(), "probability": float(pr)})
    surfaces = []
    for idx, n in zip(m.facets, m.facets_normal):
        if n @ up >= np.cos(np.radians(10.0)):
            surfaces.append({"normal": n.tolist(), "area": float(m.area_faces[idx].sum()),
                             "point": m.vertices[m.faces[idx[0]][0]].tolist()})
    obb = m.bounding_box_oriented
    ext = obb.primitive.extents
    axis = obb.primitive.transform[:3, int(np.argmax(ext))]
    return {"self_supporting_faces": faces, "support_surfaces": sorted(surfaces, key=lambda s: -s["area"]),
            "longitudinal_axis": axis.tolist()}
