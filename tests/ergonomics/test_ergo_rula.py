"""RULA (McAtamney & Corlett 1993) scored from postures posed on the standard human."""

import pytest

from jackpy.ergonomics import Task, assess
from jackpy.ergonomics import constants as C
from jackpy.ergonomics.rula import load_score


def rula(f, **task):
    return assess(f, ["rula"], Task(**task))["rula"]


def test_neutral_standing_is_the_lowest_rula(poser):
    r = rula(poser.f)
    ws = r.worksheet
    # arms hanging straight: RULA scores the lower arm 2 below 60° elbow flexion; everything else minimal
    assert (ws["upper_arm"], ws["lower_arm"], ws["wrist"], ws["wrist_twist"]) == (1, 2, 1, 1)
    assert (ws["neck"], ws["trunk"], ws["legs"]) == (1, 1, 1)
    assert ws["table_a"] == 2 and ws["table_b"] == 1
    assert r.score == 2 and r.level == 1
    # with the elbows in the 60-100° band every part is at its minimum: the grand score's floor, 1
    for side in ("left", "right"):
        poser.elbow(side, 80.0)
    r = rula(poser.f)
    assert r.score == 1 and r.level == 1
    assert int(C.RULA_TABLE_C.min()) == 1


def test_arms_overhead_trunk_flexed_60_is_rula_7(poser):
    for side in ("left", "right"):
        poser.arm(side, 180.0, plane=90.0)
    poser.hinge(60.0)
    held = rula(poser.f, static=True)  # arms held overhead: static muscle use
    ws = held.worksheet
    assert ws["upper_arm"] == 5  # 90°+ (4), shoulder raised with the arm overhead (+1)
    assert ws["adjustments"]["shoulder_raised"]["measured"]
    assert ws["trunk"] == 4  # 60°+
    assert (ws["table_a"], ws["table_b"], ws["score_c"], ws["score_d"]) == (5, 5, 6, 6)
    assert held.score == 7 and held.level == 4
    # looking up at the hands instead of holding still: the neck in extension also gives 7
    poser.neck(flexion=-20.0)
    looking = rula(poser.f)
    assert looking.worksheet["neck"] == 4
    assert looking.score == 7


def _arm(poser, side, deg):
    if deg < 0:
        poser.arm(side, -deg, plane=-90.0)
    else:
        poser.arm(side, deg, plane=90.0)


@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize("deg,score", [(19, 1), (21, 2), (44, 2), (46, 3), (89, 3), (91, 4), (-19, 1), (-21, 2)])
def test_upper_arm_steps_at_its_thresholds(poser, side, deg, score):
    _arm(poser, side, deg)
    r = rula(poser.f, side=side)
    assert r.posture["upper_arm_flexion"] == pytest.approx(deg, abs=1e-6)
    assert r.worksheet["upper_arm"] == score


@pytest.mark.parametrize("deg,score", [(44, 1), (46, 2)])
def test_abducted_arm_adds_one(poser, deg, score):
    poser.arm("right", deg, plane=0.0)
    assert rula(poser.f, side="right").worksheet["upper_arm"] == score


@pytest.mark.parametrize("deg,score", [(59, 2), (61, 1), (99, 1), (101, 2)])
def test_lower_arm_steps_at_its_thresholds(poser, deg, score):
    poser.elbow("left", deg)
    assert rula(poser.f, side="left").worksheet["lower_arm"] == score


@pytest.mark.parametrize("deg,score", [(4, 1), (6, 2), (14, 2), (16, 3), (-6, 2), (-16, 3)])
def test_wrist_steps_at_its_thresholds(poser, deg, score):
    poser.wrist("left", flexion=deg)
    assert rula(poser.f, side="left").worksheet["wrist"] == score


@pytest.mark.parametrize("deg,score", [(9, 1), (11, 2), (19, 2), (21, 3), (-4, 1), (-6, 4)])
def test_neck_steps_at_its_thresholds(poser, deg, score):
    poser.neck(flexion=deg)
    assert rula(poser.f).worksheet["neck"] == score


