"""L5/S1 low-back load (static sagittal model) and percent capable, against independent statics."""

import numpy as np
import pytest

from jackpy.analysis.statics import Load, joint_torques
from jackpy.body.strength import torque
from jackpy.ergonomics import Task, assess
from jackpy.ergonomics import constants as C


def stoop(poser, deg):
    """Bend at the hips with the arms hanging vertically (flexed forward by the same angle)."""
    poser.hinge(deg)
    for side in ("left", "right"):
        poser.arm(side, deg)


def test_moment_matches_the_statics_and_the_model_balances(poser):
    stoop(poser, 45.0)
    r = assess(poser.f, ["lowback"], Task(load_kg=12.0))["lowback"]
    w = r.worksheet
    loads = [Load.held_mass(poser.f, f"{s}_palm", "grip", 6.0) for s in ("left", "right")]
    tau = joint_torques(poser.f, loads)
    flex = tau[poser.f.joint_dof_slice("l5_s1")][2]  # l5_s1 flexion DOF, axis = l5's x
    assert w["flexion_moment_Nm"] == pytest.approx(-flex, rel=1e-9)
    # moment balance about the disc and the force sum along it
    assert (w["erector_force_N"] * C.ERECTOR_MOMENT_ARM_M + w["abdominal_force_N"] * C.ABDOMINAL_MOMENT_ARM_M
            == pytest.approx(w["flexion_moment_Nm"]))
    assert r.score == pytest.approx(w["erector_force_N"] - w["abdominal_force_N"] + w["axial_weight_N"])
    weight = (w["upper_body_mass_kg"] + 12.0) * 9.80665
    assert np.hypot(w["axial_weight_N"], w["shear_N"]) == pytest.approx(weight, rel=1e-9)
    assert w["disc_tilt_deg"] == pytest.approx(45.0, abs=1e-6)


def test_standing_upright_is_about_the_upper_body_weight(poser):
    r = assess(poser.f, ["lowback"], Task())["lowback"]
    w = r.worksheet
    weight = w["upper_body_mass_kg"] * 9.80665
    # the trunk's centre of mass lies a few cm ahead of the disc: some erector force on top of the weight;
    # upright standing loads of 500-800 N are the usual order (Nachemson's disc-pressure measurements)
    assert weight < r.score < 2.0 * weight
    assert 400.0 < r.score < 1000.0
    assert abs(w["shear_N"]) < 1e-6 and r.level == 1


def test_limits_and_levels(poser):
    stoop(poser, 60.0)
    light = assess(poser.f, ["lowback"], Task(load_kg=0.0))["lowback"]
    heavy = assess(poser.f, ["lowback"], Task(load_kg=20.0))["lowback"]
    assert heavy.score > light.score
    assert C.COMPRESSION_DESIGN_LIMIT_N < heavy.score < C.COMPRESSION_UPPER_LIMIT_N
    assert heavy.level == 2 and "3,400" in heavy.action
    stoop(poser, 90.0)
    very = assess(poser.f, ["lowback"], Task(load_kg=60.0))["lowback"]
    assert very.score > C.COMPRESSION_UPPER_LIMIT_N and very.level == 3


def test_asymmetric_posture_is_flagged(poser):
    poser.arm("right", 90.0, plane=0.0)  # the right hand's half of the load out to the side
    r = assess(poser.f, ["lowback"], Task(load_kg=15.0))["lowback"]
    assert any("asymmetric" in f for f in r.flags)


def test_percent_capable_inverts_the_strength_model(poser):
    stoop(poser, 40.0)
    r = assess(poser.f, ["capable"], Task(load_kg=10.0, sex="both"))["capable"]
    rows = {(x["joint"], x["dof"]): x for x in r.worksheet["joints"]}
    trunk = rows[("l5_s1", "flexion")]
    for sex in ("male", "female"):
        pct = trunk[f"{sex}_capable_pct"]
        assert 1.0 < pct < 99.0
        lo, hi = torque("spine", "flexion", sex, 100.0 - pct)
        assert (hi if trunk["moment_Nm"] >= 0 else lo) == pytest.approx(abs(trunk["moment_Nm"]), rel=1e-3)
    assert trunk["female_capable_pct"] < trunk["male_capable_pct"]
    assert r.score == min(x[f"{s}_capable_pct"] for x in r.worksheet["joints"] for s in ("male", "female"))
    assert r.worst == r.worksheet["weakest"]["female"]["joint"]


