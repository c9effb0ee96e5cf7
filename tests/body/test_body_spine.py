"""Spine group (Monheit weighting): sums, limits, initiator, resistor, range, Jacobian."""

import numpy as np
import pytest

from jackpy.body.spine import (
    SPINE_ANGLES,
    SPINE_DOFS,
    SpineDriver,
    SpineWeights,
    distribute,
    spine_group,
)


def _members(driver, theta):
    return driver(np.asarray(theta, dtype=float)).reshape(18, 3)


@pytest.mark.parametrize("deg", [10.0, 30.0, 60.0, -20.0, 94.0])
def test_flexion_is_sum_of_vertebral_flexions(deg):
    d = SpineDriver()
    m = _members(d, np.radians([deg, 0.0, 0.0]))
    assert np.degrees(m[:, SPINE_DOFS.index("flexion")].sum()) == pytest.approx(deg, abs=1e-9)
    assert np.all(m >= d.lower - 1e-12) and np.all(m <= d.upper + 1e-12)
    assert np.allclose(m[:, [0, 1]], 0.0)


def test_all_three_axes_independent():
    d = SpineDriver()
    theta = np.radians([25.0, -15.0, 30.0])
    m = _members(d, theta)
    for a, t in zip(SPINE_ANGLES, theta):
        assert m[:, SPINE_DOFS.index(a)].sum() == pytest.approx(t, abs=1e-12)


def test_initiator_moves_most_relative_to_its_range():
    d = SpineDriver(SpineWeights(initiator=8))
    k = SPINE_DOFS.index("flexion")
    m = _members(d, np.radians([20.0, 0, 0]))[:, k]
    frac = m / d.upper[:, k]
    assert np.argmax(frac) == 8


def test_full_bend_reaches_every_limit():
    d = SpineDriver()
    _lo, hi = d.group_limits()
    m = _members(d, hi)
    assert np.allclose(m, d.upper)


def test_resistance_reduces_motion_beyond_resistor_but_never_freezes():
    k = SPINE_DOFS.index("flexion")
    free = _members(SpineDriver(SpineWeights(initiator=0)), np.radians([30.0, 0, 0]))[:, k]
    held = _members(SpineDriver(SpineWeights(initiator=0, resistor=6, resistance=1.0)), np.radians([30.0, 0, 0]))[:, k]
    assert held[6:].sum() < free[6:].sum()
    assert np.all(held[6:] > 0)
    assert held.sum() == pytest.approx(free.sum())


def test_joints_outside_range_do_not_move():
    d = SpineDriver(SpineWeights(bottom=5, top=12, initiator=9))
    m = _members(d, np.radians([15.0, 5.0, 5.0]))
    assert np.allclose(m[:5], 0.0) and np.allclose(m[13:], 0.0)
    _lo, hi = d.group_limits()
    assert hi[0] == pytest.approx(d.upper[5:13, SPINE_DOFS.index("flexion")].sum())


def test_unbending_returns_toward_rest_exactly():
    n = 6
    w = SpineWeights(top=5, initiator=0)
    lo, hi, rest = -np.ones(n) * 0.1, np.ones(n) * 0.2, np.zeros(n)
    bent = distribute(rest, rest, lo, hi, 0.9, w)
    back = distribute(bent, rest, lo, hi, 0.3, w)
    assert back.sum() == pytest.approx(0.3)
    assert np.all(np.abs(back) <= np.abs(bent) + 1e-12)
    assert np.allclose(distribute(bent, rest, lo, hi, 0.0, w), 0.0)


def test_zero_interpolation_no_uses_limits_only():
    d = SpineDriver(zero_interpolation=False)
    k = SPINE_DOFS.index("flexion")
    m = _members(d, np.radians([10.0, 0.0, 0.0]))[:, k]
    assert m.sum() == pytest.approx(np.radians(10.0))
    u = (m - d.lower[:, k]) / (d.upper[:, k] - d.lower[:, k])
    assert np.allclose(u, u[0])


def test_group_in_figure_and_jacobian(male50):
    fig = male50
    g = fig.groups["spine"]
    saved = fig.q.copy(), g.angles.copy()
    try:
        g.set_angles(fig, np.radians([30.0, 10.0, -10.0]))
        flex = sum(fig.joint(j).displacement[SPINE_DOFS.index("flexion")] for j in g.joints)
        assert flex == pytest.approx(np.radians(30.0))
        # no elongation: the neck base stays at the spine length from the pelvis joint
        p0 = fig.site_world("pelvis", "l5_s1")[:3, 3]
        p1 = fig.site_world("neck", "base")[:3, 3]
        assert np.linalg.norm(p1 - p0) < fig.body_spec.dims["spine.length"] + 1e-9
        assert fig.site_world("head", "top")[2, 3] > 0.1  # bent forward
    finally:
        fig.q, g.angles = saved
    th = np.radians([20.0, 5.0, 8.0])
    jac = g.driver.jacobian(th)
    h = 1e-5
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        assert np.allclose(jac[:, k], (g.driver(th + e) - g.driver(th - e)) / (2 * h), atol=1e-5)
    assert spine_group().nangles == 3