@pytest.mark.parametrize("deg,score", [(4, 1), (6, 2), (19, 2), (21, 3), (59, 3), (61, 4)])
def test_trunk_steps_at_its_thresholds(poser, deg, score):
    poser.hinge(deg)
    r = rula(poser.f)
    assert r.posture["trunk_flexion"] == pytest.approx(deg, abs=1e-6)
    assert r.worksheet["trunk"] == score


@pytest.mark.parametrize("deg,add", [(9, 0), (11, 1)])
def test_neck_twist_adds_one(poser, deg, add):
    poser.neck(twist=deg)
    assert rula(poser.f).worksheet["neck"] == 1 + add


def test_one_foot_off_the_floor_scores_legs_2(poser):
    poser.lift_foot("left")
    r = rula(poser.f)
    assert r.posture["feet_bearing"] == ["right"]
    assert r.worksheet["legs"] == 2


def test_overrides_replace_what_the_posture_gives(poser):
    r = rula(poser.f, side="left", overrides={"shoulder_raised": True})
    assert r.worksheet["upper_arm"] == 2
    assert r.worksheet["adjustments"]["shoulder_raised"] == {"measured": False, "value": True, "overridden": True}


def test_hand_checked_worksheet(poser):
    """Upper arm 60° (3), elbow 30° (2), wrist 10° (2), neck 11° (2), trunk 25° (3), 5 kg
    intermittent (force 1, muscle 0): Table A 4, C 5; Table B 4, D 5; Table C 6. Repeated, the
    same load scores force 2 and muscle 1: C 7, D 7, grand score 7."""
    poser.arm("right", 60.0)
    poser.elbow("right", 30.0)
    poser.wrist("right", flexion=10.0)
    poser.hinge(25.0)
    poser.neck(flexion=11.0)
    r = rula(poser.f, side="right", load_kg=5.0)
    ws = r.worksheet
    assert (ws["upper_arm"], ws["lower_arm"], ws["wrist"], ws["wrist_twist"], ws["table_a"]) == (3, 2, 2, 1, 4)
    assert (ws["neck"], ws["trunk"], ws["legs"], ws["table_b"]) == (2, 3, 1, 4)
    assert (ws["muscle_use"], ws["force_load"], ws["score_c"], ws["score_d"]) == (0, 1, 5, 5)
    assert r.score == 6 and r.level == 3
    r = rula(poser.f, side="right", load_kg=5.0, repeated=True)
    assert (r.worksheet["muscle_use"], r.worksheet["force_load"], r.worksheet["score_c"], r.worksheet["score_d"]) == (1, 2, 7, 7)
    assert r.score == 7 and r.level == 4


@pytest.mark.parametrize("kg,static,shock,score", [(1.9, False, False, 0), (2.0, False, False, 1), (9.9, False, False, 1),
                                                    (10.0, False, False, 2), (5.0, True, False, 2),
                                                    (10.0, True, False, 3), (0.0, False, True, 3)])
def test_force_load_score(kg, static, shock, score):
    assert load_score(Task(load_kg=kg, static=static, shock=shock)) == score


@pytest.mark.parametrize("deg,twist", [(59.0, 1), (61.0, 2), (-61.0, 2)])
def test_wrist_twist_near_the_end_of_the_range(poser, deg, twist):
    for k in (1, 2):
        poser.joint(f"right_forearm_twist_{k}", deg / 2)
    assert rula(poser.f, side="right").worksheet["wrist_twist"] == twist


def test_hand_across_the_midline_adds_to_the_lower_arm(poser):
    poser.arm("right", 60.0, plane=90.0)
    poser.elbow("right", 95.0)
    r = rula(poser.f, side="right")
    assert r.posture["hand_across_midline_m"] == 0.0 and r.worksheet["lower_arm"] == 1
    poser.arm("right", 60.0, plane=90.0, twist=60.0)  # rotated inward: the hand crosses the body's midline
    r = rula(poser.f, side="right")
    assert r.posture["hand_across_midline_m"] > 0.0
    assert r.worksheet["lower_arm"] == 2


def test_worst_contributor_is_the_part_that_raises_the_score_most(poser):
    poser.hinge(65.0)  # trunk 4: back to upright would lower the grand score the most
    r = rula(poser.f)
    assert r.worst == "trunk"
    poser.neutral()
    for side in ("left", "right"):
        poser.arm(side, 120.0)
    assert rula(poser.f).worst == "upper_arm"
