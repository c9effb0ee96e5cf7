"""de Leva table checks and mesh mass properties."""

import numpy as np
import pytest

from jackpy.body.segment_inertia import GROUPS, de_leva, mesh_mass_properties
from jackpy.body.shapes import signed_volume, superellipse_ring, tube


def test_de_leva_fractions_check():
    for sex, total in (("male", 100.00), ("female", 99.99)):
        t = de_leva(sex)
        s = t["head"]["mass_pct"] + t["trunk"]["mass_pct"] + 2 * sum(
            t[k]["mass_pct"] for k in ("upper_arm", "forearm", "hand", "thigh", "shank", "foot"))
        assert s == pytest.approx(total, abs=1e-9)
        parts = sum(t[k]["mass_pct"] for k in ("upper_trunk", "mid_trunk", "lower_trunk"))
        assert parts == pytest.approx(t["trunk"]["mass_pct"], abs=1e-9)
        assert 0 < min(r["com_pct"] for r in t.values()) and max(r["com_pct"] for r in t.values()) < 100
    assert de_leva("male")["upper_trunk"]["r_sag"] > de_leva("male")["upper_trunk"]["r_trans"]
    assert set(GROUPS) == {k for k in de_leva("male") if k != "trunk"}


def test_mesh_mass_properties_of_a_cylinder():
    r, h, n = 0.05, 0.4, 256
    rings = np.stack([superellipse_ring(np.array([0, y, 0.0]), np.array([1.0, 0, 0]), np.array([0, 0, 1.0]), r, r, n)
                      for y in (0.0, h)])
    mesh = tube(rings)
    vol, c, inertia = mesh_mass_properties(mesh)
    assert signed_volume(mesh) == pytest.approx(vol)
    assert vol == pytest.approx(np.pi * r * r * h, rel=1e-3)
    assert np.allclose(c, [0, h / 2, 0], atol=1e-9)
    assert inertia[1, 1] / vol == pytest.approx(r * r / 2, rel=2e-3)
    assert inertia[0, 0] / vol == pytest.approx(r * r / 4 + h * h / 12, rel=2e-3)


def test_figure_segments_take_de_leva(male50):
    f = male50
    t = de_leva("male")
    m = f.body_spec.mass
    assert f.segment("left_thigh").mass == pytest.approx(m * t["thigh"]["mass_pct"] / 100)
    hand = sum(f.segment(n).mass for n in f.segments if n.startswith("left_") and
               n.split("_")[1] in ("palm", "thumb", "index", "middle", "ring", "little"))
    assert hand == pytest.approx(m * t["hand"]["mass_pct"] / 100)
    thigh = f.segment("left_thigh")
    knee = thigh.site("knee").location[:3, 3]
    assert thigh.com == pytest.approx(knee * t["thigh"]["com_pct"] / 100)
    for s in f.segments.values():
        if s.mass > 0:
            assert np.all(np.linalg.eigvalsh(s.inertia) > 0)
