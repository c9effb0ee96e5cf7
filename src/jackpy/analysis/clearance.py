"""Collision and clearance between a figure's segments, environment objects, and the figure itself.

Library: python-fcl (the Flexible Collision Library's bindings, also what ``trimesh.collision``
wraps). Each segment's and object's mesh gets one bounding-volume hierarchy (OBBRSS) built once in
its own frame; a frame only moves the BVHs' transforms, so per-frame cost is the narrow phase of the
few pairs that survive the broad phase. fcl gives exact triangle-triangle collision and mesh-mesh
distance with nearest points, which trimesh's own proximity queries (point-to-mesh only, and they
need rtree) do not.

Broad phase (vectorised numpy): every segment has a bounding sphere (segment frame); every object
body has a world AABB (recomputed from its location each frame). Segment-object collision pairs are
tested only when the sphere touches the AABB; segment-segment pairs only when their spheres overlap.

Minimum clearance (issue 8: one exact fcl query between a large segment and a large object can take
milliseconds) prunes with a :class:`~jackpy.analysis.distance_field.DistanceGrid` per body, built on
the first clearance query in the body's frame, that gives sound lower and upper bounds on the
distance from any point to the body's surface:

1. per segment, from its bounding sphere's centre (+- the radius) and the sphere-to-AABB gap;
2. for the segments whose lower bound is within the best upper bound: per vertex, and per triangle
   (its vertices' smallest lower bound minus its cover radius, every point of a triangle being that
   close to a vertex); large triangles whose bound is still in range are refined with points of a
   regular subdivision. Vertex and refined bounds are cached per segment and reused while the
   segment's pose relative to the body is unchanged (exactly the same numbers);
3. one exact fcl query on the few triangles bounded lowest gives an exact upper bound; then one
   exact query on a small BVH, built in the world, of every triangle whose lower bound is within it
   gives the minimum (a triangle left out cannot be nearer). A contact found in the previous query
   is tried first (frame coherence); touching is decided by fcl collision on the triangles that may
   touch.

The result is exact (the same triangle-triangle distances fcl computes for whole meshes).

Self-collision skips adjacent segments (joined by a joint) and, with ``ignore_initial``, pairs
already touching in the posture the checker was built in (their shapes overlap by design, e.g.
vertebrae, or a thigh and the pelvis); that is the usual "allowed collision matrix".

Contact tolerance (issue 16): a checker built with ``erode=d`` shrinks every segment's mesh by
moving each vertex ``d`` inwards along its vertex normal (at most 45 % of the segment's smallest
half-extent, so thin segments such as finger phalanges never turn inside out). A segment of the
eroded figure collides with an object exactly when the real segment presses more than about ``d``
into it: touching a surface passes, passing through a desk or a thin partition does not.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass

import numpy as np

from jackpy.analysis.distance_field import DistanceGrid, triangle_cover_radius
from jackpy.errors import JackpyError
from jackpy.peabody.geometry import Mesh
from jackpy.peabody.model import Figure

try:
    import fcl
except ImportError:  # pragma: no cover - reported when a checker is made
    fcl = None


@dataclass(frozen=True)
class Clearance:
    """Smallest distance (metres) from the figure to an object: the segment and object body that
    attain it and the nearest points on each (world). ``distance`` is 0 when they touch."""

    distance: float
    segment: str
    body: str
    point_on_segment: np.ndarray
    point_on_body: np.ndarray


#: spacing (cover radius, metres) of the points on a segment's triangles whose grid bounds bound it
_BOUND_SPACING = 0.01

#: triangles in the first exact query of a clearance (an upper bound that narrows the rest)
_SEED_TRIANGLES = 8


def _bvh(mesh: Mesh):
    m = fcl.BVHModel()
    m.beginModel(len(mesh.vertices), len(mesh.faces))
    m.addSubModel(np.ascontiguousarray(mesh.vertices, dtype=np.float64),
                  np.ascontiguousarray(mesh.faces, dtype=np.int32))
    m.endModel()
    return m


def _refinement(mesh: Mesh, spacing: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per triangle of ``mesh``: its cover radius ``R`` (see :func:`triangle_cover_radius`), and for
    one with ``R > spacing`` extra points, the vertices of its regular subdivision into ``n²``
    similar triangles (``n = ceil(R / spacing)``), so that every point of it lies within ``R / n`` of
    its vertices or those points. Returns ``(R, extra points, extra count per triangle, R / n)``,
    the extra points in triangle order."""
    v = np.asarray(mesh.vertices, dtype=float)
    f = np.asarray(mesh.faces, dtype=np.int64)
    r = triangle_cover_radius(v, f)
    n = np.maximum(np.ceil(r / spacing).astype(np.int64), 1)
    per_tri: dict[int, np.ndarray] = {}
    for level in np.unique(n[n > 1]):
        ks = np.flatnonzero(n == level)
        i, j = np.meshgrid(np.arange(level + 1), np.arange(level + 1), indexing="ij")
        corner = ((i == 0) & (j == 0)) | ((i == level) & (j == 0)) | ((i == 0) & (j == level))
        keep = (i + j <= level) & ~corner
        w1, w2 = i[keep] / level, j[keep] / level
        tri = v[f[ks]]  # (m, 3, 3)
        p = ((1.0 - w1 - w2)[None, :, None] * tri[:, None, 0] + w1[None, :, None] * tri[:, None, 1]
             + w2[None, :, None] * tri[:, None, 2])
        per_tri.update(zip(ks.tolist(), p))
    counts = np.array([len(per_tri[k]) if k in per_tri else 0 for k in range(len(f))], dtype=np.int64)
    extra = np.vstack([per_tri[k] for k in sorted(per_tri)]) if per_tri else np.zeros((0, 3))
    return r, extra, counts, r / n


