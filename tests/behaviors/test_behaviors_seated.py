"""The behavior loop's seated mode (jackpy.behaviors.seat, manipulation.sit): a seated standard human
keeps its ischia on the seat and its feet on the floor or footrest while a hand is dragged."""

import numpy as np
import pytest

from jackpy.behaviors import BehaviorLoop
from jackpy.behaviors import manipulation as m
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.body.human import make_human
from jackpy.body.seated import seat_contact_points

#: reach targets as fractions of the arm length from the shoulder (x left, y up, z forward): ahead,
#: out to the right side, down towards the floor in front (needs the lean), up and across
TARGETS = [(0.0, -0.2, 0.9), (-0.9, -0.2, 0.2), (-0.2, -1.0, 0.6), (0.1, 0.5, 0.7)]


def _feet(f, a):
    return {s: (f.site_world(*ft.ball)[:3, 3].copy(), f.site_world(*ft.heel)[:3, 3].copy())
            for s, ft in a.feet.items()}


@pytest.mark.parametrize("sex,percentile,seat,footrest", [("male", 50, 0.42, 0.0), ("female", 5, 0.55, 0.20)])
def test_seated_figure_keeps_seat_and_feet_while_a_hand_is_dragged(sex, percentile, seat, footrest):
    f = make_human(sex, percentile)
    a = human_anatomy(f)
    lp = BehaviorLoop(f, a)
    assert m.sit(lp, seat, footrest)  # both feet reach the floor / footrest at these heights
    contacts = seat_contact_points(f)
    assert contacts[:, 1] == pytest.approx([seat, seat], abs=1e-9)
    feet = _feet(f, a)
    for ball, heel in feet.values():
        assert heel[1] == pytest.approx(footrest, abs=0.002)
    spine0 = f.groups["spine"].angles.copy()
    shoulder = f.site_world(*a.hands["right"].shoulder)[:3, 3]
    length = lp.arm_length("right")
    for k, frac in enumerate(TARGETS):
        target = shoulder + length * np.array(frac)
        for _ in range(20):
            m.move_hand(lp, "right", position=target, lean=True)
            r = lp.step()
            assert r.root == "pelvis"
            assert np.abs(seat_contact_points(f) - contacts).max() < 1e-3
            for s, (ball, heel) in feet.items():
                assert np.linalg.norm(f.site_world(*a.feet[s].ball)[:3, 3] - ball) < 1e-3
                assert abs(f.site_world(*a.feet[s].heel)[1, 3] - heel[1]) < 1e-3
        assert np.linalg.norm(f.site_world(*a.hands["right"].palm)[:3, 3] - target) < 0.01
        if k == 2:  # down to the floor in front: the trunk leans forward to get there
            assert f.groups["spine"].angles[0] > spine0[0] + np.radians(10.0)
    assert lp.state.steps_taken == 0


def test_a_seat_too_high_leaves_the_feet_hanging_still():
    f = make_human("female", 5)
    a = human_anatomy(f)
    lp = BehaviorLoop(f, a)
    assert not m.sit(lp, 0.75)
    feet = _feet(f, a)
    assert all(heel[1] > 0.05 for _, heel in feet.values())
    shoulder = f.site_world(*a.hands["left"].shoulder)[:3, 3]
    for _ in range(15):
        m.move_hand(lp, "left", position=shoulder + lp.arm_length("left") * np.array([0.3, -0.3, 0.8]), lean=True)
        lp.step()
    for s, (ball, heel) in feet.items():
        assert np.linalg.norm(f.site_world(*a.feet[s].ball)[:3, 3] - ball) < 1e-3
        assert np.linalg.norm(f.site_world(*a.feet[s].heel)[:3, 3] - heel) < 2e-3


def test_figure_moved_off_the_seat_settles_back_and_stand_up_frees_the_root():
    f = make_human("male", 50)
    a = human_anatomy(f)
    lp = BehaviorLoop(f, a)
    m.sit(lp, 0.42)
    contacts = seat_contact_points(f)
    loc = f.location.copy()
    loc[1, 3] += 0.01  # lifted 1 cm off the seat
    f.location = loc
    for _ in range(6):  # at most 3 mm a frame
        lp.step()
    assert np.abs(seat_contact_points(f) - contacts).max() < 1e-6
    m.stand_up(lp)
    assert lp.state.seat is None and not lp.state.root_claimed
