"""The terrain's display mesh: on the surface, wound to face up, forbidden footholds tinted."""

from pathlib import Path

import numpy as np

from jackpy.locomotion.terrain import Terrain, load
from jackpy.locomotion.terrain_mesh import FORBIDDEN_COLOR, GROUND_COLOR, display_mesh

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "creatures"


def test_mesh_lies_on_the_terrain_and_faces_up():
    t = load(EXAMPLES / "rolling_hills.terrain.json")
    v, n, tri, c = display_mesh(t)
    nz, nx = t.shape
    assert v.shape == (nz * nx, 3) and tri.shape == (2 * (nz - 1) * (nx - 1), 3)
    assert np.allclose(v[:, 1], t.height(v[:, 0], v[:, 2]), atol=1e-12)
    a, b, d = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
    assert np.all(np.cross(b - a, d - a)[:, 1] > 0)  # counter-clockwise seen from +y
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0) and np.all(n[:, 1] > 0)
    xs, zs = v[:, 0], v[:, 2]
    x1, x2, z1, z2 = t.extent
    assert (xs.min(), xs.max(), zs.min(), zs.max()) == (x1, x2, z1, z2)


def test_every_forbidden_foothold_is_tinted_and_flat_ground_is_not():
    t = load(EXAMPLES / "steps.terrain.json")
    v, _, _, c = display_mesh(t)
    tinted = np.all(c == FORBIDDEN_COLOR, axis=1)
    assert tinted.any() and np.all(c[~tinted] == GROUND_COLOR)
    # the nearest display vertex of every forbidden raster sample is tinted
    a, b = np.nonzero(t.forbidden)
    x, z = t.x0 + b * t.raster_step, t.z0 + a * t.raster_step
    nz, nx = t.shape
    col = np.clip(np.rint((x - t.x0) / t.cell).astype(int), 0, nx - 1)
    row = np.clip(np.rint((z - t.z0) / t.cell).astype(int), 0, nz - 1)
    assert np.all(tinted[row * nx + col])
    flat = Terrain.flat(4.0, 0.25)
    assert not np.any(np.all(display_mesh(flat)[3] == FORBIDDEN_COLOR, axis=1))


def test_a_large_grid_is_sampled_down_keeping_its_edges():
    t = Terrain.from_function(lambda x, z: 0.05 * x, (0.0, 99.9), (0.0, 59.9), 0.1)
    v, _, tri, _ = display_mesh(t, max_side=100)
    assert len(v) <= 101 * 101 and tri.max() < len(v)
    x1, x2, z1, z2 = t.extent
    assert np.isclose(v[:, 0].max(), x2) and np.isclose(v[:, 2].max(), z2)
