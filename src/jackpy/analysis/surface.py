"""Iso-surfaces of sampled volumes by naive surface nets (a dual-contouring cousin of marching cubes
that needs no case table; scikit-image is not a dependency).

One vertex per grid cube whose corners straddle the level, at the mean of the straddling edges'
linear crossings; one quad (two triangles) per straddling grid edge, joining the four cubes around
it. On a volume padded with outside values the result is closed and consistently oriented
(outward normals, positive volume).
"""

from __future__ import annotations

import numpy as np

from jackpy.peabody.geometry import Mesh

_CORNERS = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
_EDGES = [(a, b) for a in range(8) for b in range(a + 1, 8)
          if np.abs(_CORNERS[a] - _CORNERS[b]).sum() == 1]


def surface_nets(field: np.ndarray, level: float, spacing: float, origin: np.ndarray) -> Mesh:
    """The surface ``field == level`` (inside where ``field > level``) of samples on a regular grid:
    sample ``(i, j, k)`` lies at ``origin + spacing * (i, j, k)`` (metres). The field is padded with
    outside values, so the surface is closed."""
    f = np.pad(np.asarray(field, dtype=float), 1, constant_values=min(level - 1.0, float(np.min(field)) - 1.0))
    inside = f > level
    n = np.array(f.shape)
    # --- one vertex per straddling cube -------------------------------------------------------
    c = [inside[i:n[0] - 1 + i, j:n[1] - 1 + j, k:n[2] - 1 + k] for i, j, k in _CORNERS]
    vals = [f[i:n[0] - 1 + i, j:n[1] - 1 + j, k:n[2] - 1 + k] for i, j, k in _CORNERS]
    total = np.zeros(tuple(n - 1) + (3,))
    count = np.zeros(tuple(n - 1))
    for a, b in _EDGES:
        cross = c[a] != c[b]
        t = np.where(cross, (level - vals[a]) / np.where(cross, vals[b] - vals[a], 1.0), 0.0)
        p = _CORNERS[a] + t[..., None] * (_CORNERS[b] - _CORNERS[a])
        total += np.where(cross[..., None], p, 0.0)
        count += cross
    active = count > 0
    vid = np.full(active.shape, -1, dtype=np.int64)
    vid[active] = np.arange(int(active.sum()))
    cube_idx = np.argwhere(active)
    verts = cube_idx + total[active] / count[active][:, None]
    # --- one quad per straddling grid edge -----------------------------------------------------
    quads = []
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        lo = [slice(None)] * 3
        hi = [slice(None)] * 3
        lo[axis] = slice(0, n[axis] - 1)
        hi[axis] = slice(1, n[axis])
        a_in, b_in = inside[tuple(lo)], inside[tuple(hi)]
        edges = np.argwhere(a_in != b_in)  # edge from point e to e + unit(axis)
        outward = a_in[tuple(edges.T)]  # inside -> outside along +axis
        e = edges.copy()
        ring = []
        for du, dv in ((-1, -1), (0, -1), (0, 0), (-1, 0)):  # counter-clockwise about +axis
            cube = e.copy()
            cube[:, u] += du
            cube[:, v] += dv
            ring.append(vid[tuple(cube.T)])
        q = np.stack(ring, axis=1)
        quads.append(np.where(outward[:, None], q, q[:, ::-1]))
    q = np.concatenate(quads) if quads else np.zeros((0, 4), dtype=np.int64)
    faces = np.concatenate([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
    return Mesh(np.asarray(origin, dtype=float) + (verts - 1.0) * spacing, faces)


def mesh_volume(mesh: Mesh) -> float:
    """Signed volume (m^3) enclosed by a closed, outward-oriented triangle mesh."""
    v = mesh.vertices[mesh.faces]
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)
