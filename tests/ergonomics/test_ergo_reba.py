"""REBA (Hignett & McAtamney 2000) scored from postures posed on the standard human."""

import pytest

from jackpy.ergonomics import ErgonomicsError, Task, assess
from jackpy.ergonomics.reba import action_level, load_score


def reba(f, **task):
    return assess(f, ["reba"], Task(**task))["reba"]


def test_neutral_standing_is_the_lowest_reba(poser):
    r = reba(poser.f)
    ws = r.worksheet
    assert (ws["trunk"], ws["neck"], ws["legs"], ws["table_a"]) == (1, 1, 1, 1)
    assert (ws["upper_arm"], ws["lower_arm"], ws["wrist"], ws["table_b"]) == (1, 2, 1, 1)
    assert r.score == 1 and r.level == 0  # the method's minimum: negligible risk


@pytest.mark.parametrize("deg,score", [(4, 1), (6, 2), (20, 2), (21, 3), (60, 3), (61, 4)])
def test_trunk_steps_just_above_its_thresholds(poser, deg, score):
    poser.hinge(deg)
    assert reba(poser.f).worksheet["trunk"] == score


@pytest.mark.parametrize("deg,score", [(20, 1), (21, 2), (-4, 1), (-6, 2)])
def test_neck(poser, deg, score):
    poser.neck(flexion=deg)
    assert reba(poser.f).worksheet["neck"] == score


@pytest.mark.parametrize("deg,score", [(19, 1), (21, 2), (44, 2), (46, 3), (89, 3), (91, 4), (-21, 2)])
def test_upper_arm_steps_at_its_thresholds(poser, deg, score):
    if deg < 0:
        poser.arm("left", -deg, plane=-90.0)
    else:
        poser.arm("left", deg, plane=90.0)
    assert reba(poser.f, side="left").worksheet["upper_arm"] == score


@pytest.mark.parametrize("deg,score", [(59, 2), (61, 1), (99, 1), (101, 2)])
def test_lower_arm(poser, deg, score):
    poser.elbow("right", deg)
    assert reba(poser.f, side="right").worksheet["lower_arm"] == score


@pytest.mark.parametrize("deg,score", [(14, 1), (16, 2), (-16, 2)])
def test_wrist(poser, deg, score):
    poser.wrist("right", flexion=deg)
    assert reba(poser.f, side="right").worksheet["wrist"] == score


@pytest.mark.parametrize("deg,add", [(29, 0), (31, 1), (59, 1), (61, 2)])
def test_knee_flexion_adds_to_legs(poser, deg, add):
    poser.knees(deg)
    ws = reba(poser.f).worksheet
    assert ws["knee_adjustment"] == add
    assert ws["legs"] == 1 + add


def test_one_foot_bearing_scores_legs_2(poser):
    poser.lift_foot("left")
    assert reba(poser.f).worksheet["legs"] >= 2


def test_load_coupling_activity_and_levels(poser):
    assert [load_score(Task(load_kg=k)) for k in (4.9, 5.0, 10.0, 10.1)] == [0, 1, 1, 2]
    assert load_score(Task(load_kg=1.0, shock=True)) == 1
    r = reba(poser.f, coupling="poor", static=True, repeated=True)
    assert r.worksheet["coupling"] == 2 and r.worksheet["activity"] == 2
    assert r.worksheet["score_b"] == r.worksheet["table_b"] + 2
    assert [action_level(s)[0] for s in (1, 2, 3, 4, 7, 8, 10, 11, 15)] == [0, 1, 1, 2, 2, 3, 3, 4, 4]
    with pytest.raises(ErgonomicsError, match="coupling"):
        Task(coupling="sticky")


def test_hand_checked_worksheet(poser):
    """Trunk 30° (3), neck 25° (2), both knees 45° (legs 1 + 1 = 2): Table A 5, 6 kg (+1) -> A 6.
    Upper arm 50° (3), elbow 90° (1), wrist 20° (2): Table B 4, fair coupling (+1) -> B 5.
    Table C (6, 5) = 8, one activity point -> 9, high risk."""
    poser.knees(45.0)
    poser.hinge(30.0)
    poser.neck(flexion=25.0)
    poser.arm("right", 50.0)
    poser.elbow("right", 90.0)
    poser.wrist("right", flexion=20.0)
    r = reba(poser.f, side="right", load_kg=6.0, coupling="fair", static=True)
    ws = r.worksheet
    assert (ws["trunk"], ws["neck"], ws["legs"], ws["table_a"], ws["score_a"]) == (3, 2, 2, 5, 6)
    assert (ws["upper_arm"], ws["lower_arm"], ws["wrist"], ws["table_b"], ws["score_b"]) == (3, 1, 2, 4, 5)
    assert ws["table_c"] == 8 and r.score == 9 and r.level == 3


def test_worst_contributor(poser):
    poser.hinge(65.0)
    assert reba(poser.f).worst == "trunk"
    poser.neutral()
    poser.knees(70.0)
    assert reba(poser.f).worst == "legs"
