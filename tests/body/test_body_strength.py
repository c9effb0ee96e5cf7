"""Strength table: every DOF, two directions, sex and percentile order."""

import numpy as np
import pytest

from jackpy.body.strength import default_cv, strength_table, torque


def test_every_dof_has_two_strengths(male50):
    t = strength_table(male50)
    assert list(t) == male50.dof_names()
    assert all(lo > 0 and hi > 0 for lo, hi in t.values())
    assert t["left_elbow[0]"] == pytest.approx((45.0, harbo("elbow", "male")))


def test_sex_and_percentile_order(female5, male95):
    f, m = strength_table(female5), strength_table(male95)
    assert all(f[k][0] < m[k][0] for k in f if not k.endswith("eye[0]") and "eye" not in k)
    assert torque("knee", "flexion", "male", 5)[0] < torque("knee", "flexion", "male", 50)[0] \
        < torque("knee", "flexion", "male", 95)[0]
    assert torque("elbow", "flexion", "female", 50)[0] == pytest.approx(0.56 * 45.0)  # uncited row


# Anderson, Madigan & Nussbaum (2007) J. Biomech. 40:3105-3113, Table 3, age 18-25, typed here from
# the table (independently of strength_posture.csv): (joint, side, sex) -> (c1, c1_sd, c2, c3).
ANDERSON_2007 = {
    ("hip", "lower", "male"): (0.161, 0.049, 0.958, 0.932),
    ("hip", "upper", "female"): (0.127, 0.033, 0.650, -0.350),
    ("knee", "lower", "male"): (0.163, 0.040, 1.258, 1.133),
    ("knee", "upper", "female"): (0.080, 0.015, 0.873, 0.635),
    ("ankle", "lower", "female"): (0.104, 0.034, 1.399, 0.424),
    ("ankle", "upper", "male"): (0.033, 0.005, 1.510, -0.187),
}
#: ANSUR II medians (population_ansur2.csv): sex -> (mass kg, stature m)
MEDIAN = {"male": (84.36567475048071, 1.75621), "female": (66.88499194679233, 1.62847)}

# Harbo, Brincks & Andersen (2012) Eur. J. Appl. Physiol. 112:267-275, isometric equations typed
# here from D. Bachasson's transcription (independently of strength_regression.csv):
# (function, sex) -> (intercept, per year, per m, per kg), N m
HARBO_2012 = {("elbow", "male"): (-23.8, -0.13, 22.0, 0.51), ("elbow", "female"): (6.9, -0.13, 9.0, 0.18),
              ("wrist", "male"): (-6.9, -0.07, 10.0, 0.21), ("wrist", "female"): (-22.2, -0.04, 23.0, 0.0)}


def harbo(function: str, sex: str, age: float = 30.0) -> float:
    """The source's mean isometric strength (N m) for the sex's ANSUR II median body at ``age``."""
    i, a, h, w = HARBO_2012[(function, sex)]
    mass, stature = MEDIAN[sex]
    return i + a * age + h * stature + w * mass


@pytest.mark.parametrize("sex", ["male", "female"])
def test_arm_strength_in_the_analysis_is_harbo_2012(sex):
    """Measured from a posed figure through the analysis code (joint torques of a 5 kg load, the
    utilisation of the acting muscle group): elbow flexors and wrist flexors are Harbo et al.'s means for the figure's sex at the median body, and their 5th percentile lies
    1.645 spread below (no SD in the source: the default cv, checked in test_strength_sources.py)."""
    from jackpy.analysis.statics import Load, joint_torques
    from jackpy.analysis.strength import dof_strengths, utilisation
    from jackpy.body.human import make_human

    f = make_human(sex, 50)
    f.groups["right_shoulder_complex"].set_angles(f, np.radians([90.0, 90.0, 0.0]))  # arm forward
    f.joint("right_elbow").displacement = np.array([np.radians(30.0)])
    tau = joint_torques(f, [Load.held_mass(f, "right_palm", "grip", 5.0)])
    u = utilisation(f, tau, dof_strengths(strength_table(f)))
    names = f.dof_names()
    i = names.index("right_elbow[0]")
    assert tau[i] > 0  # the flexors act
    assert u[i] == pytest.approx(tau[i] / harbo("elbow", sex), rel=1e-9)
    assert torque("wrist", "flexion", sex, 50)[1] == pytest.approx(harbo("wrist", sex), rel=1e-9)
    assert torque("elbow", "flexion", sex, 5)[1] == pytest.approx(harbo("elbow", sex) * (1 - 1.645 * default_cv()),
                                                                 rel=1e-3)