def _ranges(starts: np.ndarray, stops: np.ndarray) -> np.ndarray:
    """The concatenation of ``arange(a, b)`` for each pair (vectorised)."""
    counts = stops - starts
    total = int(counts.sum())
    if total == 0:
        return np.zeros(0, dtype=np.int64)
    offsets = np.repeat(starts - np.r_[0, np.cumsum(counts)[:-1]], counts)
    return offsets + np.arange(total)


def _tf(t: np.ndarray):
    return fcl.Transform(t[:3, :3], t[:3, 3])


def eroded(mesh: Mesh, depth: float) -> Mesh:
    """``mesh`` with every vertex moved ``depth`` metres inwards along its vertex normal (at most 45 %
    of the mesh's smallest half-extent along its principal axes; a negative ``depth`` grows it
    outwards by ``-depth``); the outside is told by the sign of the enclosed volume, so either
    winding works."""
    v, f = mesh.vertices, mesh.faces
    if depth == 0.0 or len(f) == 0:
        return mesh
    volume = float(np.einsum("ij,ij->i", v[f[:, 0]], np.cross(v[f[:, 1]], v[f[:, 2]])).sum()) / 6.0
    centred = v - v.mean(axis=0)
    axes = np.linalg.svd(centred, full_matrices=False)[2]
    extent = centred @ axes.T
    half = float((extent.max(axis=0) - extent.min(axis=0)).min()) / 2.0
    d = min(depth, 0.45 * half)
    inward = -1.0 if volume >= 0.0 else 1.0
    return Mesh(v + inward * d * mesh.vertex_normals(), f.copy())


#: the broad phase splits an object's triangles into at most this many boxes ...
MAX_PARTS = 256
#: ... of at least this many triangles each
PART_TRIANGLES = 1


def part_boxes(mesh: Mesh) -> np.ndarray:
    """(k, 2, 3) boxes (mesh frame) that together cover every triangle of ``mesh``: the triangles
    split at the median of their centres along the widest axis, again and again (at most
    :data:`MAX_PARTS` boxes of at least :data:`PART_TRIANGLES` triangles). A box's walls or a desk's
    top and legs get tight boxes, so a hand inside the box is near none of them."""
    v = np.asarray(mesh.vertices, dtype=float)
    tri = v[np.asarray(mesh.faces, dtype=np.int64)]  # (n, 3, 3)
    centres = tri.mean(axis=1)
    parts, out = [np.arange(len(tri))], []
    while parts:
        idx = parts.pop(0)  # breadth first: the boxes split evenly until the cap
        if len(idx) < 2 * PART_TRIANGLES or len(parts) + len(out) + 2 > MAX_PARTS:
            out.append(idx)
            continue
        c = centres[idx]
        axis = int(np.argmax(c.max(axis=0) - c.min(axis=0)))
        order = idx[np.argsort(c[:, axis], kind="stable")]
        half = len(order) // 2
        parts += [order[:half], order[half:]]
    return np.array([[tri[idx].reshape(-1, 3).min(axis=0), tri[idx].reshape(-1, 3).max(axis=0)] for idx in out])


