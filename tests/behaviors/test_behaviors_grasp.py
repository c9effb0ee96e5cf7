"""Grasp on the standard human: each of the five grips closes every contacting digit, thumb
included, onto a cylinder and a box of its size (within 3 mm, no digit penetrating more than 3 mm)."""

import numpy as np
import pytest

from jackpy.behaviors.anatomy import human_anatomy, synthetic_anatomy
from jackpy.behaviors.grasp import (
    GRIP_TYPES,
    GraspObject,
    GraspParams,
    close_fingers,
    palm_goal,
    preshape,
    thumb_plan,
)
from jackpy.peabody.transforms import rigid_inverse

import jackpy.body.human as body  # noqa: E402  (a broken import fails, never skips)

#: long axis across the palm (the fingers wrap round it); a disc's axis along the palm normal
ACROSS = np.array([[0, 0, 1], [0, 1, 0], [-1, 0, 0]], float).T
FACE = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], float).T


def _site(r):
    s = np.eye(4)
    s[:3, :3] = r
    return s


OBJECTS = {
    "power": [("cylinder", (0.04, 0.15, 0.0), ACROSS), ("box", (0.035, 0.15, 0.035), ACROSS)],
    "precision": [("cylinder", (0.015, 0.10, 0.0), ACROSS), ("box", (0.015, 0.10, 0.015), ACROSS)],
    "disc": [("cylinder", (0.08, 0.02, 0.0), FACE), ("box", (0.08, 0.02, 0.08), FACE)],
    "small disc": [("cylinder", (0.03, 0.015, 0.0), FACE), ("box", (0.03, 0.015, 0.03), FACE)],
    "tripod": [("cylinder", (0.02, 0.10, 0.0), ACROSS), ("box", (0.02, 0.10, 0.02), ACROSS)],
}
CASES = [(g, k) for g in OBJECTS for k in range(2)]


@pytest.fixture(scope="module")
def hand():
    f = body.make_human("male", 50)
    return f, human_anatomy(f).hands["right"], f.q.copy()


def _grasp_at_palm(f, h, grip, shape, size, rot):
    """Preshape, put the object where the grip wants it relative to the palm as it stands, close."""
    obj = GraspObject("thing", shape, size, np.eye(4), _site(rot))
    preshape(f, h, grip)
    goal = palm_goal(h, f.site_location(*h.palm), obj, grip)  # palm pose relative to the object
    obj.pose = f.site_world(*h.palm) @ rigid_inverse(goal)
    return obj, close_fingers(f, h, obj, GraspParams(grip=grip))


@pytest.mark.parametrize("grip,k", CASES)
def test_every_contacting_digit_touches_within_3mm(hand, grip, k):
    f, h, q0 = hand
    f.q = q0
    shape, size, rot = OBJECTS[grip][k]
    _obj, r = _grasp_at_palm(f, h, grip, shape, size, rot)
    names = [h.digits[d].name for d in GRIP_TYPES[grip].digits]
    assert set(r.contacts) == set(names) and "thumb" in names
    mm = {n: 1000 * c for n, c in r.clearance.items()}
    assert all(-3.0 < mm[n] < 3.0 for n in names), (grip, shape, mm)
    assert min(mm.values()) > -3.0, (grip, shape, mm)  # tucked digits stay out of the object too
    q = f.q
    assert np.all(q >= f.lower - 1e-9) and np.all(q <= f.upper + 1e-9)


def test_thumb_preshape_is_opened_clear_of_the_object(hand):
    """A preshape that starts inside the object (thumb abducted into a bar held close to the palm)
    opens first: the thumb ends in contact, not 1 cm inside."""
    f, h, q0 = hand
    f.q = q0
    obj, r = _grasp_at_palm(f, h, "power", "cylinder", (0.04, 0.15, 0.0), ACROSS)
    cmc = f.joint(h.digits[0].flex[0][0])
    cmc.displacement[0] = cmc.dofs[0].upper  # thumb swung fully out of the palm into the bar
    r = close_fingers(f, h, obj, GraspParams(grip="power"))
    assert -0.003 < r.clearance["thumb"] < 0.003


def test_thumb_modes():
    assert {g: GRIP_TYPES[g].thumb_mode for g in GRIP_TYPES} == {
        "power": "opposition", "precision": "opposition", "tripod": "opposition",
        "disc": "lateral", "small disc": "lateral"}


def test_simple_hand_thumb_closes_by_its_flexion():
    from jackpy.peabody.synthetic import human_like_tree

    f = human_like_tree()
    h = synthetic_anatomy(f).hands["right"]
    assert thumb_plan(f, h, "power") == list(h.digits[0].flex)


def test_cylinder_half_depth_follows_the_grip_axis():
    across = GraspObject("c", "cylinder", (0.04, 0.2, 0.0), np.eye(4), _site(ACROSS))
    face = GraspObject("c", "cylinder", (0.08, 0.02, 0.0), np.eye(4), _site(FACE))
    assert across.half_depth == pytest.approx(0.02)
    assert face.half_depth == pytest.approx(0.01)
