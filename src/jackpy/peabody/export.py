"""Posed geometry of figures in world coordinates (metres, y up), as trimesh scenes and files."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from jackpy.atomic import atomic_write_bytes, atomic_write_text
from jackpy.errors import JackpyError
from jackpy.peabody.geometry import Mesh
from jackpy.peabody.model import Environment, Figure

if TYPE_CHECKING:
    import trimesh

#: colour of a segment whose attribute is not a known colour name (RGBA)
DEFAULT_RGBA = (180, 180, 180, 255)
#: file types :func:`export_scene` writes
SCENE_FORMATS = (".glb", ".obj", ".stl", ".ply")


def _figures(item: Environment | Figure) -> list[Figure]:
    return [item] if isinstance(item, Figure) else list(item.figures.values())


def posed_meshes(item: Environment | Figure) -> list[tuple[Figure, str, Mesh]]:
    """``(figure, segment name, mesh in world metres)`` for every segment with a loaded psurf."""
    out = []
    for fig in _figures(item):
        world = fig.world_transforms()
        for seg in fig.segments.values():
            if seg.psurf is not None and seg.psurf.mesh is not None:
                out.append((fig, seg.name, seg.psurf.mesh.transformed(world[seg.name] @ seg.psurf.transform)))
    return out


def rgba(attribute: str | None) -> tuple[int, int, int, int]:
    """RGBA of a Peabody ``attribute`` colour name (X11/CSS names), else :data:`DEFAULT_RGBA`."""
    from PIL import ImageColor

    if attribute:
        try:
            rgb = ImageColor.getrgb(attribute)
        except ValueError:
            return DEFAULT_RGBA
        return (*rgb[:3], 255)
    return DEFAULT_RGBA


def posed_scene(item: Environment | Figure) -> trimesh.Scene:
    """A trimesh scene of the posed geometry: one mesh per segment named ``figure.segment``,
    vertices in world metres, faces coloured by the segment's attribute."""
    import trimesh

    scene = trimesh.Scene()
    for fig, seg_name, mesh in posed_meshes(item):
        tm = trimesh.Trimesh(mesh.vertices, mesh.faces, process=False)
        tm.visual.face_colors = rgba(fig.segments[seg_name].attribute)
        scene.add_geometry(tm, geom_name=f"{fig.name}.{seg_name}", node_name=f"{fig.name}.{seg_name}")
    return scene


def world_bounds(fig: Figure) -> tuple[np.ndarray, str]:
    """World bounding box (2,3) in metres of a figure's posed geometry, and ``"geometry"``; for a
    figure without loaded geometry, the box of its site positions and ``"sites"``."""
    meshes = [m for _, _, m in posed_meshes(fig) if len(m.vertices)]
    if meshes:
        b = np.array([m.bounds() for m in meshes])
        return np.stack([b[:, 0].min(axis=0), b[:, 1].max(axis=0)]), "geometry"
    world = fig.world_transforms()
    points = [(world[s.name] @ site.location)[:3, 3] for s in fig.segments.values() for site in s.sites.values()]
    points += [w[:3, 3] for w in world.values()]
    p = np.array(points)
    return np.stack([p.min(axis=0), p.max(axis=0)]), "sites"


def export_scene(path: str | os.PathLike[str], item: Environment | Figure) -> None:
    """Write the posed geometry to ``.glb`` (a scene), ``.obj`` (objects per segment), ``.stl`` or
    ``.ply`` (one merged mesh), in metres, atomically."""
    import trimesh

    ext = Path(path).suffix.lower()
    if ext not in SCENE_FORMATS:
        raise JackpyError(f"{path}: cannot export geometry as {ext!r} (use {', '.join(SCENE_FORMATS)})")
    scene = posed_scene(item)
    if not scene.geometry:
        raise JackpyError(f"{path}: nothing to export: no segment has loaded geometry")
    if ext == ".glb":
        atomic_write_bytes(path, scene.export(file_type="glb"))
    elif ext == ".obj":
        atomic_write_text(path, scene.export(file_type="obj"))
    else:
        merged = trimesh.util.concatenate(list(scene.geometry.values()))
        atomic_write_bytes(path, merged.export(file_type=ext[1:]))
