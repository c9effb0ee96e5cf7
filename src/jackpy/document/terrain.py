"""The scene's terrain (Sims 1987, Ch. 8): kept in the document, saved with it, undone with it.

A document has at most one terrain (:class:`jackpy.locomotion.terrain.Terrain`). It lives in
:attr:`Document.extras` under ``"terrain"`` as its JSON form (:meth:`Terrain.to_dict`), so the
session file carries it (every height exactly: JSON floats round-trip), undo and redo restore it,
and nothing else in the document needs to know about it. :func:`terrain_of` gives the object,
rebuilt only when the stored data changed (a load, an undo, an open).

The workbench reaches it from Scene → Load terrain... (a ``.json`` grid, a ``.png`` heightmap or a
triangle mesh sampled into a grid, :func:`terrain_from_file`), Scene → Example terrain
(:func:`example_terrain`) and Scene → Remove terrain, each one undo step.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

import numpy as np

from jackpy.errors import ParseError
from jackpy.locomotion.terrain import Terrain
from jackpy.locomotion.terrain import load as load_terrain_file

if TYPE_CHECKING:
    from jackpy.document.document import Document

KEY = "terrain"
_CACHE = "_terrain_cache"
MESH_EXTENSIONS = (".stl", ".obj", ".ply", ".off", ".glb", ".gltf")
"""Triangle meshes a terrain can be sampled from (trimesh's formats; metres, y up)."""
MESH_CELL = 0.05
"""Grid spacing a mesh terrain is sampled at, m."""


def terrain_of(doc: "Document") -> Terrain | None:
    """The document's terrain, or None."""
    data = getattr(doc, "extras", {}).get(KEY)  # (extras: Document's tool data, saved and undone)
    if data is None:
        return None
    cached = doc.__dict__.get(_CACHE)
    if cached is not None and cached[0] is data:
        return cached[1]
    terrain = Terrain.from_dict(data, f"{doc.path or 'document'}: extras.terrain")
    doc.__dict__[_CACHE] = (data, terrain)
    return terrain


def set_terrain(doc: "Document", terrain: Terrain | None, label: str | None = None) -> None:
    """Give the document ``terrain`` (None removes it) as one undoable command."""

    def act() -> None:
        if terrain is None:
            doc.extras.pop(KEY, None)
            doc.__dict__.pop(_CACHE, None)
            return
        data = terrain.to_dict()
        doc.extras[KEY] = data
        doc.__dict__[_CACHE] = (data, terrain)

    doc.command(label or ("remove terrain" if terrain is None else f"set terrain {terrain.name}"), act)
    doc.changed = True


def terrain_from_file(path: str | os.PathLike[str]) -> Terrain:
    """A terrain from a file: a ``.json`` grid or ``.png`` heightmap (see
    :func:`jackpy.locomotion.terrain.load`), or a triangle mesh of :data:`MESH_EXTENSIONS` (metres,
    y up) sampled every :data:`MESH_CELL` by vertical rays; ParseError for a bad file."""
    name = os.path.basename(str(path))
    if not name.lower().endswith(MESH_EXTENSIONS):
        return load_terrain_file(path)
    import trimesh

    try:
        mesh = trimesh.load(str(path), force="mesh")
    except Exception as exc:  # trimesh raises many kinds for unreadable files
        raise ParseError(f"cannot read terrain mesh: {exc}", str(path)) from None
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise ParseError("cannot read terrain mesh: no triangles", str(path))
    return Terrain.from_mesh(mesh.vertices, mesh.faces, MESH_CELL, name=os.path.splitext(name)[0])


def load_terrain(doc: "Document", path: str | os.PathLike[str]) -> Terrain:
    """Read a terrain file (:func:`terrain_from_file`) into the document (undoable); ParseError
    for a bad file (the document is left as it was)."""
    terrain = terrain_from_file(path)
    set_terrain(doc, terrain, f"load terrain {os.path.basename(str(path))}")
    return terrain


def example_terrain() -> Terrain:
    """Gentle rolling ground around the origin, 6 m x 6 m every 10 cm: three crossed sine waves at
    most 9 cm high, no slope steep enough to forbid a foothold (like the creature examples'
    ``rolling_hills``, ``examples/creatures/make_examples.py``)."""
    def height(x: np.ndarray, z: np.ndarray) -> np.ndarray:
        return (0.04 * np.sin(2 * np.pi * z / 1.6) + 0.03 * np.sin(2 * np.pi * x / 1.3 + 0.5)
                + 0.02 * np.sin(2 * np.pi * (x + z) / 2.1))

    terrain = Terrain.from_function(height, (-3.0, 3.0), (-3.0, 3.0), 0.1, name="example hills")
    terrain.heights = np.round(terrain.heights, 5)
    return terrain