@pytest.mark.parametrize("key", sorted(ANDERSON_2007))
def test_fifth_percentile_is_mean_minus_1645_sd(key):
    kind, side, sex = key
    c1, sd, _, _ = ANDERSON_2007[key]
    m, h = MEDIAN[sex]
    i = 0 if side == "lower" else 1
    assert torque(kind, "flexion", sex, 50)[i] == pytest.approx(c1 * m * 9.81 * h, rel=1e-9)
    assert torque(kind, "flexion", sex, 5)[i] == pytest.approx((c1 - 1.645 * sd) * m * 9.81 * h, rel=1e-3)
    assert torque(kind, "flexion", sex, 95)[i] == pytest.approx((c1 + 1.645 * sd) * m * 9.81 * h, rel=1e-3)


def test_given_body_size_scales_by_weight_times_stature():
    base = torque("knee", "flexion", "male", 50)[0]
    assert torque("knee", "flexion", "male", 50, mass_kg=2 * MEDIAN["male"][0])[0] == pytest.approx(2 * base)
    assert torque("knee", "flexion", "male", 50, stature_m=1.5 * MEDIAN["male"][1])[0] == pytest.approx(1.5 * base)


@pytest.mark.parametrize("key", sorted(ANDERSON_2007))
def test_posture_curve_at_the_source_points(key):
    """cos(c2 (theta - c3)): the peak at c3, half of it a 60-degree phase away, the straight joint."""
    kind, side, sex = key
    _, _, c2, c3 = ANDERSON_2007[key]
    i = 0 if side == "lower" else 1
    peak = torque(kind, "flexion", sex, 50)[i]
    assert torque(kind, "flexion", sex, 50, angle=c3)[i] == pytest.approx(peak)
    for a in (c3 - np.pi / 3 / c2, c3 + np.pi / 3 / c2):
        assert torque(kind, "flexion", sex, 50, angle=a)[i] == pytest.approx(0.5 * peak)
    straight = max(0.1, np.cos(c2 * (0.0 - c3)))
    assert torque(kind, "flexion", sex, 50, angle=0.0)[i] == pytest.approx(straight * peak)


def test_knee_extension_is_weak_straight_and_strong_bent():
    """Male knee extensors: 14.5 % of the peak with the knee straight, the peak at 65 deg flexion."""
    straight = torque("knee", "flexion", "male", 50, angle=0.0)[0]
    bent = torque("knee", "flexion", "male", 50, angle=np.radians(65.0))[0]
    peak = torque("knee", "flexion", "male", 50)[0]
    assert straight / peak == pytest.approx(np.cos(1.258 * 1.133), rel=1e-6)
    assert bent / peak > 0.999


def test_strength_table_at_posture_reads_the_figure_angles(male50):
    assert male50.joint("left_knee").displacement[0] == 0.0  # the standard human stands straight-kneed
    peak = strength_table(male50)
    here = strength_table(male50, at_posture=True)
    assert here["left_knee[0]"][0] < 0.2 * peak["left_knee[0]"][0]
    # the straight elbow's flexors hold the 45-degree value of Kamon's curve (52 of 85 N m, men); its
    # extensors have no curve: unchanged
    assert here["left_elbow[0]"] == (peak["left_elbow[0]"][0], pytest.approx(peak["left_elbow[0]"][1] * 52 / 85))


def test_percent_capable_signature_over_percentiles_1_to_99():
    """ERGO's capable.py calls torque(kind, dof, sex, percentile) for P = 1..99."""
    for sex in ("male", "female"):
        for kind, dof in (("knee", "flexion"), ("hip", "flexion"), ("elbow", "flexion"), ("spine", "flexion")):
            vals = [torque(kind, dof, sex, p) for p in range(1, 100)]
            assert all(lo > 0 and hi > 0 for lo, hi in vals)
            assert all(a[0] <= b[0] and a[1] <= b[1] for a, b in zip(vals, vals[1:]))


@pytest.mark.parametrize("sex, neck_extend, trunk_extend", [("male", 36.4, 240.0), ("female", 26.5, 130.0)])
def test_neck_base_takes_the_neck_rows_and_the_lumbar_spine_the_trunks(sex, neck_extend, trunk_extend):
    """C7/T1 carries the head and neck: its strength is the neck's (NECK2007), not the trunk's
    back extension (KAMON1981), which the lumbar joints keep; posed, so at_posture reads real angles."""
    from jackpy.body.human import make_human
    from jackpy.body.skeleton import SPINE_DOFS
    f = make_human(sex, 50)
    f.groups["spine"].set_angles(f, np.array([0.3, 0.1, 0.05]))
    k = SPINE_DOFS.index("flexion")
    for at_posture in (False, True):
        t = strength_table(f, at_posture=at_posture)
        assert t[f"c7_t1[{k}]"][0] == pytest.approx(neck_extend)
        assert t[f"c7_t1[{k}]"] == t[f"atlanto_occipital[{k}]"]
        for lumbar in ("l5_s1", "l4_l5", "l3_l4", "l2_l3", "l1_l2"):
            assert t[f"{lumbar}[{k}]"][0] == pytest.approx(trunk_extend)
