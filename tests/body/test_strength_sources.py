"""Strength measured from posed figures against the cited sources, typed here from the sources
(independently of the data files): means by sex, posture curves, 5th percentiles, and which rows
stay uncited."""

import re
from importlib import resources

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.stats import norm

from jackpy.analysis.statics import Load, joint_torques
from jackpy.analysis.strength import dof_strengths, utilisation
from jackpy.body.human import make_human
from jackpy.body.strength import (default_cv, has_posture, posture_data, source_of, strength_rows, strength_table,
                                  torque)

# Kamon (1981) via Johnson, Biomechanics and Exercise Physiology, Table 2.2.2: N m at 45/90/135 deg
KAMON_SHOULDER_FLEXION = {"male": {45: 67, 90: 68, 135: 47}, "female": {45: 29, 90: 30, 135: 21}}
KAMON_ELBOW_FLEXION = {"male": {45: 52, 90: 85, 135: 60}, "female": {45: 24, 90: 43, 135: 23}}
KAMON_BACK_EXTENSION = {"male": 240, "female": 130}
# "Strength curve comparisons between gender for shoulder internal and external rotation": mean, SD
IRER = {("male", "IR"): (54.6, 16.0), ("female", "IR"): (24.7, 6.5),
        ("male", "ER"): (39.6, 15.5), ("female", "ER"): (20.4, 3.7)}
# Arch. Phys. Med. Rehabil. 88:1441 (2007): peak isometric neck flexion / extension, N m
NECK = {"male": (24.0, 36.4), "female": (16.6, 26.5)}
# 220 healthy women: neck rotation right / left, mean and SD, N m
NECK_ROTATION_F = {"right": (8.1, 2.3), "left": (7.9, 2.3)}
# every SD the data cite, as (mean, SD): Anderson et al. (2007) Table 3 c1 and c1_sd, IRER, the women's
# neck rotation - default_cv() is their mean SD/mean
CITED_SDS = [(0.161, 0.049), (0.181, 0.047), (0.113, 0.025), (0.127, 0.033), (0.163, 0.040), (0.159, 0.028),
             (0.087, 0.015), (0.080, 0.015), (0.095, 0.022), (0.104, 0.034), (0.033, 0.005), (0.027, 0.006),
             *IRER.values(), *NECK_ROTATION_F.values()]
#: Harbo, Brincks & Andersen (2012) isometric elbow flexion at the ANSUR II median body, age 30 (as
#: tests/body/test_body_strength.py types it)
HARBO_ELBOW = {"male": -23.8 - 0.13 * 30 + 22 * 1.75621 + 0.51 * 84.36567475048071,
               "female": 6.9 - 0.13 * 30 + 9 * 1.62847 + 0.18 * 66.88499194679233}
Z5 = norm.ppf(0.05)


@pytest.fixture(scope="module")
def figures():
    return {(sex, p): make_human(sex, p) for sex in ("male", "female") for p in (50, 5)}


def pose_arm(f, elevation_deg, elbow_deg=0.0, twist_deg=0.0):
    """Right arm elevated forward (abduction angle 90 deg: the sagittal plane), elbow flexed."""
    f.groups["right_shoulder_complex"].set_angles(f, np.radians([elevation_deg, 90.0, twist_deg]))
    f.joint("right_elbow").displacement = np.array([np.radians(elbow_deg)])
    assert f.joint("right_shoulder").displacement[1] == pytest.approx(np.radians(elevation_deg))


@pytest.mark.parametrize("sex", ["male", "female"])
def test_shoulder_elevation_follows_kamons_curve_on_the_figure(figures, sex):
    """The posed figure's shoulder elevators: the source's value at 45, 90 and 135 deg, linear between,
    held beyond; the peak (no posture) is the 90 deg value."""
    f = figures[(sex, 50)]
    q = f.q.copy()
    try:
        for phi, expect in [*KAMON_SHOULDER_FLEXION[sex].items(), (112.5, np.mean([KAMON_SHOULDER_FLEXION[sex][90],
                                                                                   KAMON_SHOULDER_FLEXION[sex][135]])),
                            (20.0, KAMON_SHOULDER_FLEXION[sex][45]), (160.0, KAMON_SHOULDER_FLEXION[sex][135])]:
            pose_arm(f, phi)
            assert strength_table(f, at_posture=True)["right_shoulder[1]"][1] == pytest.approx(expect, rel=1e-9)
        assert strength_table(f)["right_shoulder[1]"][1] == pytest.approx(KAMON_SHOULDER_FLEXION[sex][90])
    finally:
        f.q = q


@pytest.mark.parametrize("sex", ["male", "female"])
def test_elbow_flexion_is_harbos_peak_on_kamons_curve(figures, sex):
    """The elbow flexors of the posed figure, measured through the analysis code (a 5 kg load in the
    hand, utilisation of the acting group): Harbo's mean at 90 deg, Kamon's shape at 45 and 135 deg."""
    f = figures[(sex, 50)]
    q = f.q.copy()
    curve = KAMON_ELBOW_FLEXION[sex]
    try:
        for elbow, points in curve.items():
            pose_arm(f, 30.0, elbow)
            tau = joint_torques(f, [Load.held_mass(f, "right_palm", "grip", 5.0)])
            u = utilisation(f, tau, dof_strengths(strength_table(f, at_posture=True)))
            i = f.dof_names().index("right_elbow[0]")
            assert tau[i] > 0  # the flexors act
            assert tau[i] / u[i] == pytest.approx(HARBO_ELBOW[sex] * points / max(curve.values()), rel=1e-6)
    finally:
        f.q = q


