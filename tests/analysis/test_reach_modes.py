"""Whole-body point reach (issue 8): "arm" (arm chain only), "body" (behaviors, feet planted, lean)
and "step" (the figure may step), on the 50th-percentile male, targets in front of the chest.
Frame counts are bounded; nothing depends on wall time (about 15 s in all)."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.analysis.reach import point_reach

import jackpy.body.human as body  # noqa: E402  (a broken import fails, never skips)


@pytest.fixture(scope="module")
def human():
    return body.make_human("male", 50)


def _target(f, beyond: float) -> np.ndarray:
    """In front of the chest (10 cm below the shoulder), ``beyond`` metres past the straight arm."""
    sh = f.site_world("right_clavicle", "shoulder")[:3, 3]
    arm = float(np.linalg.norm(f.site_world("right_palm", "grip")[:3, 3] - sh))
    dy = -0.1
    return sh + np.array([0.0, dy, np.sqrt((arm + beyond) ** 2 - dy ** 2)])


def _check_final(f, r):
    import copy

    c = copy.deepcopy(f)
    r.posture.apply(c)
    np.testing.assert_allclose(c.site_world("right_palm", "grip")[:3, 3], r.position, atol=1e-9)
    q = c.q
    assert np.all(q >= c.lower - 1e-9) and np.all(q <= c.upper + 1e-9), "joints in limits"
    assert r.balanced and r.com_margin < 0.0, "COM inside the support polygon"
    return c


@pytest.fixture(scope="module")
def near(human):
    t = _target(human, 0.30)
    state = (human.q.copy(), tuple(human.root), human.location.copy())
    out = {m: point_reach(human, t, mode=m) for m in ("arm", "body")}
    assert np.array_equal(human.q, state[0]) and tuple(human.root) == state[1]
    np.testing.assert_array_equal(human.location, state[2])  # the caller's figure is left alone
    return out


@pytest.fixture(scope="module")
def far(human):
    t = _target(human, 0.60)
    return {m: point_reach(human, t, mode=m) for m in ("body", "step")}


def test_30cm_beyond_the_arm_is_short_with_the_arm_and_reached_with_the_body(human, near):
    arm, whole = near["arm"], near["body"]
    assert not arm.reached and 0.2 < arm.shortfall < 0.32 and arm.describe().startswith("short by ~")
    assert arm.com_margin is None and arm.mode == "arm"
    assert whole.shortfall < arm.shortfall - 0.2
    assert whole.reached and whole.describe().startswith("reached (")
    assert not whole.stepped and whole.steps == 0 and whole.frames <= 150
    _check_final(human, whole)


def test_60cm_beyond_the_body_stays_short_and_balanced_the_step_reaches(human, far):
    planted, step = far["body"], far["step"]
    assert not planted.reached and 0.1 < planted.shortfall < 0.5 and not planted.stepped
    _check_final(human, planted)  # the best balanced posture, not one falling towards the target
    assert step.stepped and step.steps >= 1 and step.frames <= 150
    assert step.reached or step.shortfall < planted.shortfall - 0.1
    assert step.shortfall < planted.shortfall
    assert step.describe().endswith("step" if step.steps == 1 else "steps")
    c = _check_final(human, step)
    # the feet are on the floor after the steps, and the figure moved towards the target
    for side in ("left", "right"):
        assert abs(c.site_world(f"{side}_foot", "ball")[1, 3]) < 2e-3
    assert c.centre_of_mass()[2] > human.centre_of_mass()[2] + 0.1


def test_keep_posture_puts_the_figure_in_the_final_posture(human):
    import copy

    f = copy.deepcopy(human)
    t = _target(f, 0.30)
    r = point_reach(f, t, mode="body", keep_posture=True)
    np.testing.assert_allclose(f.site_world("right_palm", "grip")[:3, 3], r.position, atol=1e-9)


def test_unknown_mode_is_rejected(human):
    with pytest.raises(ValueError, match="reach mode"):
        point_reach(human, np.zeros(3), mode="walk")
