"""Collision and clearance between a figure's segments, environment objects, and the figure itself.

Library: python-fcl (the Flexible Collision Library's bindings, also what ``trimesh.collision``
wraps). Each segment's and object's mesh gets one bounding-volume hierarchy (OBBRSS) built once in
its own frame; a frame only moves the BVHs' transforms, so per-frame cost is the narrow phase of the
few pairs that survive the broad phase. fcl gives exact triangle-triangle collision and mesh-mesh
distance with nearest points, which trimesh's own proximity queries (point-to-mesh only, and they
need rtree) do not.

Broad phase (vectorised numpy): every segment has a bounding sphere (segment frame); every object
body has a world AABB (recomputed from its location each frame). Segment-object pairs are tested
only when the sphere touches the AABB; segment-segment pairs only when their spheres overlap.
Minimum clearance first measures the segment that was nearest that object in the previous query
(frame coherence: its distance is usually already close to the answer), then visits the others in
increasing order of the sphere-to-AABB lower bound and stops once that bound exceeds the best
distance found.

Self-collision skips adjacent segments (joined by a joint) and, with ``ignore_initial``, pairs
already touching in the posture the checker was built in (their shapes overlap by design, e.g.
vertebrae, or a thigh and the pelvis); that is the usual "allowed collision matrix".
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

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


def _bvh(mesh: Mesh):
    m = fcl.BVHModel()
    m.beginModel(len(mesh.vertices), len(mesh.faces))
    m.addSubModel(np.ascontiguousarray(mesh.vertices, dtype=np.float64),
                  np.ascontiguousarray(mesh.faces, dtype=np.int32))
    m.endModel()
    return m


def _tf(t: np.ndarray):
    return fcl.Transform(t[:3, :3], t[:3, 3])


def _sphere(mesh: Mesh) -> tuple[np.ndarray, float]:
    lo, hi = mesh.bounds()
    c = (lo + hi) / 2
    return c, float(np.sqrt(((mesh.vertices - c) ** 2).sum(axis=1).max()))


class ClearanceChecker:
    """Collision and clearance queries for ``figure`` against ``objects`` (figures whose segments
    carry meshes, e.g. :class:`~jackpy.scene.CADObject`) and against itself.

    Call :meth:`update` after the posture or an object's location changes, then query. Object bodies
    are named like their figure when it has one segment with geometry, ``figure.segment`` otherwise.
    """

    def __init__(self, figure: Figure, objects: Sequence[Figure] = (), self_collision: bool = True,
                 ignore_initial: bool = True) -> None:
        if fcl is None:
            raise JackpyError("collision and clearance need the package 'python-fcl' (pip install python-fcl)")
        self.figure = figure
        kin = figure.kinematics()
        self._kin = kin
        seg_idx, centres, radii, self._seg_obj = [], [], [], []
        self.segment_names: list[str] = []
        for name in kin.segment_names:
            seg = figure.segments[name]
            mesh = seg.psurf.posed_mesh() if seg.psurf is not None else None
            if mesh is None or len(mesh.faces) == 0:
                continue
            c, r = _sphere(mesh)
            seg_idx.append(kin.segment_index[name])
            centres.append(c)
            radii.append(r)
            self._seg_obj.append(fcl.CollisionObject(_bvh(mesh), fcl.Transform()))
            self.segment_names.append(name)
        self._seg_idx = np.array(seg_idx, dtype=int)
        self._centre_local = np.array(centres).reshape(-1, 3)
        self._radius = np.array(radii)
        # object bodies
        self.objects = list(objects)
        self.body_names: list[str] = []
        self._body_src: list[tuple[Figure, str]] = []
        self._body_obj = []
        self._body_box_local: list[np.ndarray] = []
        for obj in self.objects:
            meshes = {n: s.psurf.posed_mesh() for n, s in obj.segments.items() if s.psurf is not None}
            meshes = {n: m for n, m in meshes.items() if m is not None and len(m.faces)}
            for n, m in meshes.items():
                self.body_names.append(obj.name if len(meshes) == 1 else f"{obj.name}.{n}")
                self._body_src.append((obj, n))
                self._body_obj.append(fcl.CollisionObject(_bvh(m), fcl.Transform()))
                self._body_box_local.append(m.bounds())
        self._box_world = np.zeros((len(self.body_names), 2, 3))
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
        self._last_nearest: dict[str, int] = {}
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
            co.setTransform(_tf(t))
            corners = np.array([[box[i, 0], box[j, 1], box[l, 2]] for i in (0, 1) for j in (0, 1) for l in (0, 1)])
            w = corners @ t[:3, :3].T + t[:3, 3]
            self._box_world[k] = (w.min(axis=0), w.max(axis=0))

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

    # ----- queries -------------------------------------------------------------------------------
    def object_collisions(self) -> list[tuple[str, str]]:
        """``(segment, body)`` for every segment touching an object body."""
        out = []
        req = fcl.CollisionRequest()
        for s, b in np.argwhere(self._sphere_box_gap() <= 0.0):
            if fcl.collide(self._place(s), self._body_obj[b], req, fcl.CollisionResult()):
                out.append((self.segment_names[s], self.body_names[b]))
        return out

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

    def clearance(self, obj: str) -> Clearance:
        """Smallest distance from the figure's segments to object ``obj`` (a figure name: all its
        bodies; or a body name)."""
        bodies = np.array([k for k, (n, (f, _)) in enumerate(zip(self.body_names, self._body_src))
                           if n == obj or f.name == obj], dtype=int)
        if not len(bodies) or not len(self.segment_names):
            raise JackpyError(f"no object {obj!r} with geometry in the clearance check (objects: "
                              f"{', '.join(self.body_names) or 'none'}; segments with geometry: "
                              f"{len(self.segment_names)})")
        gap = self._sphere_box_gap(bodies)
        creq = fcl.CollisionRequest(num_max_contacts=1, enable_contact=True)
        for s, bi in np.argwhere(gap <= 0.0):  # touching: distance 0 at a contact (collide is cheap)
            res = fcl.CollisionResult()
            if fcl.collide(self._place(s), self._body_obj[bodies[bi]], creq, res):
                p = np.array(res.contacts[0].pos, dtype=float) if res.contacts else self._centre_world[s]
                return Clearance(0.0, self.segment_names[s], self.body_names[bodies[bi]], p, p.copy())
        order = np.argsort(gap, axis=None)
        if obj in self._last_nearest:
            order = np.r_[self._last_nearest[obj], order]
        best: Clearance | None = None
        best_flat = -1
        req = fcl.DistanceRequest(enable_nearest_points=True)
        visited = set()
        for flat in order:
            if flat in visited:
                continue
            visited.add(flat)
            s, bi = np.unravel_index(flat, gap.shape)
            if best is not None and gap[s, bi] >= best.distance:
                break
            b = bodies[bi]
            res = fcl.DistanceResult()
            d = max(float(fcl.distance(self._place(s), self._body_obj[b], req, res)), 0.0)
            if best is None or d < best.distance:
                p1, p2 = (np.array(p, dtype=float) for p in res.nearest_points)
                best = Clearance(d, self.segment_names[s], self.body_names[b], p1, p2)
                best_flat = int(flat)
        assert best is not None
        self._last_nearest[obj] = best_flat
        return best