@pytest.mark.parametrize("sex", ["male", "female"])
def test_fifth_percentile_figures(figures, sex):
    """A 5th-percentile figure: mean - 1.645 SD where the source gives an SD (shoulder rotation),
    mean (1 - 1.645 cv) otherwise (shoulder elevation at 90 deg, back extension)."""
    f = figures[(sex, 5)]
    q = f.q.copy()
    cv = np.mean([sd / mean for mean, sd in CITED_SDS])
    try:
        pose_arm(f, 90.0)
        t = strength_table(f, at_posture=True)
        assert t["right_shoulder[1]"][1] == pytest.approx(KAMON_SHOULDER_FLEXION[sex][90] * (1 + Z5 * cv), rel=1e-9)
        er, ir = t["right_shoulder[0]"]
        assert ir == pytest.approx(IRER[(sex, "IR")][0] + Z5 * IRER[(sex, "IR")][1], rel=1e-9)
        assert er == pytest.approx(IRER[(sex, "ER")][0] + Z5 * IRER[(sex, "ER")][1], rel=1e-9)
        assert t["l5_s1[2]"][0] == pytest.approx(KAMON_BACK_EXTENSION[sex] * (1 + Z5 * cv), rel=1e-9)
    finally:
        f.q = q


@pytest.mark.parametrize("sex", ["male", "female"])
def test_trunk_neck_and_rotation_means(figures, sex):
    t = strength_table(figures[(sex, 50)])
    assert t["l5_s1[2]"][0] == pytest.approx(KAMON_BACK_EXTENSION[sex])       # extensors (toward lower)
    flex, ext = NECK[sex]
    assert t["atlanto_occipital[2]"] == pytest.approx((ext, flex))
    assert t["right_shoulder[0]"] == pytest.approx((IRER[(sex, "ER")][0], IRER[(sex, "IR")][0]))


def test_womens_neck_rotation_and_its_spread():
    (right, sd_r), (left, sd_l) = NECK_ROTATION_F["right"], NECK_ROTATION_F["left"]
    assert torque("atlanto_occipital", "axial", "female", 50) == pytest.approx((right, left))
    assert torque("atlanto_occipital", "axial", "female", 5) == pytest.approx((right + Z5 * sd_r, left + Z5 * sd_l))


def test_default_cv_is_the_mean_of_the_cited_cvs():
    assert default_cv() == pytest.approx(np.mean([sd / mean for mean, sd in CITED_SDS]), rel=1e-12)
    assert 0.2 < default_cv() < 0.3


def test_every_row_names_a_source_defined_in_the_file_header():
    text = resources.files("jackpy.body").joinpath("data", "strength.csv").read_text()
    defined = set(re.findall(r"^# ([A-Z][A-Z0-9_]+)\s", text, flags=re.M))
    used = {r.source for r in strength_rows().values()}
    assert used <= defined, used - defined
    assert {"KAMON1981", "IRER", "NECK2007", "NECKROT_F220", "HARBO2012", "LAUBACH1976", "UNCITED"} <= used


def test_known_uncited_rows_are_marked():
    """Issue 19 item 6: horizontal adduction / abduction have no citable mean here, nor do the men's
    neck rotation and the shoulder's arm-lowering muscles; the hip/knee/ankle rows are Anderson's."""
    for side in ("lower", "upper"):
        assert source_of("shoulder", "abduction", side, "male") == "UNCITED"
        assert source_of("shoulder", "abduction", side, "female") == "LAUBACH1976"
        assert source_of("atlanto_occipital", "axial", side, "male") == "UNCITED"
        assert source_of("knee", "flexion", side, "female") == "ANDERSON2007"
    assert source_of("shoulder", "elevation", "lower", "male") == "UNCITED"
    assert source_of("shoulder", "elevation", "upper", "female") == "KAMON1981"


def test_posture_flags():
    assert has_posture("knee", "flexion") and not has_posture("elbow", "flexion")
    assert has_posture("elbow", "flexion", include_curves=True)
    assert has_posture("shoulder", "elevation", include_curves=True)
    assert not has_posture("shoulder", "twist", include_curves=True)


KINDS = sorted({(k[0], k[1]) for k in (*strength_rows(), *posture_data())})


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(KINDS), st.sampled_from(["male", "female"]), st.floats(1.0, 99.0),
       st.floats(-np.pi, np.pi))
def test_no_posture_is_stronger_than_the_peak(kind_dof, sex, percentile, angle):
    """Every posture's strength lies in (0, peak]: the curves are shapes of at most 1."""
    peak = torque(*kind_dof, sex, percentile)
    here = torque(*kind_dof, sex, percentile, angle=angle)
    assert all(0.0 < h <= p * (1 + 1e-12) for h, p in zip(here, peak))