def _world_boxes(boxes: np.ndarray, t: np.ndarray) -> np.ndarray:
    """World AABBs (k, 2, 3) of local boxes ``boxes`` (k, 2, 3) moved by ``t`` (4x4)."""
    centre, half = (boxes[:, 0] + boxes[:, 1]) / 2, (boxes[:, 1] - boxes[:, 0]) / 2
    c = centre @ t[:3, :3].T + t[:3, 3]
    h = half @ np.abs(t[:3, :3]).T
    return np.stack([c - h, c + h], axis=1)


@dataclass
class _Shape:
    """A segment's collision shape: its (eroded) ``mesh``, bounding sphere and fcl BVH, and its
    triangle refinement for the clearance bounds (on first use)."""

    mesh: Mesh
    centre: np.ndarray
    radius: float
    bvh: object
    _refinement: tuple | None = None

    def refinement(self) -> tuple:
        if self._refinement is None:
            self._refinement = _refinement(self.mesh, _BOUND_SPACING)
        return self._refinement


#: segment shapes by mesh content and erosion: a figure's copies, and every checker made for the
#: same figure, share them (building the BVHs was most of a checker's cost)
_SHAPES: dict[tuple[bytes, float], _Shape] = {}
_SHAPES_MAX = 4096


def _shape(mesh: Mesh, erode: float) -> _Shape:
    import hashlib

    v = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
    f = np.ascontiguousarray(mesh.faces, dtype=np.int64)
    key = (hashlib.blake2b(v.tobytes() + f.tobytes(), digest_size=16).digest(), float(erode))
    shape = _SHAPES.get(key)
    if shape is None:
        m = eroded(mesh, erode)
        c, r = _sphere(m)
        if len(_SHAPES) >= _SHAPES_MAX:
            _SHAPES.clear()
        shape = _SHAPES[key] = _Shape(m, c, r, _bvh(m))
    return shape


def _sphere(mesh: Mesh) -> tuple[np.ndarray, float]:
    lo, hi = mesh.bounds()
    c = (lo + hi) / 2
    return c, float(np.sqrt(((mesh.vertices - c) ** 2).sum(axis=1).max()))