def test_percent_capable_falls_with_the_load(poser):
    for side in ("left", "right"):
        poser.arm(side, 90.0)
    scores = [assess(poser.f, ["capable"], Task(load_kg=kg, sex="female"))["capable"].score for kg in (0, 4, 8, 16)]
    assert scores == sorted(scores, reverse=True) and scores[0] > scores[-1]
    r = assess(poser.f, ["capable"], Task(load_kg=16, sex="female"))["capable"]
    assert "shoulder" in r.worst or "elbow" in r.worst


def test_legs_stand_on_the_feet_whatever_the_root(poser):
    poser.hinge(30.0)
    r = assess(poser.f, ["capable"], Task(load_kg=10.0))["capable"]
    rows = {(x["joint"], x["dof"]): x for x in r.worksheet["joints"]}
    assert r.worksheet["weight_share"] == pytest.approx({"left": 0.5, "right": 0.5}, abs=1e-4)
    hips = rows[("left_hip", "flexion")]["moment_Nm"] + rows[("right_hip", "flexion")]["moment_Nm"]
    poser.f.reroot("left_foot", "heel")  # the same posture rooted at a foot: the same standing torques
    try:
        again = assess(poser.f, ["capable"], Task(load_kg=10.0))["capable"]
    finally:
        poser.f.reroot("pelvis", "centre")
    rows2 = {(x["joint"], x["dof"]): x for x in again.worksheet["joints"]}
    for key in (("left_hip", "flexion"), ("right_knee", "flexion"), ("l5_s1", "flexion")):
        assert abs(rows2[key]["moment_Nm"]) == pytest.approx(abs(rows[key]["moment_Nm"]), rel=1e-6, abs=1e-6)
    assert hips < 0  # the hip extensors hold the bent-forward trunk
    seated = assess(poser.f, ["capable"], Task(seated=True))["capable"]
    assert not any(x["joint"].endswith("knee") for x in seated.worksheet["joints"])
    assert any("seated" in f for f in seated.flags)


def test_foot_reactions_hold_the_whole_body(poser):
    """The floor's reactions balance the body: the hips' torques equal the moment of everything
    above them about the hip axis, computed here from the segments' centres of mass."""
    from jackpy.analysis.statics import G, foot_reactions

    stoop(poser, 30.0)
    f = poser.f
    kin = f.kinematics()
    fk = kin.forward(f.q, f.location)
    reactions = foot_reactions(f, [], ["left_foot", "right_foot"], fk)
    assert sum(r.force for r in reactions) == pytest.approx([0.0, kin.mass.sum() * G, 0.0])
    tau = joint_torques(f, reactions, fk=fk)
    legs = [n for n in kin.segment_names if n.split("_", 1)[-1] in ("thigh", "shank", "foot", "toes")]
    coms = kin.segment_coms(fk)
    hip = fk.segments[kin.segment_index["left_thigh"]][:3, 3]
    upper = sum(kin.mass[i] * G * (coms[i][2] - hip[2]) for i, n in enumerate(kin.segment_names) if n not in legs)
    hips = tau[f.joint_dof_slice("left_hip")][2] + tau[f.joint_dof_slice("right_hip")][2]
    assert upper > 10.0 and hips == pytest.approx(-upper, rel=1e-9)


def test_percent_capable_uses_the_posture_curves(poser):
    """The elbow's flexor strength is read at the elbow's angle (the strength module's posture curve,
    Kamon 1981's shape): the p50 strength each row reports equals torque(..., angle) of the measured
    displacement, and bending the elbow from 45 to 90 degrees changes it."""
    seen = {}
    for deg in (45.0, 90.0):
        poser.neutral()
        poser.arm("right", 60.0)
        poser.elbow("right", deg)
        r = assess(poser.f, ["capable"], Task(load_kg=6.0, sex="female"))["capable"]
        row = next(x for x in r.worksheet["joints"] if x["joint"] == "right_elbow")
        angle = float(np.asarray(poser.f.joint("right_elbow").displacement).reshape(-1)[0])
        col = 1 if row["moment_Nm"] >= 0 else 0
        expected = torque("elbow", row["dof"], "female", 50.0, angle)[col]
        assert row["female_p50_strength_Nm"] == pytest.approx(expected, rel=1e-9)
        seen[deg] = row["female_p50_strength_Nm"]
    assert abs(seen[45.0] - seen[90.0]) > 0.05 * seen[90.0]
