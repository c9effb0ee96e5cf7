"""Workplace scene files: imported CAD objects with their placement and named sites, where the
figures stand, and the analyses to run (``jackpy analyze``).

The file is JSON (``*.json``), written atomically::

    {"jackpy_scene": 1,
     "objects": [{"name": "desk", "source": "desk.obj", "units": "mm", "up": "z",
                  "matrix": [[...4x4...]],            # or "position": [x,y,z], "rotation_deg": [rx,ry,rz]
                  "colour": [0.7, 0.7, 0.72],
                  "sites": {"switch": {"position": [x, y, z]}}}],   # object frame, metres, y up
     "figure": {"position": [x, z], "heading_deg": 0},                # where figures stand (floor y = 0)
     "analysis": {"reach": ["desk.switch"], "view": ["panel.display"], "load_kg": 5, "hand": "right"}}

``source`` is relative to the scene file's folder. Site positions are metres in the object frame;
``rotation_deg`` is fixed-axis x, then y, then z rotation in degrees. Figures face +z at heading 0.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from jackpy import jsonfile
from jackpy.atomic import atomic_write_text
from jackpy.errors import JackpyError, SessionError
from jackpy.peabody.model import Environment, Figure
from jackpy.peabody.transforms import euler_xyz, rotation, translation
from jackpy.scene.cad import UNITS, UP_AXES, CADObject, import_cad

FORMAT_VERSION = 1


@dataclass
class Stand:
    """Where a figure stands: floor point ``(x, z)`` metres and heading (radians about +y; 0 faces +z)."""

    position: tuple[float, float] = (0.0, 0.0)
    heading: float = 0.0


@dataclass
class AnalysisPlan:
    """The analyses a scene asks for: reach and view targets (``object.site`` or ``object``), hand
    load (kg) and the reaching hand (``"right"``/``"left"``)."""

    reach: list[str] = field(default_factory=list)
    view: list[str] = field(default_factory=list)
    load_kg: float = 0.0
    hand: str = "right"


@dataclass
class Workplace:
    """A scene: the environment of CAD objects, where figures stand and the analysis plan."""

    env: Environment = field(default_factory=Environment)
    stand: Stand = field(default_factory=Stand)
    plan: AnalysisPlan = field(default_factory=AnalysisPlan)
    path: Path | None = None

    @property
    def objects(self) -> dict[str, CADObject]:
        """The CAD objects of the environment, by name."""
        return {n: f for n, f in self.env.figures.items() if isinstance(f, CADObject)}

    def site_position(self, ref: str) -> np.ndarray:
        """World position (metres) of ``object.site``, or of an object's bounding-box centre."""
        return resolve_target(self.env, ref)[1]


def resolve_target(env: Environment, ref: str) -> tuple[CADObject, np.ndarray]:
    """The object and world point (metres) named by ``object.site`` or ``object`` (bounding-box
    centre). Raises :class:`~jackpy.errors.SessionError` for an unknown name."""
    name, _, site = ref.partition(".")
    obj = env.figures.get(name)
    if not isinstance(obj, CADObject):
        known = ", ".join(n for n, f in env.figures.items() if isinstance(f, CADObject)) or "none"
        raise SessionError(f"no object named {name!r} (objects: {known})")
    if not site:
        lo, hi = obj.mesh().bounds()
        return obj, (obj.location @ np.append((lo + hi) / 2, 1.0))[:3]
    if site not in obj.user_sites():
        raise SessionError(f"object {name!r} has no site {site!r} (sites: {', '.join(obj.user_sites()) or 'none'})")
    return obj, obj.site_position(site)


def stand_figure(figure: Figure, stand: Stand) -> None:
    """Place ``figure`` (keeping its posture) so its lowest point rests on the floor (y = 0) at
    ``stand.position``, rotated by ``stand.heading`` about +y. The lowest point is the lowest mesh
    vertex, or the lowest segment origin or site when segments have no geometry."""
    figure.location = np.eye(4)
    world = figure.world_transforms()
    low = np.inf
    for name, t in world.items():
        seg = figure.segments[name]
        pts = [site.location[:3, 3] for site in seg.sites.values()] or [np.zeros(3)]
        local = np.array(pts)
        if seg.psurf is not None and seg.psurf.mesh is not None:
            local = seg.psurf.posed_mesh().vertices
        low = min(low, float((local @ t[:3, :3].T + t[:3, 3])[:, 1].min()))
    x, z = stand.position
    figure.location = translation(x, -low, z) @ rotation("y", stand.heading)


