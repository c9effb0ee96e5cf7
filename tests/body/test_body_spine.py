"""Spine group (Monheit weighting): sums, limits, initiator, resistor, range, Jacobian."""

import numpy as np
import pytest

from jackpy.body.spine import (
    SPINE_ANGLES,
    SPINE_DOFS,
    SpineDriver,
    SpineWeights,
    distribute,
    distribute_with_derivative,
    spine_group,
)


def _members(driver, theta):
    return driver(np.asarray(theta, dtype=float)).reshape(18, 3)


@pytest.mark.parametrize("deg", [10.0, 30.0, 60.0, -20.0, 85.0])  # AAOS 80 + C7/T1 5.4 = 85.4 max
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


FLAVOURS = [
    SpineWeights(),
    SpineWeights(initiator=17),
    SpineWeights(initiator=8, resistor=12, resistance=0.7),
    SpineWeights(bottom=3, top=14, initiator=14, resistor=5, resistance=1.0),
    SpineWeights(bottom=2, top=9, initiator=5, spread=1.5),
]


def _near_kink(driver, theta, h):
    """True when a central difference at ``theta`` straddles a piece boundary (a joint reaching its
    goal, the target reaching the range, the turn at rest): compare one-sided differences."""
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        f0, fp, fm = driver(theta), driver(theta + e), driver(theta - e)
        if not np.allclose((fp - f0) / h, (f0 - fm) / h, atol=1e-4):
            return True
    return False


@pytest.mark.parametrize("zero_interpolation", [True, False])
@pytest.mark.parametrize("flavour", range(len(FLAVOURS)))
def test_analytic_jacobian_matches_finite_differences(flavour, zero_interpolation):
    d = SpineDriver(FLAVOURS[flavour], zero_interpolation)
    lo, hi = d.group_limits()
    rng = np.random.default_rng(flavour)
    checked = 0
    for _ in range(60):
        th = lo + (hi - lo) * rng.uniform(0.01, 0.99, 3)
        if _near_kink(d, th, 1e-6):
            continue
        d._cache = None
        jac = d.jacobian(th)
        assert jac.shape == (54, 3)
        assert np.allclose(jac, d.numerical_jacobian(th, 1e-7), atol=1e-6)
        # each torso angle moves only its own DOF, and the vertebral sum moves one for one
        cols = jac.reshape(18, 3, 3)
        for c, a in enumerate(SPINE_ANGLES):
            k = SPINE_DOFS.index(a)
            assert cols[:, k, c].sum() == pytest.approx(1.0)
            assert np.allclose(np.delete(cols[:, :, c], k, axis=1), 0.0)
        checked += 1
    assert checked >= 40


def test_jacobian_at_rest_is_mean_of_both_sides_and_zero_beyond_range():
    d = SpineDriver(SpineWeights(initiator=4, resistor=10, resistance=0.5))
    assert np.allclose(d.jacobian(np.zeros(3)), d.numerical_jacobian(np.zeros(3), 1e-8), atol=1e-6)
    lo, hi = d.group_limits()
    assert np.allclose(d.jacobian(hi + 0.1), 0.0)
    assert np.allclose(d.jacobian(lo - 0.1), 0.0)
    # the cached evaluation follows a change of parameters
    before = d.jacobian(np.radians([20.0, 0.0, 0.0]))
    d.weights = SpineWeights(initiator=15)
    assert not np.allclose(d.jacobian(np.radians([20.0, 0.0, 0.0])), before)


def test_distribute_derivative_when_unbending():
    n = 8
    w = SpineWeights(top=7, initiator=2, resistor=5, resistance=0.6)
    lo, hi, rest = -np.full(n, 0.1), np.full(n, 0.2), np.zeros(n)
    bent = distribute(rest, rest, lo, hi, 1.1, w)
    h = 1e-7
    for target in (0.2, 0.7, 1.4, -0.3):  # unbend, unbend, bend further, bend past rest the other way
        out, der = distribute_with_derivative(bent, rest, lo, hi, target, w)
        assert np.allclose(out, distribute(bent, rest, lo, hi, target, w))
        fd = (distribute(bent, rest, lo, hi, target + h, w) - distribute(bent, rest, lo, hi, target - h, w)) / (2 * h)
        assert np.allclose(der, fd, atol=1e-6)
        assert der.sum() == pytest.approx(1.0)
