"""A terrain as a triangle mesh for display: the height grid shaded, forbidden zones tinted.

Plain arrays (the renderer's :class:`jackpy.render.mesh.Mesh` takes them as they are): vertices
(N, 3) in metres on the terrain surface (world frame, y up), unit upward normals (N, 3), triangles
(M, 3) wound counter-clockwise seen from above (+y), and per-vertex colours (N, 3) in [0, 1].

The grid is shown at its own resolution up to ``max_side`` vertices a side (a larger grid is
sampled every k-th row and column, its last row and column always kept). The forbidden raster is
finer than the grid (a quarter of the foot radius), so a display vertex is tinted when any raster
sample within half a display spacing of it is forbidden: the tint covers every forbidden foothold,
slightly generously, never less.
"""

from __future__ import annotations

import math

import numpy as np

from jackpy.locomotion.terrain import Terrain

GROUND_COLOR = (0.56, 0.62, 0.46)
"""Allowed ground (a muted grass green)."""
FORBIDDEN_COLOR = (0.86, 0.30, 0.24)
"""Forbidden footholds: steep slopes, their downhill band and user polygons."""


def _indices(n: int, stride: int) -> np.ndarray:
    idx = np.arange(0, n, stride)
    return idx if idx[-1] == n - 1 else np.append(idx, n - 1)


def display_mesh(terrain: Terrain, max_side: int = 256) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(vertices, normals, triangles, colours) of ``terrain`` (module docstring)."""
    nz, nx = terrain.shape
    stride = max(1, math.ceil((max(nz, nx) - 1) / max(1, max_side - 1)))
    rows, cols = _indices(nz, stride), _indices(nx, stride)
    zz, xx = np.meshgrid(terrain.z0 + rows * terrain.cell, terrain.x0 + cols * terrain.cell, indexing="ij")
    yy = terrain.heights[np.ix_(rows, cols)]
    vertices = np.column_stack([xx.ravel(), yy.ravel(), zz.ravel()])
    # normals of the bilinear surface (at a grid vertex: the gradient of the cell it starts)
    gx, gz = terrain.gradient(xx.ravel(), zz.ravel())
    normals = np.column_stack([-np.asarray(gx), np.ones(vertices.shape[0]), -np.asarray(gz)])
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    a = (np.arange(len(rows) - 1)[:, None] * len(cols) + np.arange(len(cols) - 1)[None, :]).ravel()
    b, c = a + 1, a + len(cols)
    d = c + 1
    triangles = np.concatenate([np.column_stack([a, c, b]), np.column_stack([b, c, d])])
    tint = forbidden_at(terrain, xx.ravel(), zz.ravel(), 0.5 * stride * terrain.cell)
    colours = np.where(tint[:, None], FORBIDDEN_COLOR, GROUND_COLOR)
    return vertices, normals, triangles, colours


def forbidden_at(terrain: Terrain, x: np.ndarray, z: np.ndarray, radius: float) -> np.ndarray:
    """Boolean per point: some forbidden raster sample lies within ``radius`` (m, per axis) of it."""
    from scipy.ndimage import maximum_filter

    f = terrain.forbidden
    r = terrain.raster_step
    k = max(0, int(math.ceil(radius / r)))
    grown = maximum_filter(f, size=2 * k + 1, mode="nearest") if k and f.any() else f
    col = np.clip(np.rint((np.asarray(x, float) - terrain.x0) / r).astype(int), 0, f.shape[1] - 1)
    row = np.clip(np.rint((np.asarray(z, float) - terrain.z0) / r).astype(int), 0, f.shape[0] - 1)
    return grown[row, col]
