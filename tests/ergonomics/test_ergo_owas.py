"""OWAS (Karhu et al. 1977) codes measured from the posture, and the action-category table."""

import pytest

from jackpy.ergonomics import Task, assess
from jackpy.ergonomics import constants as C
from jackpy.ergonomics.owas import load_code


def owas(f, **task):
    return assess(f, ["owas"], Task(**task))["owas"]


def test_neutral_standing_is_1121_category_1(poser):
    r = owas(poser.f)
    assert r.worksheet["code"] == "1121"
    assert r.score == 1


def test_bent_back_both_arms_up_one_bent_leg(poser):
    poser.hinge(30.0)
    for side in ("left", "right"):
        poser.arm(side, 170.0)
    r = owas(poser.f, load_kg=25.0)
    assert (r.worksheet["back"], r.worksheet["arms"], r.worksheet["load"]) == (2, 3, 3)
    assert r.score == int(C.OWAS_TABLE[1, 2, r.worksheet["legs"] - 1, 2])


@pytest.mark.parametrize("elevation,arms", [(80.0, 1), (100.0, 2)])
def test_one_arm_at_shoulder_level(poser, elevation, arms):
    poser.arm("right", elevation)
    assert owas(poser.f).worksheet["arms"] == arms


@pytest.mark.parametrize("deg,back", [(19.0, 1), (21.0, 2)])
def test_back_bent_threshold(poser, deg, back):
    poser.hinge(deg)
    assert owas(poser.f).worksheet["back"] == back


def test_twisted_and_bent_back(poser):
    poser.spine(axial=30.0)
    assert owas(poser.f).worksheet["back"] == 3
    poser.hinge(40.0)
    assert owas(poser.f).worksheet["back"] == 4


def test_legs(poser):
    assert owas(poser.f, seated=True).worksheet["legs"] == 1
    assert owas(poser.f, walking=True).worksheet["legs"] == 7
    poser.knees(50.0)
    assert owas(poser.f).worksheet["legs"] == 4
    poser.neutral()
    poser.lift_foot("left")
    assert owas(poser.f).worksheet["legs"] == 3  # standing on the straight right leg


def test_load_codes_and_table_entries():
    assert [load_code(k) for k in (10.0, 10.5, 20.0, 20.5)] == [1, 2, 2, 3]
    assert C.OWAS_TABLE.shape == (4, 3, 7, 3)
    # published entries: straight back everything 1 except bent knees; bent and twisted back
    # with squatting legs 4 whatever the arms and load
    assert C.OWAS_TABLE[0, 0, 1, 0] == 1 and C.OWAS_TABLE[0, 0, 3, 0] == 2
    assert (C.OWAS_TABLE[3, :, 3:6, :] == 4).all()
