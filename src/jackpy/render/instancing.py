"""Turn a :class:`Scene` into per-mesh batches of GPU instance records (pure numpy).

Every lit thing the renderer draws is an instance of a cached mesh: draw items of their own mesh,
skeleton spheres and sticks of a unit sphere and cylinder, triads and goal-marker arrows of a unit
arrow. An instance record holds the model matrix, its normal matrix, the colour, a highlight
weight and the pick id (0 = not pickable), laid out as the vertex shader reads them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from jackpy.render.mesh import Mesh, arrow, cylinder, uv_sphere
from jackpy.render.scene import Color, DrawItem, GoalMarker, Scene, Spheres, Sticks, Triad

SPHERE = "jackpy:sphere"
CYLINDER = "jackpy:cylinder"
ARROW = "jackpy:arrow"

BUILTIN_MESHES: dict[str, Mesh] = {
    SPHERE: uv_sphere(1.0, rings=14, sectors=24),
    CYLINDER: cylinder(1.0, 1.0, sectors=16),
    ARROW: arrow(1.0, shaft_radius=0.035, head_radius=0.09, head_length=0.25),
}
"""Unit meshes for the instanced primitives: sphere radius 1, cylinder and arrow along +y, length 1."""

INSTANCE_DTYPE = np.dtype([
    ("model", np.float32, (16,)),   # column-major mat4
    ("normal", np.float32, (9,)),   # column-major mat3
    ("color", np.float32, (4,)),
    ("highlight", np.float32),
    ("pick", np.int32),
])
INSTANCE_FORMAT = "16f 9f 4f 1f 1i /i"
INSTANCE_ATTRIBUTES = ("in_model", "in_normal_matrix", "in_color", "in_highlight", "in_pick")

_AXIS_COLORS = np.array([[0.9, 0.2, 0.2, 1.0], [0.25, 0.8, 0.25, 1.0], [0.25, 0.4, 0.95, 1.0]])


@dataclass
class InstanceBatch:
    """Instances of one mesh drawn in one call; ``wireframe`` adds an edge overlay."""

    mesh: str
    records: np.ndarray
    wireframe: bool = False


@dataclass
class FrameBatches:
    """A scene sorted into render passes."""

    opaque: list[InstanceBatch] = field(default_factory=list)
    wireframe: list[InstanceBatch] = field(default_factory=list)
    transparent: list[DrawItem] = field(default_factory=list)


def rgba(color: Color | np.ndarray, n: int) -> np.ndarray:
    """(n, 4) float32 colours from one RGB(A) colour or n of them; alpha defaults to 1."""
    c = np.asarray(color, np.float32)
    c = np.broadcast_to(c, (n, c.shape[-1])) if c.ndim == 1 else c.reshape(n, -1)
    if c.shape[1] == 3:
        c = np.concatenate([c, np.ones((n, 1), np.float32)], axis=1)
    return np.ascontiguousarray(c)


def pick_array(ids: Sequence[int | None] | int | None, n: int) -> np.ndarray:
    """(n,) int32 pick ids, 0 where the id is None."""
    if ids is None or isinstance(ids, (int, np.integer)):
        return np.full(n, 0 if ids is None else int(ids), np.int32)
    return np.array([0 if i is None else int(i) for i in ids], np.int32).reshape(n)


def normal_matrices(models: np.ndarray) -> np.ndarray:
    """(N, 3, 3) cofactor matrices of the models' linear parts, which map normals correctly.

    The cofactor is ``det(A) inv(A)^T``: the shader renormalises, so the scale does not matter,
    and it stays finite for degenerate (zero-length) instances.
    """
    a = models[:, :3, :3]
    i, j = [1, 2, 0], [2, 0, 1]  # the cross products by index (np.cross costs more per call)
    p, q = a[:, i, :], a[:, j, :]  # rows rolled: columns k of p x q by rows
    out = np.empty_like(a)
    for k, (u, v) in enumerate(((1, 2), (2, 0), (0, 1))):
        out[:, :, k] = p[:, :, u] * q[:, :, v] - q[:, :, u] * p[:, :, v]
    return out


def pack(models: np.ndarray, colors: np.ndarray, pick: np.ndarray,
         highlight: np.ndarray | float = 0.0) -> np.ndarray:
    """Instance records from (N, 4, 4) model matrices, (N, 4) colours and (N,) pick ids."""
    models = np.asarray(models, float).reshape(-1, 4, 4)
    n = len(models)
    rec = np.empty(n, INSTANCE_DTYPE)
    rec["model"] = models.transpose(0, 2, 1).reshape(n, 16)
    rec["normal"] = normal_matrices(models).transpose(0, 2, 1).reshape(n, 9)
    rec["color"] = colors
    rec["highlight"] = highlight
    rec["pick"] = pick
    return rec


def frames_along(directions: np.ndarray) -> np.ndarray:
    """(N, 3, 3) rotations whose y column is each unit direction (x, z chosen orthonormal)."""
    y = np.asarray(directions, float).reshape(-1, 3)
    helper = np.where(np.abs(y[:, [0]]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 0.0, 1.0]])
    z = np.cross(helper, y)
    z /= np.linalg.norm(z, axis=1, keepdims=True)
    x = np.cross(y, z)
    return np.stack([x, y, z], axis=2)


def sphere_models(centers: np.ndarray, radius: float | np.ndarray) -> np.ndarray:
    """(N, 4, 4) models placing the unit sphere at ``centers`` with ``radius`` m."""
    c = np.asarray(centers, float).reshape(-1, 3)
    r = np.broadcast_to(np.asarray(radius, float), (len(c),))
    m = np.zeros((len(c), 4, 4))
    m[:, [0, 1, 2], [0, 1, 2]] = r[:, None]
    m[:, :3, 3] = c
    m[:, 3, 3] = 1.0
    return m


def segment_models(starts: np.ndarray, ends: np.ndarray, radius: float | np.ndarray) -> np.ndarray:
    """(N, 4, 4) models stretching a unit +y mesh from ``starts`` to ``ends``, scaled by ``radius``.

    Zero-length segments collapse to a point (an invisible instance).
    """
    a = np.asarray(starts, float).reshape(-1, 3)
    b = np.asarray(ends, float).reshape(-1, 3)
    v = b - a
    length = np.linalg.norm(v, axis=1)
    safe = np.where(length > 0.0, length, 1.0)
    rot = frames_along(np.where(length[:, None] > 0.0, v / safe[:, None], [[0.0, 1.0, 0.0]]))
    r = np.broadcast_to(np.asarray(radius, float), (len(a),))
    m = np.zeros((len(a), 4, 4))
    m[:, :3, :3] = rot * np.stack([r, length, r], axis=1)[:, None, :]
    m[:, :3, 3] = a
    m[:, 3, 3] = 1.0
    return m


def _sphere_records(s: Spheres) -> np.ndarray:
    models = sphere_models(s.centers, s.radius)
    n = len(models)
    return pack(models, rgba(s.color, n), pick_array(s.pick_ids, n))


def _stick_records(s: Sticks) -> np.ndarray:
    models = segment_models(s.starts, s.ends, s.radius)
    n = len(models)
    return pack(models, rgba(s.color, n), pick_array(s.pick_ids, n))


def _triad_records(t: Triad) -> np.ndarray:
    frame = np.asarray(t.transform, float)
    origin = frame[:3, 3]
    axes = frame[:3, :3].T  # rows: the frame's x, y, z axes in world
    models = segment_models(np.tile(origin, (3, 1)), origin + t.size * axes / np.linalg.norm(
        axes, axis=1, keepdims=True), t.size)
    return pack(models, _AXIS_COLORS, pick_array(t.pick_id, 3))


def _marker_records(g: GoalMarker) -> tuple[np.ndarray, np.ndarray | None]:
    p = np.asarray(g.position, float)
    e = np.eye(3) * g.size
    cross = segment_models(p - e, p + e, 0.12 * g.size)
    color = rgba(g.color, 3)
    sticks = pack(cross, color, pick_array(g.pick_id, 3))
    if g.direction is None:
        return sticks, None
    d = np.asarray(g.direction, float)
    tip = p + 2.0 * g.size * d / np.linalg.norm(d)
    head = pack(segment_models(p, tip, 2.0 * g.size), color[:1], pick_array(g.pick_id, 1))
    return sticks, head


def _item_colors(items: Sequence[DrawItem]) -> np.ndarray:
    try:  # the common case, every colour RGBA: one array, no per-item broadcasting
        colors = np.array([tuple(i.color) for i in items], np.float32).reshape(len(items), -1)
        if colors.shape[1] == 4:
            return colors
    except ValueError:  # a mix of RGB and RGBA
        pass
    return np.concatenate([rgba(i.color, 1) for i in items])


def _item_records(items: Sequence[DrawItem]) -> np.ndarray:
    models = np.array([i.transform for i in items], float).reshape(-1, 4, 4)
    colors = _item_colors(items) if items else np.zeros((0, 4))
    pick = pick_array([i.pick_id for i in items], len(items))
    highlight = np.array([float(i.highlighted) for i in items])
    return pack(models, colors, pick, highlight)


def _group(keys: list[str], parts: list[np.ndarray]) -> list[InstanceBatch]:
    grouped: dict[str, list[np.ndarray]] = {}
    for key, rec in zip(keys, parts):
        if len(rec):
            grouped.setdefault(key, []).append(rec)
    return [InstanceBatch(k, v[0] if len(v) == 1 else np.concatenate(v)) for k, v in grouped.items()]


def build_batches(scene: Scene) -> FrameBatches:
    """Sort a scene into opaque batches, wireframe-overlay batches and transparent items."""
    keys: list[str] = []
    parts: list[np.ndarray] = []
    opaque_items = [i for i in scene.items if not i.transparent]
    for item, rec in zip(opaque_items, _item_records(opaque_items)):
        keys.append(item.mesh)
        parts.append(rec[None])
    keys += [SPHERE] * len(scene.spheres)
    parts += [_sphere_records(s) for s in scene.spheres]
    keys += [CYLINDER] * len(scene.sticks)
    parts += [_stick_records(s) for s in scene.sticks]
    keys += [ARROW] * len(scene.triads)
    parts += [_triad_records(t) for t in scene.triads]
    for marker in scene.markers:
        sticks, head = _marker_records(marker)
        keys.append(CYLINDER)
        parts.append(sticks)
        if head is not None:
            keys.append(ARROW)
            parts.append(head)
    wire = [i for i in opaque_items if i.wireframe]
    return FrameBatches(
        opaque=_group(keys, parts),
        wireframe=_group([i.mesh for i in wire], [r[None] for r in _item_records(wire)]),
        transparent=[i for i in scene.items if i.transparent],
    )


def back_to_front(items: Sequence[DrawItem], view: np.ndarray,
                  local_centers: dict[str, np.ndarray]) -> list[DrawItem]:
    """Transparent items ordered farthest first by the view depth of their mesh's centre."""
    def depth(item: DrawItem) -> float:
        c = np.append(local_centers[item.mesh], 1.0)
        return float((view @ (np.asarray(item.transform, float) @ c))[2])

    return sorted(items, key=depth)


def item_batches(items: Sequence[DrawItem]) -> list[InstanceBatch]:
    """Runs of consecutive items with the same mesh and wireframe flag, keeping their order."""
    batches: list[InstanceBatch] = []
    for item, rec in zip(items, _item_records(items)):
        last = batches[-1] if batches else None
        if last is not None and (last.mesh, last.wireframe) == (item.mesh, item.wireframe):
            last.records = np.concatenate([last.records, rec[None]])
        else:
            batches.append(InstanceBatch(item.mesh, rec[None], item.wireframe))
    return batches
