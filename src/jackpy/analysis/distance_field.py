"""A precomputed distance grid around a mesh: sound lower and upper bounds on point-to-surface distance.

Used by :class:`~jackpy.analysis.clearance.ClearanceChecker` to prune exact mesh-mesh distance
queries (issue 8): one exact fcl query between a large segment and a large object can take
milliseconds, while bounds for every vertex of every nearby segment come from a few array lookups.

Construction (once per mesh, in the mesh's own frame):

- The surface is sampled so that every surface point lies within ``rho`` of a sample: a triangle's
  own vertices when its covering radius (see :func:`triangle_cover_radius`) is at most ``rho``,
  otherwise the vertices of its regular subdivision into ``n²`` similar triangles, each of covering
  radius ``R/n``.
- On the vertices of a regular grid spanning the mesh's bounding box plus a margin, ``upper`` is the
  distance to the nearest sample (a surface point, so never below the true distance) and ``lower``
  is that minus ``rho`` (never above it).

Queries use the 1-Lipschitz property of the distance function ``d``: for a grid vertex ``v``,
``lower(v) - |p - v| <= d(p) <= upper(v) + |p - v|``; the best of the eight corners of ``p``'s cell
is taken. A point outside the grid is clamped onto it (adding or subtracting the clamp distance) and
its lower bound is also at least its distance to the mesh's bounding box. All bounds are therefore
sound without any assumption on the mesh (open, non-manifold, a triangle soup): the distance here is
to the surface, as fcl's mesh distance is.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from jackpy.peabody.geometry import Mesh

_CORNERS = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], dtype=np.int64)


def triangle_cover_radius(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """For each triangle, a radius ``R`` such that every point of the triangle lies within ``R`` of
    one of its three vertices: the circumradius for an acute or right triangle, half the longest edge
    for an obtuse or degenerate one (the bisectors of the short sides then meet the long side closer
    than its midpoint)."""
    t = np.asarray(vertices, dtype=float)[np.asarray(faces, dtype=np.int64)]
    e = np.linalg.norm(t[:, [1, 2, 0]] - t, axis=2)  # edge lengths (n, 3)
    e.sort(axis=1)
    a, b, c = e[:, 0], e[:, 1], e[:, 2]
    area2 = np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1)  # twice the area
    acute = (a * a + b * b >= c * c) & (area2 > 1e-300)
    circum = np.divide(a * b * c, 2.0 * area2, out=np.zeros_like(c), where=acute)
    r = np.where(acute, circum, 0.5 * c)
    return np.maximum(r, 0.5 * c) * (1.0 + 1e-9) + 1e-12


def surface_samples(mesh: Mesh, rho: float, max_samples: int = 4_000_000) -> tuple[np.ndarray, float]:
    """Points on ``mesh`` such that every surface point is within the returned radius (``rho``, or
    more when the sample cap would be exceeded) of one of them."""
    v = np.asarray(mesh.vertices, dtype=float)
    f = np.asarray(mesh.faces, dtype=np.int64)
    r = triangle_cover_radius(v, f)
    while True:
        n = np.maximum(np.ceil(r / rho).astype(np.int64), 1)
        big = n > 1
        extra = int((n[big] * (n[big] + 1) // 2).sum())
        if len(v) + extra <= max_samples:
            break
        rho *= 1.5
    pts = [v]
    for level in np.unique(n[big]):
        tri = v[f[big & (n == level)]]  # (m, 3, 3)
        i, j = np.meshgrid(np.arange(level + 1), np.arange(level + 1), indexing="ij")
        keep = i + j <= level
        w1, w2 = i[keep] / level, j[keep] / level
        w0 = 1.0 - w1 - w2
        p = (w0[None, :, None] * tri[:, None, 0] + w1[None, :, None] * tri[:, None, 1]
             + w2[None, :, None] * tri[:, None, 2])
        pts.append(p.reshape(-1, 3))
    return np.vstack(pts), float(rho)


class DistanceGrid:
    """Lower and upper bounds on the distance from points to ``mesh``'s surface (mesh frame, metres).

    ``budget`` is the approximate number of grid vertices; ``margin`` (metres, default a quarter of
    the largest extent, at least 15 cm) pads the mesh's bounding box."""

    def __init__(self, mesh: Mesh, budget: int = 200_000, margin: float | None = None) -> None:
        v = np.asarray(mesh.vertices, dtype=float)
        lo, hi = v.min(axis=0), v.max(axis=0)
        self.box = np.array([lo, hi])
        ext = hi - lo
        if margin is None:
            margin = max(0.25 * float(ext.max()), 0.15)
        glo, ghi = lo - margin, hi + margin
        size = ghi - glo
        h = max(float(np.prod(size) / budget) ** (1.0 / 3.0), float(size.max()) / 512, 1e-6)
        shape = np.maximum(np.ceil(size / h).astype(np.int64), 1) + 1  # vertices per axis
        self.origin = glo
        self.cell = h
        self.shape = shape
        self.hi = glo + (shape - 1) * h
        samples, rho = surface_samples(mesh, 0.5 * h)
        self.rho = rho
        axes = [glo[i] + h * np.arange(shape[i]) for i in range(3)]
        grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
        # Near the surface: the nearest sample (a k-d tree query capped at ``cap``, as far points,
        # e.g. inside a large closed object, are slow to resolve). Farther: every surface point is
        # within half a cell diagonal of a grid vertex, which is then within that + rho of a sample
        # (the "shell"), so the Euclidean distance transform to the shell bounds the rest: from
        # below by the transform minus half a diagonal, from above by it plus the shell vertex's.
        cap = max(3.0 * h + rho, float(margin))
        dn, _ = cKDTree(samples).query(grid, workers=-1, distance_upper_bound=cap)
        dn = dn.reshape(tuple(shape))
        near = np.isfinite(dn)
        upper = np.where(near, dn, 0.0)
        lower = np.maximum(dn - rho, 0.0)
        if not near.all():
            from scipy.ndimage import distance_transform_edt

            far = ~near
            shell = near & (dn <= 0.5 * np.sqrt(3.0) * h + rho)  # vertices next to the surface
            edt, idx = distance_transform_edt(~shell, return_indices=True)
            edt = edt * h
            upper[far] = edt[far] + upper[tuple(i[far] for i in idx)]
            lower[far] = np.maximum(cap - rho, edt[far] - 0.5 * np.sqrt(3.0) * h)
        self.upper_grid = upper
        self.lower_grid = lower
        self._flat_lower = self.lower_grid.ravel()
        self._flat_upper = self.upper_grid.ravel()
        self._strides = np.array([shape[1] * shape[2], shape[2], 1], dtype=np.int64)

    def bounds(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(lower, upper)`` (N,) on the distance from each point (N,3, mesh frame) to the surface."""
        p = np.asarray(points, dtype=float).reshape(-1, 3)
        c = np.clip(p, self.origin, self.hi)
        out = np.sqrt(((p - c) ** 2).sum(axis=1))
        i0 = np.clip(np.floor((c - self.origin) / self.cell).astype(np.int64), 0, np.maximum(self.shape - 2, 0))
        base = i0 @ self._strides
        rel = c - (self.origin + i0 * self.cell)  # offset from the cell's low corner
        lower = np.full(len(p), -np.inf)
        upper = np.full(len(p), np.inf)
        for corner in _CORNERS:
            if np.any(corner >= self.shape):  # a flat grid (one vertex along an axis)
                continue
            k = base + corner @ self._strides
            dist = np.sqrt(((rel - corner * self.cell) ** 2).sum(axis=1))
            np.maximum(lower, self._flat_lower[k] - dist, out=lower)
            np.minimum(upper, self._flat_upper[k] + dist, out=upper)
        lower -= out
        upper += out
        gap = np.maximum(np.maximum(self.box[0] - p, p - self.box[1]), 0.0)
        np.maximum(lower, np.sqrt((gap ** 2).sum(axis=1)), out=lower)
        return np.maximum(lower, 0.0), upper

    def lower(self, points: np.ndarray) -> np.ndarray:
        return self.bounds(points)[0]

    def upper(self, points: np.ndarray) -> np.ndarray:
        return self.bounds(points)[1]