class ClearanceChecker:
    """Collision and clearance queries for ``figure`` against ``objects`` (figures whose segments
    carry meshes, e.g. :class:`~jackpy.scene.CADObject`) and against itself.

    Call :meth:`update` after the posture or an object's location changes, then query. Object bodies
    are named like their figure when it has one segment with geometry, ``figure.segment`` otherwise.
    ``erode`` (metres) shrinks the figure's segments (module docstring: contact tolerance);
    ``segments`` keeps only those segments (e.g. the ones a planned arm moves).
    """

    def __init__(self, figure: Figure, objects: Sequence[Figure] = (), self_collision: bool = True,
                 ignore_initial: bool = True, grid_budget: int = 500_000, erode: float = 0.0,
                 segments: Collection[str] | None = None) -> None:
        if fcl is None:
            raise JackpyError("collision and clearance need the package 'python-fcl' (pip install python-fcl)")
        self.figure = figure
        kin = figure.kinematics()
        self._kin = kin
        seg_idx, centres, radii, self._seg_obj = [], [], [], []
        self.segment_names: list[str] = []
        verts, faces, vstart, fstart = [], [], [0], [0]
        self._shapes: list[_Shape] = []
        for name in kin.segment_names:
            seg = figure.segments[name]
            mesh = seg.psurf.posed_mesh() if seg.psurf is not None and (segments is None or name in segments) else None
            if mesh is None or len(mesh.faces) == 0:
                continue
            shape = _shape(mesh, erode)
            mesh = shape.mesh
            self._shapes.append(shape)
            seg_idx.append(kin.segment_index[name])
            centres.append(shape.centre)
            radii.append(shape.radius)
            self._seg_obj.append(fcl.CollisionObject(shape.bvh, fcl.Transform()))
            self.segment_names.append(name)
            verts.append(np.asarray(mesh.vertices, dtype=float))
            faces.append(np.asarray(mesh.faces, dtype=np.int64) + vstart[-1])
            vstart.append(vstart[-1] + len(mesh.vertices))
            fstart.append(fstart[-1] + len(mesh.faces))
        # all segments' vertices and triangles, concatenated (segment frames), for the grid bounds
        self._verts = np.vstack(verts) if verts else np.zeros((0, 3))
        self._faces = np.vstack(faces) if faces else np.zeros((0, 3), dtype=np.int64)
        self._refined = False  # the triangle refinement: made on the first clearance query
        self._vstart = np.array(vstart, dtype=np.int64)
        self._fstart = np.array(fstart, dtype=np.int64)
        self._fseg = np.repeat(np.arange(len(verts)), np.diff(self._fstart)) if verts else np.zeros(0, dtype=int)
        self._vseg = np.repeat(np.arange(len(verts)), np.diff(self._vstart)) if verts else np.zeros(0, dtype=int)
        self._seg_idx = np.array(seg_idx, dtype=int)
        self._centre_local = np.array(centres).reshape(-1, 3)
        self._radius = np.array(radii)
        # object bodies
        self.objects = list(objects)
        self.body_names: list[str] = []
        self._body_src: list[tuple[Figure, str]] = []
        self._body_obj = []
        self._body_box_local: list[np.ndarray] = []
        self._body_mesh: list[Mesh] = []
        self._part_box_local: list[np.ndarray] = []  # per body: (k, 2, 3) boxes of its connected parts
        self._part_body: list[int] = []
        self._body_grid: list[DistanceGrid | None] = []
        self._grid_budget = grid_budget
        self._vb_cache: dict[int, dict[int, tuple]] = {}
        self._last_touch: dict[str, tuple[int, int]] = {}
        self._xlb_cache: dict[int, np.ndarray] = {}  # per body: refined triangle bounds (NaN: stale)
        for obj in self.objects:
            meshes = {n: s.psurf.posed_mesh() for n, s in obj.segments.items() if s.psurf is not None}
            meshes = {n: m for n, m in meshes.items() if m is not None and len(m.faces)}
            for n, m in meshes.items():
                self.body_names.append(obj.name if len(meshes) == 1 else f"{obj.name}.{n}")
                self._body_src.append((obj, n))
                self._body_obj.append(fcl.CollisionObject(_bvh(m), fcl.Transform()))
                self._body_box_local.append(m.bounds())
                parts = part_boxes(m)
                self._part_box_local.append(parts)
                self._part_body.extend([len(self.body_names) - 1] * len(parts))
                self._body_mesh.append(m)
                self._body_grid.append(None)
        self._box_world = np.zeros((len(self.body_names), 2, 3))
        self._part_box_world = np.zeros((len(self._part_body), 2, 3))
        self._part_start = np.searchsorted(np.array(self._part_body, dtype=int), np.arange(len(self.body_names)))
        self._body_world = np.tile(np.eye(4), (len(self.body_names), 1, 1))
        # self-collision pairs: not adjacent
        self._pairs = np.zeros((0, 2), dtype=int)
        if self_collision and len(self.segment_names) > 1:
            pos = {n: k for k, n in enumerate(self.segment_names)}
            adjacent = {frozenset((j.from_seg, j.to_seg)) for j in figure.joints.values()}
            pairs = [(a, b) for a in range(len(pos)) for b in range(a + 1, len(pos))
                     if frozenset((self.segment_names[a], self.segment_names[b])) not in adjacent]
            self._pairs = np.array(pairs, dtype=int).reshape(-1, 2)
        self._seg_world = np.zeros((len(self.segment_names), 4, 4))
        self._centre_world = np.zeros((len(self.segment_names), 3))
        self._placed = np.zeros(len(self.segment_names), dtype=bool)
        self._objects_placed = False
        self.update()
        if ignore_initial and len(self._pairs):
            touching = {tuple(p) for p in self._colliding_pairs()}
            keep = [k for k, p in enumerate(map(tuple, self._pairs)) if p not in touching]
            self._pairs = self._pairs[keep]

    # ----- per frame -----------------------------------------------------------------------------
    def update(self, q: np.ndarray | None = None) -> None:
        """Pose the segments at ``q`` (default: the figure's) and re-read object locations."""
        q = self.figure.q if q is None else q
        fk = self._kin.forward(q, self.figure.location)
        self._seg_world = fk.segments[self._seg_idx]
        self._centre_world = np.einsum("nij,nj->ni", self._seg_world[:, :3, :3], self._centre_local) \
            + self._seg_world[:, :3, 3]
        self._placed[:] = False
        for k, ((obj, seg), co, box) in enumerate(zip(self._body_src, self._body_obj, self._body_box_local)):
            t = obj.location if len(obj.segments) == 1 else obj.world_transforms()[seg]
            if self._objects_placed and np.array_equal(t, self._body_world[k]):
                continue  # the object has not moved
            co.setTransform(_tf(t))
            self._body_world[k] = t
            self._box_world[k] = _world_boxes(box[None], t)[0]
            start = self._part_start[k]
            parts = self._part_box_local[k]
            self._part_box_world[start:start + len(parts)] = _world_boxes(parts, t)
        self._objects_placed = True

    def _place(self, k: int) -> object:
        if not self._placed[k]:
            self._seg_obj[k].setTransform(_tf(self._seg_world[k]))
            self._placed[k] = True
        return self._seg_obj[k]

    def _sphere_box_gap(self, bodies: np.ndarray | None = None) -> np.ndarray:
        """Lower bound (nseg, nbody) on segment-to-body distance: sphere to world AABB, >= 0."""
        boxes = self._box_world if bodies is None else self._box_world[bodies]
        c = self._centre_world[:, None, :]
        d = np.maximum(np.maximum(boxes[None, :, 0] - c, c - boxes[None, :, 1]), 0.0)
        return np.maximum(np.sqrt((d ** 2).sum(axis=2)) - self._radius[:, None], 0.0)

    def _near_parts(self, segs: np.ndarray, b: int) -> np.ndarray:
        """Which of segments ``segs`` have a bounding sphere touching one of body ``b``'s part boxes
        (a box's walls, a desk's top and legs; :func:`part_boxes`)."""
        start = self._part_start[b]
        boxes = self._part_box_world[start:start + len(self._part_box_local[b])]
        c = self._centre_world[segs][:, None, :]
        d = np.maximum(np.maximum(boxes[None, :, 0] - c, c - boxes[None, :, 1]), 0.0)
        return ((d * d).sum(axis=2) <= (self._radius[segs] ** 2)[:, None]).any(axis=1)

    # ----- queries -------------------------------------------------------------------------------
    def object_collisions(self) -> list[tuple[str, str]]:
        """``(segment, body)`` for every segment touching an object body."""
        out = []
        req = fcl.CollisionRequest()
        near = self._sphere_box_gap() <= 0.0
        pairs = []
        for b in np.flatnonzero(near.any(axis=0)):
            segs = np.flatnonzero(near[:, b])
            pairs += [(int(s), int(b)) for s in segs[self._near_parts(segs, b)]]
        for s, b in sorted(pairs):
            if fcl.collide(self._place(s), self._body_obj[b], req, fcl.CollisionResult()):
                out.append((self.segment_names[s], self.body_names[b]))
        return out

    def line_hits(self, start: np.ndarray, end: np.ndarray, radius: float = 0.01) -> list[tuple[float, str]]:
        """``(distance from start, body)`` for every object body that a capsule of ``radius`` metres
        from world point ``start`` to ``end`` touches, nearest first (the distance is that of the
        first contact point found)."""
        start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
        axis = end - start
        length = float(np.linalg.norm(axis))
        if length < 1e-9:
            return []
        z = axis / length
        x = np.cross(z, [1.0, 0.0, 0.0] if abs(z[0]) < 0.9 else [0.0, 1.0, 0.0])
        x /= np.linalg.norm(x)
        rot = np.column_stack([x, np.cross(z, x), z])
        capsule = fcl.CollisionObject(fcl.Capsule(radius, length), fcl.Transform(rot, (start + end) / 2))
        lo, hi = np.minimum(start, end) - radius, np.maximum(start, end) + radius
        req = fcl.CollisionRequest(num_max_contacts=16, enable_contact=True)
        out = []
        for b, name in enumerate(self.body_names):
            box = self._box_world[b]
            if np.any(box[0] > hi) or np.any(box[1] < lo):
                continue
            res = fcl.CollisionResult()
            if fcl.collide(capsule, self._body_obj[b], req, res):
                d = min((float(np.dot(np.asarray(c.pos) - start, z)) for c in res.contacts), default=0.0)
                out.append((max(d, 0.0), name))
        return sorted(out)

    def _colliding_pairs(self) -> list[tuple[int, int]]:
        if not len(self._pairs):
            return []
        a, b = self._pairs[:, 0], self._pairs[:, 1]
        near = np.linalg.norm(self._centre_world[a] - self._centre_world[b], axis=1) <= self._radius[a] + self._radius[b]
        req = fcl.CollisionRequest()
        return [(int(i), int(j)) for i, j in self._pairs[near]
                if fcl.collide(self._place(i), self._place(j), req, fcl.CollisionResult())]

    def self_collisions(self) -> list[tuple[str, str]]:
        """Pairs of non-adjacent segments that touch (pairs allowed at construction excluded)."""
        return [(self.segment_names[i], self.segment_names[j]) for i, j in self._colliding_pairs()]

    def colliding_segments(self) -> set[str]:
        """Every segment touching an object or another segment: what the UI highlights."""
        out = {s for s, _ in self.object_collisions()}
        for a, b in self.self_collisions():
            out.update((a, b))
        return out

    def _grid(self, b: int) -> DistanceGrid:
        """The distance grid of body ``b`` (built on first use, in the body's frame)."""
        g = self._body_grid[b]
        if g is None:
            g = self._body_grid[b] = DistanceGrid(self._body_mesh[b], budget=self._grid_budget)
        return g

    def _bodies(self, obj: str) -> np.ndarray:
        bodies = np.array([k for k, (n, (f, _)) in enumerate(zip(self.body_names, self._body_src))
                           if n == obj or f.name == obj], dtype=int)
        if not len(bodies) or not len(self.segment_names):
            raise JackpyError(f"no object {obj!r} with geometry in the clearance check (objects: "
                              f"{', '.join(self.body_names) or 'none'}; segments with geometry: "
                              f"{len(self.segment_names)})")
        return bodies

    def _segment_level(self, bodies: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Coarse bounds (nseg, nbody) on segment-to-body distance from the bounding spheres: the
        sphere-to-AABB gap and the body's distance grid at the sphere centre, +- the radius."""
        lb = self._sphere_box_gap(bodies)
        ub = np.empty_like(lb)
        for bi, b in enumerate(bodies):
            t = self._body_world[b]
            local = (self._centre_world - t[:3, 3]) @ t[:3, :3]
            lo, hi = self._grid(b).bounds(local)
            np.maximum(lb[:, bi], lo - self._radius, out=lb[:, bi])
            ub[:, bi] = hi + self._radius
        return lb, ub

    def _vertex_bounds(self, segs: np.ndarray, b: int) -> tuple[np.ndarray, np.ndarray]:
        """Grid bounds for the vertices of segments ``segs`` against body ``b``, concatenated in the
        order of ``segs``. A segment whose pose relative to the body has not changed since its last
        query reuses its bounds (exactly the same numbers: frame coherence without approximation)."""
        t = self._body_world[b]
        rot_inv, off = t[:3, :3].T, t[:3, 3]
        rel = np.empty((len(segs), 3, 4))  # segment frame -> body frame
        rel[:, :, :3] = np.einsum("ij,njk->nik", rot_inv, self._seg_world[segs, :3, :3])
        rel[:, :, 3] = (self._seg_world[segs, :3, 3] - off) @ rot_inv.T
        cache = self._vb_cache.setdefault(b, {})
        todo = [j for j, k in enumerate(segs) if (c := cache.get(int(k))) is None or not np.array_equal(c[0], rel[j])]
        if todo:
            ks = segs[todo]
            counts = self._vstart[ks + 1] - self._vstart[ks]
            vidx = _ranges(self._vstart[ks], self._vstart[ks + 1])
            rep = np.repeat(np.asarray(todo), counts)
            local = np.einsum("nij,nj->ni", rel[rep, :, :3], self._verts[vidx]) + rel[rep, :, 3]
            vlo, vhi = self._grid(b).bounds(local)
            starts = np.r_[0, np.cumsum(counts)]
            xlb = self._xlb_cache.get(b)
            if xlb is not None:  # the refined triangle bounds of moved segments are stale
                xlb[_ranges(self._fstart[ks], self._fstart[ks + 1])] = np.nan
            for n, (j, k) in enumerate(zip(todo, ks)):
                cache[int(k)] = (rel[j].copy(), vlo[starts[n]:starts[n + 1]], vhi[starts[n]:starts[n + 1]])
        parts = [cache[int(k)] for k in segs]
        return np.concatenate([c[1] for c in parts]), np.concatenate([c[2] for c in parts])

    def _refinement_arrays(self) -> None:
        """Per triangle: its cover radius ``_cover`` (every point within it of a vertex) and, for
        large ones, extra points ``_xpts[_xptr[f]:_xptr[f + 1]]`` (segment frame) with a finer
        radius ``_xr[f]`` (built once, for clearance only: collision queries never need them)."""
        if self._refined:
            return
        parts = [sh.refinement() for sh in self._shapes]
        self._cover = np.concatenate([p[0] for p in parts]) if parts else np.zeros(0)
        self._xpts = np.vstack([p[1] for p in parts]) if parts else np.zeros((0, 3))
        self._xptr = np.r_[0, np.cumsum(np.concatenate([p[2] for p in parts]))] if parts else np.zeros(1, dtype=np.int64)
        self._xr = np.concatenate([p[3] for p in parts]) if parts else np.zeros(0)
        self._refined = True

    def _triangle_level(self, segs: np.ndarray, b: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """For segments ``segs`` against body ``b``: the segments' triangle indices (into the
        concatenated arrays), a lower bound per triangle (its vertices' smallest grid bound minus the
        triangle's cover radius), and per segment the lower bound (smallest of its triangles') and
        upper bound (smallest of its vertices' grid upper bounds)."""
        self._refinement_arrays()
        vlo, vhi = self._vertex_bounds(segs, b)
        counts = self._vstart[segs + 1] - self._vstart[segs]
        vidx = _ranges(self._vstart[segs], self._vstart[segs + 1])
        lower = np.empty(len(self._verts))
        lower[vidx] = vlo
        fidx = _ranges(self._fstart[segs], self._fstart[segs + 1])
        tri_lb = lower[self._faces[fidx]].min(axis=1) - self._cover[fidx]
        fcounts = self._fstart[segs + 1] - self._fstart[segs]
        seg_lb = np.minimum.reduceat(tri_lb, np.r_[0, np.cumsum(fcounts)[:-1]])
        seg_ub = np.minimum.reduceat(vhi, np.r_[0, np.cumsum(counts)[:-1]])
        return fidx, tri_lb, seg_lb, seg_ub

    def _vb_vertex_min(self, f: np.ndarray, b: int) -> np.ndarray:
        """Smallest cached vertex lower bound of each triangle ``f`` against body ``b``."""
        cache = self._vb_cache[b]
        segs = self._fseg[f]
        out = np.empty(len(f))
        for k in np.unique(segs):
            m = segs == k
            out[m] = cache[int(k)][1][self._faces[f[m]] - self._vstart[k]].min(axis=1)
        return out

    def _refine(self, fidx: np.ndarray, tri_lb: np.ndarray, b: int, bound: float) -> np.ndarray:
        """Tighter lower bounds for the large triangles among ``fidx`` whose bound is within
        ``bound``: their extra points' grid bounds minus the finer radius (the vertices' smallest
        bound is ``tri_lb + cover``). Needs :meth:`_vertex_bounds` for their segments first."""
        nx = self._xptr[fidx + 1] - self._xptr[fidx]
        sel = np.flatnonzero((tri_lb <= bound + 1e-7) & (nx > 0))
        if not len(sel):
            return tri_lb
        f = fidx[sel]
        xlb = self._xlb_cache.setdefault(b, np.full(len(self._faces), np.nan))
        need = f[np.isnan(xlb[f])]
        if len(need):
            counts = self._xptr[need + 1] - self._xptr[need]
            xidx = _ranges(self._xptr[need], self._xptr[need + 1])
            cache = self._vb_cache[b]
            segs, inv = np.unique(self._fseg[need], return_inverse=True)
            rel = np.array([cache[int(k)][0] for k in segs])
            rep = np.repeat(inv.ravel(), counts)
            local = np.einsum("nij,nj->ni", rel[rep, :, :3], self._xpts[xidx]) + rel[rep, :, 3]
            xlo, _ = self._grid(b).bounds(local)
            xmin = np.minimum.reduceat(xlo, np.r_[0, np.cumsum(counts)[:-1]])
            vmin = self._vb_vertex_min(need, b)
            xlb[need] = np.minimum(vmin, xmin) - self._xr[need]
        fine = xlb[f]
        out = tri_lb.copy()
        out[sel] = np.maximum(tri_lb[sel], fine)
        return out

    def segment_bounds(self, obj: str) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper bounds (metres, one per entry of :attr:`segment_names`) on each segment's
        distance to object ``obj``, from the object's distance grid and no exact query: what
        :meth:`clearance` prunes with. The lower bound never exceeds the true distance, the upper
        bound is never below it."""
        bodies = self._bodies(obj)
        segs = np.arange(len(self.segment_names))
        lower = np.full(len(segs), np.inf)
        upper = np.full(len(segs), np.inf)
        coarse_lb, coarse_ub = self._segment_level(bodies)
        for bi, b in enumerate(bodies):
            fidx, tri_lb, _, ub = self._triangle_level(segs, b)
            tri_lb = self._refine(fidx, tri_lb, b, np.inf)
            lb = np.minimum.reduceat(tri_lb, self._fstart[:-1])
            np.minimum(lower, np.maximum(lb, coarse_lb[:, bi]), out=lower)
            np.minimum(upper, np.minimum(ub, coarse_ub[:, bi]), out=upper)
        return np.maximum(lower, 0.0), upper

    def clearance(self, obj: str) -> Clearance:
        """Smallest distance from the figure's segments to object ``obj`` (a figure name: all its
        bodies; or a body name). Exact (fcl's triangle distances); the object's distance grid only
        decides which triangles need the exact query."""
        bodies = self._bodies(obj)
        eps = 1e-7
        creq = fcl.CollisionRequest(num_max_contacts=1, enable_contact=True)
        last = self._last_touch.get(obj)
        if last is not None:  # frame coherence: the pair that touched last time usually still does
            s, b = last
            res = fcl.CollisionResult()
            if fcl.collide(self._place(s), self._body_obj[b], creq, res):
                p = np.array(res.contacts[0].pos, dtype=float) if res.contacts else self._centre_world[s]
                return Clearance(0.0, self.segment_names[s], self.body_names[b], p, p.copy())
            del self._last_touch[obj]
        lb, ub = self._segment_level(bodies)
        upper = float(ub.min())
        # per body: the triangles (of the segments that might be nearest) that might be nearest
        cand = []
        for bi, b in enumerate(bodies):
            segs = np.flatnonzero(lb[:, bi] <= upper + eps)
            if not len(segs):
                continue
            fidx, tri_lb, _, seg_ub = self._triangle_level(segs, b)
            upper = min(upper, float(seg_ub.min()))
            cand.append((int(b), fidx, tri_lb))
        best: Clearance | None = None
        req = fcl.DistanceRequest(enable_nearest_points=True)
        if cand and upper > 0.0:  # an exact upper bound first: the few triangles bounded lowest
            b, fidx, tri_lb = min(cand, key=lambda c: float(c[2].min()))
            if float(tri_lb.min()) > 0.0:
                best = self._distance(fidx[np.argsort(tri_lb)[:_SEED_TRIANGLES]], b, req)
                upper = min(upper, best.distance)
        cand = [(b, fidx, self._refine(fidx, tri_lb, b, upper)) for b, fidx, tri_lb in cand]
        cand = [(float(tri_lb.min()), b, fidx, tri_lb) for b, fidx, tri_lb in cand]
        cand = [c for c in cand if c[0] <= upper + eps]
        cand.sort(key=lambda c: c[0])
        for low, b, fidx, tri_lb in cand:  # touching: distance 0 at a contact
            if low > 0.0:
                break
            sub = fidx[tri_lb <= eps]
            res = fcl.CollisionResult()
            if fcl.collide(self._world_triangles(sub), self._body_obj[b], creq, res):
                c = res.contacts[0] if res.contacts else None
                s = self._fseg[sub[c.b1 if c is not None else 0]]
                p = np.array(c.pos, dtype=float) if c is not None else self._centre_world[s]
                self._last_touch[obj] = (int(s), int(b))
                return Clearance(0.0, self.segment_names[s], self.body_names[b], p, p.copy())
        for low, b, fidx, tri_lb in cand:
            bound = upper if best is None else min(upper, best.distance)
            if low > bound + eps:
                break
            # one exact query over every triangle that could be nearest (a small BVH, world frame)
            c = self._distance(fidx[tri_lb <= bound + eps], b, req)
            if best is None or c.distance < best.distance:
                best = c
        assert best is not None
        return best

    def _distance(self, fidx: np.ndarray, b: int, req) -> Clearance:
        """Exact distance from the segments' triangles ``fidx`` to body ``b``."""
        res = fcl.DistanceResult()
        d = max(float(fcl.distance(self._world_triangles(fidx), self._body_obj[b], req, res)), 0.0)
        p1, p2 = (np.array(p, dtype=float) for p in res.nearest_points)
        s = self._fseg[fidx[res.b1]]
        return Clearance(d, self.segment_names[s], self.body_names[b], p1, p2)

    def _world_triangles(self, fidx: np.ndarray):
        """A collision object of the segments' triangles ``fidx`` (indices into the concatenated
        arrays) posed in the world, its primitive ``i`` being triangle ``fidx[i]``."""
        tris = self._faces[fidx]
        used, inv = np.unique(tris, return_inverse=True)
        t = self._seg_world[self._vseg[used]]
        world = np.einsum("nij,nj->ni", t[:, :3, :3], self._verts[used]) + t[:, :3, 3]
        return fcl.CollisionObject(_bvh(Mesh(world, inv.reshape(-1, 3))), fcl.Transform())
