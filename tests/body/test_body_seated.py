"""Seated support: ischia on the seat, soles flat on the floor or footrest where the legs reach."""

import numpy as np
import pytest

from jackpy.body.human import make_human
from jackpy.body.measure import site_point, surface_points
from jackpy.body.seated import seat_contact_points, sit


@pytest.mark.parametrize("seat, rest", [(0.40, 0.0), (0.43, 0.0), (0.55, 0.12)])
def test_sits_on_the_ischia_with_feet_flat(seat, rest):
    fig = make_human("male", 50)
    assert sit(fig, seat, rest)
    assert np.allclose(seat_contact_points(fig)[:, 1], seat)
    for side in ("left", "right"):
        heel, ball = (site_point(fig, f"{side}_foot", n)[1] for n in ("heel", "ball"))
        assert abs(heel - rest) < 0.002 and abs(ball - rest) < 0.002
    # nothing of the buttocks or thighs sinks more than 5 mm into the seat
    assert surface_points(fig, ["pelvis", "left_thigh", "right_thigh"])[:, 1].min() > seat - 0.005
    hip = site_point(fig, "pelvis", "centre")[1]
    assert hip - seat == pytest.approx(fig.body_spec.dims["seat.hip_height"], abs=1e-9)


def test_too_high_a_seat_leaves_the_feet_hanging():
    fig = make_human("female", 5)
    assert not sit(fig, 0.70)
    assert site_point(fig, "left_foot", "heel")[1] > 0.1
