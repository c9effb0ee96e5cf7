"""SASS rules: free and fixed stature, mass-stature, percentile <-> value, overrides, uneven scaling."""

import numpy as np
import pytest

from jackpy.body.anthropometry import AnthropometryError, load_population
from jackpy.body.human import make_human
from jackpy.body.sass import (
    STATURE_PATH,
    ScalingError,
    mass_for_stature,
    scale_segment_unevenly,
    set_dimension,
    set_mass,
    set_stature,
    spec_for,
    uneven_scale,
)


def test_stature_is_sum_of_path_and_free_rule():
    s = spec_for("male", 50)
    assert s.stature == pytest.approx(sum(s.dims[k] for k in STATURE_PATH))
    t = set_dimension(s, "thigh.length", s.dims["thigh.length"] + 0.02)
    assert t.stature == pytest.approx(s.stature + 0.02)
    assert t.dims["hip.breadth"] == s.dims["hip.breadth"]
    u = set_stature(s, s.stature + 0.05)
    assert u.stature == pytest.approx(s.stature + 0.05)
    assert all(u.dims[k] > s.dims[k] for k in STATURE_PATH)
    assert all(u.dims[k] == s.dims[k] for k in s.dims if k not in STATURE_PATH)


def test_fixed_rule_holds_stature_within_5_95():
    s = spec_for("female", 50)
    pop = load_population("ansur2")
    t = set_dimension(s, "thigh.length", s.dims["thigh.length"] + 0.03, rule="fixed")
    assert t.stature == pytest.approx(s.stature, abs=1e-12)
    for k in STATURE_PATH:
        if k != "thigh.length":
            v = pop.dimension("female", k).values
            assert v[1] - 1e-12 <= t.dims[k] <= v[5] + 1e-12
    with pytest.raises(ScalingError):
        set_dimension(s, "thigh.length", s.dims["thigh.length"] + 0.30, rule="fixed")


def test_fixed_rule_clamps_and_shares_the_rest():
    pop = load_population("ansur2")
    s = set_dimension(spec_for("male", 50), "shank.length", pop.value("male", "shank.length", 10))
    t = set_dimension(s, "spine.length", s.dims["spine.length"] + 0.08, rule="fixed")
    clamped = [k for k in STATURE_PATH if k != "spine.length"
               and t.dims[k] == pytest.approx(pop.dimension("male", k).values[1])]
    assert clamped == ["shank.length"]  # it hit its 5th percentile first; the others took the rest
    assert t.stature == pytest.approx(s.stature)


def test_mass_stature_rule():
    s = spec_for("male", 50)
    t = set_stature(s, 1.9, tie_mass=True)
    assert t.mass == pytest.approx(s.mass * (1.9 / s.stature) ** 2)
    assert mass_for_stature(70.0, 1.7, 1.7) == 70.0
    u = set_mass(s, s.mass * 1.21, tie_stature=True)
    assert u.stature == pytest.approx(s.stature * 1.1)
    assert set_mass(s, 60.0).stature == s.stature


def test_percentile_value_round_trip():
    pop = load_population("ansur2")
    for name in ("stature", "thigh.length", "hand.breadth", "mass"):
        for p in (1, 3, 5, 20, 50, 77, 95, 99):
            v = pop.value("female", name, p)
            assert pop.percentile("female", name, v) == pytest.approx(p)
    with pytest.raises(AnthropometryError):
        pop.value("female", "stature", 0.5)
    with pytest.raises(AnthropometryError):
        load_population("martians")


def test_overrides_in_make_human():
    f = make_human("male", 50, overrides={"stature": 1.80, "mass": 70.0})
    assert f.site_world("head", "top")[1, 3] == pytest.approx(1.80)
    assert f.total_mass == pytest.approx(70.0)
    g = make_human("male", 50, overrides={"hand.length": 0.21})
    tip = g.site_world("right_middle_3", "tip")[:3, 3]
    wrist = g.site_world("right_palm", "base")[:3, 3]
    assert np.linalg.norm(tip - wrist) == pytest.approx(0.21, rel=0.08)
    with pytest.raises(AnthropometryError):
        make_human("male", 50, overrides={"tail.length": 0.3})


def test_uneven_scaling():
    pts = np.array([[0.05, 0.0, 0.0], [0.05, -0.5, 0.0], [0.05, -0.25, 0.02], [0.0, 0.1, 0.0]])
    axis, r0, r1 = np.array([0, -1.0, 0]), np.zeros(3), np.array([0, -0.5, 0])
    out = uneven_scale(pts, axis, r0, r1, np.array([2.0, 1, 1]), np.array([1.0, 1, 1]))
    assert out[0, 0] == pytest.approx(0.10) and out[1, 0] == pytest.approx(0.05)
    assert out[2, 0] == pytest.approx(0.075) and out[3, 0] == 0.0
    same = uneven_scale(pts, axis, r0, r1, np.array([1.2, 0.9, 1.1]), np.array([1.2, 0.9, 1.1]))
    assert np.allclose(same, pts * [1.2, 0.9, 1.1])


def test_scale_segment_unevenly_keeps_children_attached():
    f = make_human("female", 50)
    before = f.site_world("left_shank", "base")[:3, 3]
    scale_segment_unevenly(f, "left_thigh", np.array([0, -1.0, 0]), "base", "knee",
                           np.array([1.1, 1.0, 1.1]), np.array([0.9, 1.0, 0.9]))
    after = f.site_world("left_shank", "base")[:3, 3]
    assert np.allclose(f.site_world("left_thigh", "knee")[:3, 3], after)
    assert np.allclose(before, after)  # knee on the axis: scaling across it does not move it
