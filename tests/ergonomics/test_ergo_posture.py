"""The posture measurements: zero in neutral standing, and each posed angle measured back exactly."""

import numpy as np
import pytest

from jackpy.ergonomics import measure
from jackpy.errors import FigureError
from jackpy.peabody.model import Figure, Segment


def test_neutral_standing_measures_upright(poser):
    p = measure(poser.f)
    for name in ("trunk_flexion", "trunk_side_bend", "trunk_twist", "neck_flexion", "neck_side_bend", "neck_twist"):
        assert getattr(p, name) == pytest.approx(0.0, abs=1e-9), name
    for side in ("left", "right"):
        a = p.arms[side]
        assert a.upper_arm_flexion == pytest.approx(0.0, abs=1e-9)
        assert a.upper_arm_abduction == pytest.approx(7.0, abs=1e-6)  # NEUTRAL_ARM_ELEVATION, sideways
        assert a.elbow_flexion == pytest.approx(0.0, abs=1e-6)
        assert a.wrist_flexion == pytest.approx(0.0, abs=1e-9)
        assert p.knee_flexion[side] == pytest.approx(0.0, abs=1e-6)
    assert sorted(p.feet_bearing()) == ["left", "right"]


@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize("deg", [-30.0, 19.0, 46.0, 91.0, 150.0])
def test_upper_arm_flexion_and_abduction(poser, side, deg):
    if deg < 0:
        poser.arm(side, -deg, plane=-90.0)
    else:
        poser.arm(side, deg, plane=90.0)
    a = measure(poser.f).arms[side]
    assert a.upper_arm_flexion == pytest.approx(deg, abs=1e-6)
    assert a.upper_arm_abduction == pytest.approx(0.0, abs=1e-6)
    poser.arm(side, 50.0, plane=0.0)
    assert measure(poser.f).arms[side].upper_arm_abduction == pytest.approx(50.0, abs=1e-6)


@pytest.mark.parametrize("side", ["left", "right"])
def test_elbow_wrist_and_forearm(poser, side):
    poser.elbow(side, 85.0)
    poser.wrist(side, flexion=-22.0)
    poser.joint(f"{side}_forearm_twist_1", 30.0)
    poser.joint(f"{side}_forearm_twist_2", 35.0)
    a = measure(poser.f).arms[side]
    assert a.elbow_flexion == pytest.approx(85.0, abs=1e-6)
    assert a.wrist_flexion == pytest.approx(-22.0, abs=1e-6)
    assert a.forearm_pronation == pytest.approx(65.0, abs=1e-6)
    poser.wrist(side, deviation=12.0)
    a = measure(poser.f).arms[side]
    assert a.wrist_deviation == pytest.approx(12.0, abs=1e-6)
    assert a.wrist_flexion == pytest.approx(0.0, abs=1e-6)


def test_trunk_hinge_side_bend_twist_and_neck(poser):
    poser.hinge(37.0)
    p = measure(poser.f)
    assert p.trunk_flexion == pytest.approx(37.0, abs=1e-6)
    assert p.hip_flexion["left"] == pytest.approx(37.0, abs=1e-6)
    assert sorted(p.feet_bearing()) == ["left", "right"]  # legs still vertical, feet flat
    poser.neutral()
    poser.spine(axial=30.0)
    p = measure(poser.f)
    below_t1 = [j for j in poser.f.groups["spine"].joints if j != "c7_t1"]  # c7_t1 turns the neck, not the thorax
    twist = np.degrees(sum(poser.f.joint(j).displacement[0] for j in below_t1))
    assert 25.0 < twist < 30.0
    assert p.trunk_twist == pytest.approx(twist, abs=1e-6)  # + = shoulders turned to the left
    assert p.trunk_flexion == pytest.approx(0.0, abs=1e-6)
    poser.spine(lateral=25.0)
    p = measure(poser.f)
    assert p.trunk_side_bend > 5.0  # the chord of a bent spine leans less than the summed bend
    poser.neutral()
    poser.neck(flexion=18.0)
    assert measure(poser.f).neck_flexion == pytest.approx(18.0, abs=1e-6)
    poser.neck(twist=-25.0)
    assert measure(poser.f).neck_twist == pytest.approx(-25.0, abs=1e-6)


def test_knees(poser):
    poser.knees(45.0)
    p = measure(poser.f)
    assert p.knee_flexion["left"] == pytest.approx(45.0, abs=1e-6)
    assert p.knee_flexion["right"] == pytest.approx(45.0, abs=1e-6)


def test_non_human_figure_is_refused():
    f = Figure("box")
    f.add_segment(Segment("box"))
    with pytest.raises(FigureError, match="not a standard human"):
        measure(f)
