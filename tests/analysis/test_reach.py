"""Point reach through the IK: reached within 5 mm inside the reach, "short by ~10 cm" beyond it."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.analysis.reach import point_reach
from jackpy.peabody.synthetic import human_like_tree

ARM = 0.30 + 0.26 + 0.09  # shoulder centre to palm tip of the synthetic human


def _shoulder(f):
    return f.site_world("clavicle_right", "tip")[:3, 3]


DIRECTIONS = [np.array(d) / np.linalg.norm(d) for d in ([0, 0, 1], [0, -0.5, 0.8], [-0.6, 0.2, 0.8])]


@pytest.mark.parametrize("direction", DIRECTIONS)
def test_target_inside_the_reach_is_reached_within_5mm(direction):
    f = human_like_tree()
    q0 = f.q
    r = point_reach(f, _shoulder(f) + direction * (ARM - 0.1), start_joint="shoulder_right")
    assert r.reached and r.shortfall <= 0.005
    assert np.linalg.norm(r.position - r.target) <= 0.005
    assert r.describe().startswith("reached")
    np.testing.assert_array_equal(f.q, q0)  # posture restored


@pytest.mark.parametrize("direction", DIRECTIONS)
def test_target_10cm_beyond_the_reach_is_short_by_10cm(direction):
    f = human_like_tree()
    r = point_reach(f, _shoulder(f) + direction * (ARM + 0.1), start_joint="shoulder_right", keep_posture=True)
    assert not r.reached and r.shortfall == pytest.approx(0.1, abs=0.01)
    text = r.describe()
    assert text.startswith("short by ~") and abs(int(text.split("~")[1].split()[0]) - 10) <= 1
    np.testing.assert_allclose(f.site_world("palm_right", "tip")[:3, 3], r.position)  # posture kept


def test_whole_arm_from_the_clavicle_reaches_further_than_from_the_shoulder():
    f = human_like_tree()
    target = _shoulder(f) + DIRECTIONS[0] * (ARM + 0.03)
    assert not point_reach(f, target, start_joint="shoulder_right").reached
    assert point_reach(f, target, hand="right").shortfall < 0.03
