"""CAD import through trimesh: units, up axis, placement, named sites, display copies.

An imported CAD model becomes a :class:`CADObject`: a :class:`~jackpy.peabody.Figure` with one
segment (named like the object) whose :class:`~jackpy.peabody.Psurf` carries the mesh, so it lives
in an :class:`~jackpy.peabody.Environment` like Jack's objects. The psurf keeps the file's own
vertices (file units, file axes) in ``psurf.mesh`` and the import conversion (unit scale, then the
rotation that takes the file's up axis to +y) in ``psurf.transform``, so ``psurf.posed_mesh()`` is
the model in metres, y up, in the object's frame. ``figure.location`` places the object in the world.
The import settings (:class:`ImportSettings`) stay on the object so a scene can be saved and
reloaded.

Large models: the full mesh is kept for queries (clearance, visibility); :meth:`CADObject.display_mesh`
gives a vertex-clustered copy of at most ``max_triangles`` triangles for drawing.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from jackpy.errors import ImportCADError, ParseError
from jackpy.peabody.geometry import Mesh, Psurf
from jackpy.peabody.meshfile import DECLARED_UNITS, read_mesh_file
from jackpy.peabody.model import Environment, Figure, Segment, Site
from jackpy.peabody.transforms import rotation, scaling, translation

#: metres per file unit
UNITS: dict[str, float] = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}

#: rotation taking each supported file up axis to jackpy's +y (4x4)
UP_AXES: dict[str, np.ndarray] = {
    "y": np.eye(4),
    "z": rotation("x", -np.pi / 2),  # z -> y, y -> -z
    "x": rotation("z", np.pi / 2),  # x -> y, y -> -x
}

#: file extensions trimesh reads natively, plus STEP through the optional ``cascadio`` extra
FORMATS: dict[str, str] = {
    ".obj": "obj", ".stl": "stl", ".ply": "ply", ".off": "off", ".gltf": "gltf", ".glb": "glb",
    ".3mf": "3mf", ".dae": "dae", ".step": "step", ".stp": "step",
}

#: the optional packages (module, pip name) each format needs beyond trimesh and numpy
_EXTRAS: dict[str, tuple[tuple[str, str], ...]] = {
    "3mf": (("lxml", "lxml"), ("networkx", "networkx")),
    "dae": (("collada", "pycollada"),),
    "step": (("cascadio", "cascadio"),),
}

#: largest CAD file imported, bytes
MAX_CAD_BYTES = 1024 * 2**20

#: triangle count above which :meth:`CADObject.display_mesh` decimates by default
DISPLAY_TRIANGLES = 200_000


@dataclass(frozen=True)
class ImportSettings:
    """How a CAD file was imported: ``source`` path, file ``units`` (a key of :data:`UNITS`), file
    ``up`` axis (a key of :data:`UP_AXES`)."""

    source: str
    units: str = "m"
    up: str = "y"

    def conversion(self) -> np.ndarray:
        """4x4 transform from file coordinates to the object frame (metres, y up). Formats that
        declare their unit (glTF, 3MF, COLLADA, STEP) are read in metres: ``units`` does not
        scale them again."""
        s = 1.0 if declares_units(self.source) else UNITS[self.units]
        return UP_AXES[self.up] @ scaling(s, s, s)


class CADObject(Figure):
    """A one-segment figure holding an imported CAD mesh, its import settings and named sites.

    Sites live on the single segment, in the object frame (metres, y up); :meth:`site_world` of the
    base class gives them in the world.
    """

    def __init__(self, name: str, settings: ImportSettings, mesh: Mesh) -> None:
        super().__init__(name)
        self.settings = settings
        self.colour: tuple[float, float, float] = (0.7, 0.7, 0.72)
        psurf = Psurf(settings.source, settings.conversion(), mesh)
        seg = Segment(name, psurf=psurf)
        seg.add_site("base")
        self.add_segment(seg)
        self.root = (name, "base")
        self._posed: Mesh | None = None
        self._display: dict[int, Mesh] = {}

    # ----- geometry ------------------------------------------------------------------------------
    @property
    def segment_name(self) -> str:
        return self.name

    def mesh(self) -> Mesh:
        """The full mesh in the object frame, metres, y up (cached)."""
        if self._posed is None:
            psurf = self.segments[self.name].psurf
            assert psurf is not None and psurf.mesh is not None
            self._posed = psurf.posed_mesh()
        return self._posed

    def world_mesh(self) -> Mesh:
        """The full mesh in world coordinates at the current location."""
        return self.mesh().transformed(self.location)

    @property
    def triangle_count(self) -> int:
        return len(self.mesh().faces)

    def display_mesh(self, max_triangles: int = DISPLAY_TRIANGLES) -> Mesh:
        """A copy for drawing with at most ``max_triangles`` triangles (object frame); the full mesh
        itself when it is small enough. Decimated by vertex clustering, cached per budget."""
        if self.triangle_count <= max_triangles:
            return self.mesh()
        if max_triangles not in self._display:
            self._display[max_triangles] = decimate(self.mesh(), max_triangles)
        return self._display[max_triangles]

    # ----- placement -----------------------------------------------------------------------------
    def place(self, position: np.ndarray, rotation_matrix: np.ndarray | None = None) -> None:
        """Put the object frame at world ``position`` (metres) with 3x3 ``rotation_matrix``."""
        t = np.eye(4)
        if rotation_matrix is not None:
            t[:3, :3] = rotation_matrix
        t[:3, 3] = position
        self.location = t

    def move(self, delta: np.ndarray) -> None:
        """Translate the object by ``delta`` (world metres)."""
        self.location = translation(*np.asarray(delta, dtype=float)) @ self.location

    def rotate(self, axis: np.ndarray | str, angle: float, about: np.ndarray | None = None) -> None:
        """Rotate by ``angle`` radians about a world ``axis`` through ``about`` (default: the
        object's origin)."""
        c = self.location[:3, 3].copy() if about is None else np.asarray(about, dtype=float)
        self.location = translation(*c) @ rotation(axis, angle) @ translation(*-c) @ self.location

    # ----- sites ---------------------------------------------------------------------------------
    def add_site(self, name: str, position: np.ndarray, rotation_matrix: np.ndarray | None = None) -> Site:
        """Add (or replace) a named site at ``position`` in the object frame (metres, y up)."""
        if not name or "." in name or name == "base":
            raise ImportCADError(f"object {self.name!r}: bad site name {name!r} (non-empty, no '.', not 'base')")
        t = np.eye(4)
        if rotation_matrix is not None:
            t[:3, :3] = rotation_matrix
        t[:3, 3] = position
        site = self.segments[self.name].add_site(name, t)
        self.topology_changed()
        return site

    def user_sites(self) -> dict[str, Site]:
        """The named sites (every site but the ``base`` root site)."""
        return {n: s for n, s in self.segments[self.name].sites.items() if n != "base"}

    def site_position(self, name: str) -> np.ndarray:
        """World position (metres) of site ``name``."""
        return (self.location @ self.segments[self.name].site(name).location)[:3, 3].copy()


def import_cad(path: str | os.PathLike, units: str = "m", up: str = "y", name: str | None = None) -> CADObject:
    """Read a CAD file into a new :class:`CADObject` (not yet placed in any environment).

    ``units`` are the file's length unit, ``up`` its up axis. Raises
    :class:`~jackpy.errors.ImportCADError` naming the file for an unknown format, a missing
    optional reader, unreadable or malformed content, or an empty model.
    """
    p = Path(path)
    if units not in UNITS:
        raise ImportCADError(f"{p}: unknown units {units!r}; use one of {', '.join(UNITS)}")
    if up not in UP_AXES:
        raise ImportCADError(f"{p}: unknown up axis {up!r}; use one of {', '.join(UP_AXES)}")
    mesh = read_mesh(p)
    return CADObject(name or p.stem, ImportSettings(str(p), units, up), mesh)


def add_cad(env: Environment, path: str | os.PathLike, units: str = "m", up: str = "y",
            name: str | None = None, position: np.ndarray | None = None) -> CADObject:
    """Import a CAD file and add it to ``env`` (at ``position``, metres); ``env`` is untouched if
    anything fails."""
    obj = import_cad(path, units, up, name)
    if obj.name in env.figures:
        raise ImportCADError(f"{path}: the scene already has an object named {obj.name!r}")
    if position is not None:
        obj.place(np.asarray(position, dtype=float))
    env.add(obj)
    return obj


def declares_units(source: str | os.PathLike) -> bool:
    """True when the file's format carries its own unit (read in metres, whatever ``units`` says)."""
    return FORMATS.get(Path(source).suffix.lower()) in DECLARED_UNITS


def read_mesh(path: Path, limit: int = MAX_CAD_BYTES) -> Mesh:
    """The triangles of a CAD file in file axes (all parts concatenated, their scene transforms
    applied): file units for OBJ/STL/PLY/OFF, metres for the formats that declare a unit. Refuses
    with one line what is not a regular file, over ``limit`` bytes, a zip bomb, a false declared
    count, a glTF reference outside its folder, non-finite or out-of-range vertices, bad faces."""
    ext = path.suffix.lower()
    if ext not in FORMATS:
        raise ImportCADError(f"{path}: unsupported CAD format {ext or '(no extension)'!r}; "
                             f"supported: {', '.join(sorted(FORMATS))}")
    kind = FORMATS[ext]
    for module, package in _EXTRAS.get(kind, ()):
        try:
            __import__(module)
        except ImportError:
            raise ImportCADError(f"{path}: reading {kind.upper()} needs the optional package "
                                 f"{package!r} (pip install {package}, or jackpy[cad])") from None
    if not os.path.lexists(path):
        raise ImportCADError(f"{path}: no such file")
    try:
        return read_mesh_file(path, kind, limit)
    except OSError as exc:
        raise ImportCADError(f"{path}: cannot read: {exc.strerror or exc}") from None
    except ParseError as exc:
        raise ImportCADError(str(exc)) from None


def decimate(mesh: Mesh, max_triangles: int) -> Mesh:
    """Vertex-clustering decimation: snap vertices to a grid, merge each cell's vertices into their
    mean, drop collapsed and duplicate triangles. The cell grows until at most ``max_triangles``
    remain. Shape error is at most about one cell (reported by nothing; for display only)."""
    v, f = mesh.vertices, mesh.faces
    lo, hi = mesh.bounds()
    extent = float(np.max(hi - lo)) or 1.0
    # start from the cell at which a closed surface of this extent has ~max_triangles triangles
    cell = extent / max(np.sqrt(max_triangles / 2.0), 1.0)
    while True:
        key = np.floor((v - lo) / cell).astype(np.int64)
        n = key.max(axis=0) + 1
        cells, inverse = np.unique((key[:, 0] * n[1] + key[:, 1]) * n[2] + key[:, 2], return_inverse=True)
        inverse = inverse.reshape(-1)
        ff = inverse[f]
        ff = ff[(ff[:, 0] != ff[:, 1]) & (ff[:, 1] != ff[:, 2]) & (ff[:, 0] != ff[:, 2])]
        rows = np.ascontiguousarray(np.sort(ff, axis=1)).view(np.dtype((np.void, 24))).reshape(-1)
        ff = ff[np.sort(np.unique(rows, return_index=True)[1])]
        if len(ff) <= max_triangles:
            break
        cell *= 1.25
    counts = np.bincount(inverse, minlength=len(cells)).astype(float)
    newv = np.zeros((len(cells), 3))
    for k in range(3):
        newv[:, k] = np.bincount(inverse, weights=v[:, k], minlength=len(cells)) / counts
    used = np.unique(ff)
    remap = np.full(len(cells), -1, dtype=np.int64)
    remap[used] = np.arange(len(used))
    return Mesh(newv[used], remap[ff])

