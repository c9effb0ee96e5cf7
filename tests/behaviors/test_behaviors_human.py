"""The loop on the standard human: look-at accuracy and a short drag keeping balance and feet."""

import numpy as np
import pytest

from jackpy.behaviors import BehaviorLoop
from jackpy.behaviors import manipulation as m
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.behaviors.support import floor

import jackpy.body.human as body  # noqa: E402  (a broken import fails, never skips)


@pytest.fixture(scope="module")
def human():
    f = body.make_human("male", 50)
    return f, human_anatomy(f)


def test_look_at_within_a_centimetre_per_metre(human):
    f, a = human
    lp = BehaviorLoop(f, a)
    view = f.site_world(*a.view)[:3, 3]
    fwd = f.world_transforms()[a.view[0]][:3, :3] @ a.view_forward
    side = np.cross([0.0, 1.0, 0.0], fwd)
    target = view + 1.0 * fwd + 0.3 * side - 0.2 * np.array([0.0, 1.0, 0.0])
    m.move_eyes(lp, target)
    for _ in range(10):
        lp.step()
    for seg, site in a.eyes.values():
        w = f.site_world(seg, site)
        ray = f.world_transforms()[seg][:3, :3] @ a.eye_forward
        d = target - w[:3, 3]
        assert np.linalg.norm(d - (d @ ray) * ray) < 0.01


def test_hand_drag_keeps_balance_and_feet(human):
    f, a = human
    lp = BehaviorLoop(f, a)
    feet0 = {s: f.site_world(*ft.ball)[:3, 3].copy() for s, ft in a.feet.items()}
    palm = f.site_world(*a.hands["right"].palm)[:3, 3].copy()
    for i in range(10):
        m.move_hand(lp, "right", position=palm + np.array([0.0, 0.02 * i, 0.02 * i]))
        lp.step()
        bf = lp.balance_frame_for({s: ft.target for s, ft in lp.state.feet.items()})
        assert bf.margin(floor(f.centre_of_mass())) < 0.0
        q = f.q
        assert np.all(q >= f.lower - 1e-9) and np.all(q <= f.upper + 1e-9)
    for s, p in feet0.items():
        assert np.linalg.norm(f.site_world(*a.feet[s].ball)[:3, 3] - p) < 1e-3


#: per grip: cylinder (diameter, length) and whether its axis runs across the palm (else along the
#: palm normal: a disc held by its rim)
GRIP_OBJECTS = {"power": (0.04, 0.15, True), "precision": (0.015, 0.10, True), "disc": (0.08, 0.02, False),
                "small disc": (0.03, 0.015, False), "tripod": (0.02, 0.10, True)}


@pytest.mark.parametrize("grip,sex,percentile", [("power", "male", 50), ("precision", "male", 50),
                                                  ("disc", "male", 50), ("small disc", "male", 50),
                                                  ("small disc", "female", 5), ("tripod", "male", 50)])
def test_grasp_closes_digits_and_thumb_onto_a_cylinder(human, grip, sex, percentile):
    from jackpy.behaviors.grasp import GraspObject

    f = body.make_human(sex, percentile)
    a = human_anatomy(f)
    lp = BehaviorLoop(f, a)
    palm = f.site_world(*a.hands["right"].palm)
    pose = np.eye(4)
    # in front of the chest, where the arm reaches the palm goal's orientation too (the grip assumes it)
    pose[:3, 3] = palm[:3, 3] + np.array([0.12, 0.25, 0.4])
    diameter, length, across = GRIP_OBJECTS[grip]
    site = np.eye(4)
    site[:3, :3] = (np.array([[0, 0, 1], [0, 1, 0], [-1, 0, 0]]).T if across  # fingers forward round a vertical bar
                    else np.array([[0, 0, 1], [1, 0, 0], [0, 1, 0]]).T)  # palm down on a disc, fingers forward
    obj = GraspObject("thing", "cylinder", (diameter, length, 0.0), pose, site)
    r = m.grasp(lp, "right", obj, grip, frames=20, attach=False)
    contacts = r.contact_clearance  # every digit of the grip, the thumb included
    assert "thumb" in contacts and len(contacts) == len(r.contacts)
    assert all(-0.003 < v < 0.003 for v in contacts.values()), contacts
    assert min(r.clearance.values()) > -0.003, r.clearance  # tucked digits stay out too
