"""Shoulder complex: the book's worked allocation values and the joint-form properties."""

import numpy as np
import pytest

from jackpy.body.shoulder import SHOULDER_ANGLES, ShoulderDriver, allocate
from jackpy.peabody.transforms import rotation

WORKED = [  # phi, theta -> phi_c, theta_c, phi_s, theta_s (body-model.md 3.2)
    (0, 0, 1.0760, 0, -1.0760, 0), (45, 30, 12.3138, 6, 32.6862, 24), (90, 0, 23.7020, 0, 66.2980, 0),
    (90, 90, 21.3074, 18, 68.6926, 72), (130, 90, 29.7338, 18, 100.2662, 72), (131.4, 0, 34.1100, 0, 97.2900, 0),
    (150, 45, 32.4395, 9, 117.5605, 36), (180, 0, 32.4000, 0, 147.6000, 0), (180, 90, 30.0, 18, 150.0, 72),
]


@pytest.mark.parametrize("row", WORKED)
def test_worked_allocation_values(row):
    phi, theta, *expected = row
    assert allocate(phi, theta) == pytest.approx(expected, abs=1e-4)


def test_clavicle_gets_a_fifth_of_abduction_and_no_twist():
    d = ShoulderDriver()
    a = d(np.radians([60.0, 50.0, 0.0]))
    b = d(np.radians([60.0, 50.0, 40.0]))
    assert np.degrees(a[1]) == pytest.approx(10.0)
    assert np.allclose(a[:3], b[:3])


def _shoulder_matrix(phi, theta_s, phi_c, tau=0.0):
    # book frame: R(z)*R(x)*R(z)*R(x) with (tau + (phi/90 - 1) theta_s, phi, theta_s, -phi_c), column form
    first = tau + (phi / 90.0 - 1.0) * theta_s
    return (rotation("x", np.radians(-phi_c)) @ rotation("z", np.radians(theta_s)) @ rotation("x", np.radians(phi))
            @ rotation("z", np.radians(first)))


@pytest.mark.parametrize("phi,dep", [(0.0, False), (180.0, False), (90.0, True)])
def test_shoulder_joint_independent_of_theta_s_at_poles(phi, dep):
    a, b = _shoulder_matrix(phi, 10.0, 20.0), _shoulder_matrix(phi, 70.0, 20.0)
    assert np.allclose(a, b) != dep


def test_identity_rx180_rz():
    t = np.radians(37.0)
    assert np.allclose(rotation("x", np.pi) @ rotation("z", t), rotation("z", -t) @ rotation("x", np.pi))


def test_elevate_abduct_lower_leaves_no_twist():
    # (90 up, 90 abduct, -90 down) with the 3-rotation form (2.11)/(2.13) and tau0 = (phi/90) theta
    def joint(phi, theta, tau=0.0):
        tau0 = phi / 90.0 * theta
        return rotation("z", np.radians(theta)) @ rotation("x", np.radians(phi)) @ rotation("z", np.radians(tau0 + tau - theta))
    assert np.allclose(joint(0.0, 90.0), joint(0.0, 0.0))  # back to hanging, untwisted


def _arm(fig, side):
    return fig.site_world(f"{side}_forearm", "base")[:3, 3] - fig.site_world(f"{side}_upper_arm", "base")[:3, 3]


@pytest.mark.parametrize("phi,theta", [(0.0, 0.0), (45.0, 30.0), (90.0, 0.0), (90.0, 90.0), (115.0, -30.0)])
def test_arm_direction_is_elevation_and_abduction(male50, phi, theta):
    fig = male50
    saved = fig.q.copy(), {n: g.angles.copy() for n, g in fig.groups.items()}
    try:
        for side, sx in (("left", 1.0), ("right", -1.0)):
            fig.groups[f"{side}_shoulder_complex"].set_angles(fig, np.radians([phi, theta, 0.0]))
            arm = _arm(fig, side)
            arm /= np.linalg.norm(arm)
            # book frame: z down, x forward, -y lateral
            assert np.degrees(np.arccos(-arm[1])) == pytest.approx(phi, abs=1e-6)
            if phi > 1:
                lateral, forward = sx * arm[0], arm[2]
                assert np.degrees(np.arctan2(forward, lateral)) == pytest.approx(theta, abs=1e-6)
    finally:
        fig.q = saved[0]
        for n, g in fig.groups.items():
            g.angles = saved[1][n]


def test_humeral_head_moves_on_sphere_about_clavicle_joint(male50):
    fig = male50
    saved = fig.q.copy(), fig.groups["left_shoulder_complex"].angles.copy()
    try:
        centre = fig.site_world("t1", "left_clavicle")[:3, 3]
        radii = []
        for phi, theta in [(0, 0), (90, 0), (170, 45), (60, 120)]:
            fig.groups["left_shoulder_complex"].set_angles(fig, np.radians([phi, theta, 0.0]))
            radii.append(np.linalg.norm(fig.site_world("left_upper_arm", "base")[:3, 3] - centre))
        assert np.ptp(radii) < 1e-9
        assert radii[0] == pytest.approx(0.06, abs=0.01)
    finally:
        fig.q, fig.groups["left_shoulder_complex"].angles = saved


def test_globographic_limits():
    from jackpy.body.shoulder import shoulder_group

    g = shoulder_group("left")
    assert g.angle_names == list(SHOULDER_ANGLES)
    assert g.is_feasible(np.radians([170.0, 60.0, 0.0]))
    assert not g.is_feasible(np.radians([120.0, -80.0, 0.0]))  # far behind the back, high
    assert not g.is_feasible(np.radians([175.0, 130.0, 0.0]))  # across the body, high
    assert g.is_feasible(np.radians([50.0, -80.0, 0.0]))
