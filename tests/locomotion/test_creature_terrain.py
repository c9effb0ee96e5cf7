"""Terrain (Sims Ch. 8): bilinear height queries and the forbidden raster."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from jackpy.errors import ParseError
from jackpy.locomotion.terrain import Terrain, load, save


def _random(seed=1, shape=(7, 9), cell=0.3):
    return Terrain(np.random.default_rng(seed).normal(0, 0.2, shape), cell, -1.0, 2.0)


def test_height_exact_at_vertices_and_linear_along_edges():
    t = _random()
    nz, nx = t.shape
    for i in range(nz):
        for j in range(nx):
            assert t.height(t.x0 + j * t.cell, t.z0 + i * t.cell) == pytest.approx(t.heights[i, j], abs=1e-12)
    s = np.linspace(0, 1, 11)
    along = t.height(t.x0 + (2 + s) * t.cell, t.z0 + 3 * t.cell)
    assert np.allclose(along, t.heights[3, 2] + s * (t.heights[3, 3] - t.heights[3, 2]))


@settings(max_examples=40, deadline=None)
@given(st.floats(-1.0, 1.5), st.floats(2.0, 3.8), st.floats(-2, 2), st.floats(-2, 2))
def test_planar_terrain_is_exact_and_translation_invariant(x, z, dx, dz):
    plane = Terrain.from_function(lambda X, Z: 0.3 * X - 0.2 * Z + 1.0, (-1.0, 1.6), (2.0, 4.0), 0.2)
    assert plane.height(x, z) == pytest.approx(0.3 * x - 0.2 * z + 1.0, abs=1e-9)
    assert np.allclose(plane.normal(x, z), np.array([-0.3, 1.0, 0.2]) / np.linalg.norm([-0.3, 1.0, 0.2]))
    t = _random()
    moved = Terrain(t.heights, t.cell, t.x0 + dx, t.z0 + dz)
    assert moved.height(x + dx, z + dz) == pytest.approx(t.height(x, z), abs=1e-9)


def test_vectorised_queries_match_scalar_ones():
    t = _random()
    xs, zs = np.random.default_rng(2).uniform(-1, 1.4, 50), np.random.default_rng(3).uniform(2, 3.8, 50)
    assert np.allclose(t.height(xs, zs), [t.height(a, b) for a, b in zip(xs, zs)])


def _step(rise=0.05, run=0.03, threshold=35.0):
    return Terrain.from_function(lambda x, z: np.clip((z - 1.0) / run, 0, 1) * rise, (-0.5, 0.5), (0.0, 2.0),
                                 0.05, max_slope_deg=threshold, foot_radius=0.03)


def test_flat_ground_has_no_forbidden_zone():
    assert not Terrain.flat(4.0, 0.1).forbidden.any()


def test_steep_step_forbids_its_face_and_a_foot_radius_band_below_only():
    t = _step()  # 45 degrees over the cell from z = 1.0 to 1.05
    r = t.raster_step
    assert t.is_forbidden(0.0, 1.02)  # on the face
    assert t.is_forbidden(0.0, 1.0 - 0.03 + 2 * r)  # inside the band below
    assert not t.is_forbidden(0.0, 1.0 - 0.03 - 2 * r)  # just beyond it
    assert not t.is_forbidden(0.0, 1.05 + 2 * r)  # no band on the high side
    assert not t.is_forbidden(0.0, 0.5) and not t.is_forbidden(0.0, 1.5)


def test_slopes_below_the_threshold_are_allowed():
    assert not _step(rise=0.03, run=0.05, threshold=35.0).forbidden.any()  # 31 degrees


def test_user_polygons_are_forbidden():
    t = Terrain.flat(4.0, 0.1)
    t.polygons = [np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)]
    t._forbidden = None
    assert t.is_forbidden(0.5, 0.5) and not t.is_forbidden(-0.5, 0.5)


def test_json_round_trip_and_errors(tmp_path):
    t = _random()
    t.polygons = [np.array([[0, 2.2], [0.5, 2.2], [0.5, 2.8]])]
    save(t, tmp_path / "t.json")
    back = load(tmp_path / "t.json")
    assert np.array_equal(back.heights, t.heights) and back.cell == t.cell and back.x0 == t.x0
    assert np.array_equal(back.polygons[0], t.polygons[0])
    (tmp_path / "bad.json").write_text('{"cell": 0.1,\n "heights": [[0, 1], [2]]}')
    with pytest.raises(ParseError, match="bad.json: heights"):
        load(tmp_path / "bad.json")
    (tmp_path / "syntax.json").write_text('{"cell": 0.1,\n "heights": [[0, 1] [2, 3]]}')
    with pytest.raises(ParseError, match=r"syntax.json:2:\d+"):
        load(tmp_path / "syntax.json")


def test_png_heightmap_and_mesh(tmp_path):
    from PIL import Image

    img = np.zeros((11, 21), dtype=np.uint8)
    img[:, 10:] = 255
    Image.fromarray(img).save(tmp_path / "h.png")
    t = Terrain.from_png(tmp_path / "h.png", (2.0, 1.0), 0.5)
    assert t.shape == (11, 21) and t.cell == pytest.approx(0.1)
    assert t.height(-0.9, 0.0) == 0.0 and t.height(0.9, 0.0) == pytest.approx(0.5)
    v = np.array([[0, 0, 0], [2, 0.4, 0], [2, 0.4, 2], [0, 0, 2]], float)
    m = Terrain.from_mesh(v, np.array([[0, 1, 2], [0, 2, 3]]), 0.25)
    assert m.height(1.0, 1.0) == pytest.approx(0.2, abs=1e-9)


def test_example_terrains(tmp_path):
    from pathlib import Path

    root = Path(__file__).resolve().parents[2] / "examples" / "creatures"
    hills = load(root / "rolling_hills.terrain.json")
    steps = load(root / "steps.terrain.json")
    assert not hills.forbidden.any()
    assert steps.forbidden.any()
    assert json.loads((root / "steps.terrain.json").read_text())["jackpy_terrain"] == 1


@settings(max_examples=100, deadline=None)
@given(st.recursive(st.none() | st.integers(-3, 3) | st.floats(allow_nan=False, allow_infinity=False, width=32),
                    lambda c: st.lists(c, max_size=4) | st.dictionaries(st.sampled_from(
                        ["heights", "cell", "origin", "max_slope_deg", "foot_radius", "polygons"]), c, max_size=6),
                    max_leaves=24))
def test_fuzzed_terrains_parse_or_fail_cleanly(data):
    try:
        t = Terrain.from_dict(data, "fuzz.json")
    except ParseError as exc:
        assert str(exc).startswith("fuzz.json: ")
        return
    assert np.isfinite(t.height(0.0, 0.0))