def load_workplace(path: str | os.PathLike) -> Workplace:
    """Read a scene file and import its objects. Errors (:class:`SessionError`) name the file and
    the part at fault: ``file:line:column`` for JSON syntax, the key path for a value of the wrong
    shape (``objects[2].units: expected one of m, cm, mm, in, found 'km'``)."""
    p = Path(path)
    try:
        data = jsonfile.load(p, SessionError)
    except FileNotFoundError:
        raise SessionError(f"{p}: no such scene file") from None
    except OSError as exc:
        raise SessionError(f"{p}: cannot read the scene: {exc.strerror or exc}") from None
    except ValueError:  # a name with a NUL byte
        raise SessionError(f"{p!s}: not a valid file name") from None
    if not isinstance(data, dict) or data.get("jackpy_scene") != FORMAT_VERSION:
        raise SessionError(f"{p}: not a jackpy scene file (missing \"jackpy_scene\": {FORMAT_VERSION})")
    wp = Workplace(path=p)
    try:
        objects = jsonfile.arr(data.get("objects", []), "objects")
        specs = [_object_spec(od, f"objects[{k}]") for k, od in enumerate(objects)]
        fd = jsonfile.obj(data.get("figure", {}), "figure")
        pos = jsonfile.vector(fd.get("position", [0.0, 0.0]), "figure.position", 2)
        heading = jsonfile.num(fd.get("heading_deg", 0.0), "figure.heading_deg")
        ad = jsonfile.obj(data.get("analysis", {}), "analysis")
        reach = [jsonfile.string(s, f"analysis.reach[{k}]")
                 for k, s in enumerate(jsonfile.arr(ad.get("reach", []), "analysis.reach"))]
        view = [jsonfile.string(s, f"analysis.view[{k}]")
                for k, s in enumerate(jsonfile.arr(ad.get("view", []), "analysis.view"))]
        load_kg = jsonfile.num(ad.get("load_kg", 0.0), "analysis.load_kg", 0.0)
        hand = jsonfile.string(ad.get("hand", "right"), "analysis.hand", ("right", "left"))
    except jsonfile.Invalid as exc:
        raise jsonfile.schema_error(SessionError, str(p), exc) from None
    for k, spec in enumerate(specs):
        try:
            wp.env.add(_object_from_spec(spec, p.parent))
        except JackpyError as exc:  # unreadable CAD file, bad site name, a second object of that name
            raise SessionError(f"{p}: objects[{k}]: {exc}") from None
    wp.stand = Stand((float(pos[0]), float(pos[1])), float(np.radians(heading)))
    wp.plan = AnalysisPlan(reach, view, load_kg, hand)
    return wp


def save_workplace(wp: Workplace, path: str | os.PathLike) -> None:
    """Write ``wp`` to ``path`` atomically; object sources are stored relative to its folder."""
    p = Path(path)
    objects = []
    for obj in wp.objects.values():
        src = Path(obj.settings.source)
        try:
            src_text = os.path.relpath(src.resolve(), p.parent.resolve())
        except ValueError:  # another drive
            src_text = str(src.resolve())
        objects.append({
            "name": obj.name, "source": Path(src_text).as_posix(), "units": obj.settings.units,
            "up": obj.settings.up, "matrix": obj.location.tolist(), "colour": list(obj.colour),
            "sites": {n: {"matrix": s.location.tolist()} for n, s in obj.user_sites().items()},
        })
    data: dict[str, Any] = {
        "jackpy_scene": FORMAT_VERSION,
        "objects": objects,
        "figure": {"position": list(wp.stand.position), "heading_deg": float(np.degrees(wp.stand.heading))},
        "analysis": {"reach": wp.plan.reach, "view": wp.plan.view, "load_kg": wp.plan.load_kg,
                     "hand": wp.plan.hand},
    }
    atomic_write_text(p, json.dumps(data, indent=1) + "\n")
    wp.path = p


def _object_spec(od: Any, where: str) -> dict[str, Any]:
    """The checked content of one entry of ``objects`` (raises :class:`jsonfile.Invalid`)."""
    od = jsonfile.obj(od, where)
    spec: dict[str, Any] = {
        "source": jsonfile.string(jsonfile.required(od, "source", where), f"{where}.source"),
        "units": jsonfile.string(od.get("units", "m"), f"{where}.units", UNITS),
        "up": jsonfile.string(od.get("up", "y"), f"{where}.up", UP_AXES),
        "name": None if od.get("name") is None else jsonfile.string(od["name"], f"{where}.name"),
        "location": _transform_from_json(od, where),
        "colour": None, "sites": {},
    }
    if not spec["source"] or "\0" in spec["source"]:
        raise jsonfile.Invalid(f"{where}.source", "expected a file name")
    if spec["name"] == "":
        raise jsonfile.Invalid(f"{where}.name", "expected a name, found ''")
    if "colour" in od:
        spec["colour"] = tuple(float(c) for c in jsonfile.vector(od["colour"], f"{where}.colour", 3))
    for name, sd in jsonfile.obj(od.get("sites", {}), f"{where}.sites").items():
        swhere = f"{where}.sites.{name}"
        spec["sites"][name] = _transform_from_json(jsonfile.obj(sd, swhere), swhere)
    return spec


def _object_from_spec(spec: dict[str, Any], base: Path) -> CADObject:
    src = Path(spec["source"])
    obj = import_cad(src if src.is_absolute() else base / src, spec["units"], spec["up"], spec["name"])
    obj.location = spec["location"]
    if spec["colour"] is not None:
        obj.colour = spec["colour"]
    for name, t in spec["sites"].items():
        obj.add_site(name, t[:3, 3], t[:3, :3])
    return obj


def _transform_from_json(d: dict[str, Any], where: str) -> np.ndarray:
    """``matrix`` (4x4) or ``position`` and ``rotation_deg`` of ``d`` (raises jsonfile.Invalid)."""
    if "matrix" in d:
        t = jsonfile.matrix(d["matrix"], f"{where}.matrix", 4, 4)
        if not np.allclose(t[3], [0, 0, 0, 1]) or abs(np.linalg.det(t[:3, :3])) < 1e-12:
            raise jsonfile.Invalid(f"{where}.matrix", "expected a placement (last row 0 0 0 1, invertible)")
        return t
    t = euler_xyz(tuple(np.radians(jsonfile.vector(d.get("rotation_deg", [0, 0, 0]), f"{where}.rotation_deg", 3))))
    t[:3, 3] = jsonfile.vector(d.get("position", [0, 0, 0]), f"{where}.position", 3)
    return t
