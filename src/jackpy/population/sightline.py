"""Visibility from the eye by ray casting against the scene's objects (no GPU, no figure surfaces):
the view test of a sweep, where thousands of eye points look at the same scene.

A target object is sampled by ``SAMPLES`` points spread over its surface in proportion to area
(fixed seed: the same points in every process). From an eye point, the samples on faces turned
towards the eye are weighted by the solid angle they subtend (``area cos / distance^2``) and the
**visible fraction** is the weight of those whose line of sight no object blocks: the share of the
target's silhouette that can be seen, as the ID-buffer measure of :mod:`jackpy.analysis.view`
gives it. A site is one line of sight, blocked by any surface more than ``SITE_TOLERANCE`` in front
of it. The figure's own body is not an occluder here (skeleton figures have no surfaces).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.scene.cad import CADObject

SAMPLES = 256
SITE_TOLERANCE = 0.01
#: a surface sample's own face is this far behind its line of sight's end (m)
SAMPLE_TOLERANCE = 1e-3
_TRIANGLE_CHUNK = 4096


@dataclass(frozen=True)
class _Object:
    triangles: np.ndarray  # (T, 3, 3) world
    lo: np.ndarray
    hi: np.ndarray
    samples: np.ndarray  # (S, 3) world
    normals: np.ndarray  # (S, 3) outward unit normals of the sampled faces


def _sample(tri: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = np.linalg.norm(cross, axis=1)
    rng = np.random.default_rng(0)
    pick = rng.choice(len(tri), size=n, p=area / area.sum())
    a, b = rng.random(n), rng.random(n)
    flip = a + b > 1.0
    a[flip], b[flip] = 1.0 - a[flip], 1.0 - b[flip]
    t = tri[pick]
    points = t[:, 0] + a[:, None] * (t[:, 1] - t[:, 0]) + b[:, None] * (t[:, 2] - t[:, 0])
    return points, cross[pick] / np.maximum(area[pick], 1e-300)[:, None]


class Sightlines:
    """Ray-cast visibility against a set of scene objects at their current world placement."""

    def __init__(self, objects: dict[str, CADObject]) -> None:
        self.objects: dict[str, _Object] = {}
        for name, obj in objects.items():
            mesh = obj.world_mesh()
            tri = mesh.vertices[mesh.faces]
            samples, normals = _sample(tri, SAMPLES)
            self.objects[name] = _Object(tri, tri.reshape(-1, 3).min(axis=0), tri.reshape(-1, 3).max(axis=0),
                                         samples, normals)

    def _blocked(self, eye: np.ndarray, points: np.ndarray, tolerance: np.ndarray) -> np.ndarray:
        """(R,) bool: a triangle lies on the segment eye -> point, more than ``tolerance`` (R,) metres
        in front of the point."""
        d = points - eye
        length = np.linalg.norm(d, axis=1)
        t_max = 1.0 - tolerance / np.maximum(length, 1e-12)
        blocked = np.zeros(len(points), dtype=bool)
        lo_box = np.minimum(points.min(axis=0), eye)
        hi_box = np.maximum(points.max(axis=0), eye)
        for obj in self.objects.values():
            if np.any(obj.lo > hi_box) or np.any(obj.hi < lo_box):
                continue
            for start in range(0, len(obj.triangles), _TRIANGLE_CHUNK):
                tri = obj.triangles[start:start + _TRIANGLE_CHUNK]
                todo = ~blocked
                if not todo.any():
                    return blocked
                blocked[todo] |= _hits(eye, d[todo], t_max[todo], tri)
        return blocked

    def site_visible(self, eye: np.ndarray, point: np.ndarray) -> bool:
        """Whether the line of sight from ``eye`` to ``point`` is clear (module docstring)."""
        p = np.asarray(point, dtype=float).reshape(1, 3)
        return not bool(self._blocked(np.asarray(eye, dtype=float), p, np.array([SITE_TOLERANCE]))[0])

    def object_fraction(self, eye: np.ndarray, name: str) -> float:
        """Visible fraction (0..1) of object ``name`` from ``eye``: solid-angle weighted share of its
        eye-facing surface samples with a clear line of sight."""
        obj = self.objects[name]
        eye = np.asarray(eye, dtype=float)
        to_eye = eye - obj.samples
        dist = np.linalg.norm(to_eye, axis=1)
        cos = np.einsum("ij,ij->i", obj.normals, to_eye) / np.maximum(dist, 1e-12)
        facing = cos > 1e-6
        if not facing.any():
            return 0.0
        weight = cos[facing] / dist[facing] ** 2
        blocked = self._blocked(eye, obj.samples[facing], np.full(int(facing.sum()), SAMPLE_TOLERANCE))
        return float(weight[~blocked].sum() / weight.sum())


def _hits(eye: np.ndarray, d: np.ndarray, t_max: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Möller-Trumbore: (R,) whether segment ``eye + t d`` (0 < t < t_max) crosses any of ``tri``."""
    v0 = tri[:, 0]
    e1 = tri[:, 1] - v0
    e2 = tri[:, 2] - v0
    p = np.cross(d[:, None, :], e2[None, :, :])  # (R, T, 3)
    det = np.einsum("tk,rtk->rt", e1, p)
    ok = np.abs(det) > 1e-14
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = eye - v0  # (T, 3)
    u = np.einsum("tk,rtk->rt", s, p) * inv
    q = np.cross(s, e1)  # (T, 3)
    v = np.einsum("rk,tk->rt", d, q) * inv
    t = np.einsum("tk,tk->t", e2, q)[None, :] * inv
    hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-9) & (t < t_max[:, None])
    return hit.any(axis=1)
