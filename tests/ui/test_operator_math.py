"""Geometry of the Jack direct-manipulation operator (spec manipulation-and-ik.md §2)."""

import numpy as np
import pytest

from jackpy.ui.operator_math import (
    PrimitiveKind,
    axis_parameter,
    clamp_joint_angle,
    closest_point_on_axis,
    goal_orientation,
    in_sector,
    limit_sector,
    linear_translation,
    manipulation_axes,
    orientation_offset,
    planar_translation,
    plane_normal,
    ray_plane_hit,
    rotate_manipulation,
    rotation_matrix,
    select_primitive,
    signed_angle,
    spoke_angle,
    unwrap_angle,
    wheel_arc,
    wheel_hit,
)

RNG = np.random.default_rng(1234)


def unit(v):
    v = np.asarray(v, float)
    return v / np.linalg.norm(v)


def random_rotation():
    q, _ = np.linalg.qr(RNG.normal(size=(3, 3)))
    return q * np.sign(np.linalg.det(q))


# ------------------------------------------------------------------ Table 3.1
@pytest.mark.parametrize("buttons, shift, control, kind, axes", [
    ({"left"}, False, False, PrimitiveKind.LINEAR, (0,)),
    ({"middle"}, False, False, PrimitiveKind.LINEAR, (1,)),
    ({"right"}, False, False, PrimitiveKind.LINEAR, (2,)),
    ({"left", "middle"}, False, False, PrimitiveKind.PLANAR, (0, 1)),
    ({"left", "right"}, False, False, PrimitiveKind.PLANAR, (0, 2)),
    ({"middle", "right"}, False, False, PrimitiveKind.PLANAR, (1, 2)),
    ({"left", "middle", "right"}, False, False, PrimitiveKind.NONE, ()),
    ({"left"}, False, True, PrimitiveKind.ROTATE, (0,)),
    ({"middle"}, False, True, PrimitiveKind.ROTATE, (1,)),
    ({"right"}, True, True, PrimitiveKind.ROTATE, (2,)),
    ({"left", "right"}, False, True, PrimitiveKind.NONE, ()),
    ({"middle", "right"}, True, False, PrimitiveKind.PLANAR, (1, 2)),
    (set(), False, False, PrimitiveKind.NONE, ()),
])
def test_button_table(buttons, shift, control, kind, axes):
    p = select_primitive(buttons, shift=shift, control=control)
    assert p.kind is kind
    assert p.axes == axes
    if kind is not PrimitiveKind.NONE:
        assert p.local is shift


def test_local_axes_are_the_normalised_columns_of_M():
    M = np.eye(4)
    R = random_rotation()
    M[:3, :3] = 2.0 * R
    assert np.allclose(manipulation_axes(M, local=True), R)
    assert np.allclose(manipulation_axes(M, local=False), np.eye(3))


# ------------------------------------------------------------------ linear translation
def test_axis_parameter_is_the_common_perpendicular():
    for _ in range(50):
        c0, o = RNG.normal(size=3), RNG.normal(size=3) * 3
        a, d = unit(RNG.normal(size=3)), unit(RNG.normal(size=3))
        t = axis_parameter(c0, a, o, d)
        p = c0 + t * a
        s = float(np.dot(p - o, d))  # closest ray parameter to p
        q = o + s * d
        gap = p - q
        assert abs(np.dot(gap, a)) < 1e-9 and abs(np.dot(gap, d)) < 1e-9


def test_axis_parallel_to_ray_is_ignored():
    a = np.array([0.0, 0.0, 1.0])
    assert axis_parameter(np.zeros(3), a, np.array([1.0, 0, 5]), -a) is None
    assert linear_translation(np.zeros(3), a, 0.0, np.array([1.0, 0, 5]), -a) is None


def test_linear_translation_has_no_jump_at_press_and_follows_the_mouse():
    c0, a = np.array([0.0, 1.0, 0.0]), np.array([1.0, 0.0, 0.0])
    eye = np.array([0.0, 1.0, 3.0])
    grab = np.array([0.2, 1.0, 0.0])  # user grabbed the axis 20 cm off the origin
    d_press = unit(grab - eye)
    t_press = axis_parameter(c0, a, eye, d_press)
    assert np.allclose(linear_translation(c0, a, t_press, eye, d_press), c0)
    d_move = unit(np.array([0.7, 1.0, 0.0]) - eye)
    moved = linear_translation(c0, a, t_press, eye, d_move)
    assert np.allclose(moved[1:], c0[1:])           # stays on the axis
    assert moved[0] == pytest.approx(0.5)           # and moves by the cursor's x motion
    literal = linear_translation(c0, a, 0.0, eye, d_press)
    assert np.allclose(literal, closest_point_on_axis(c0, a, eye, d_press))
    assert literal[0] == pytest.approx(0.2)         # the literal mode jumps to the grab point


# ------------------------------------------------------------------ planar translation
def test_ray_plane_hit():
    n = np.array([0.0, 1.0, 0.0])
    hit = ray_plane_hit(np.array([1.0, 2.0, 0.0]), unit([0.0, -1.0, 1.0]), np.zeros(3), n)
    assert np.allclose(hit, [1.0, 0.0, 2.0])
    assert ray_plane_hit(np.array([0, 1.0, 0]), np.array([1.0, 0, 0]), np.zeros(3), n) is None  # edge-on
    assert ray_plane_hit(np.array([0, 1.0, 0]), n, np.zeros(3), n) is None  # behind the eye


def test_planar_translation_keeps_the_grabbed_spot_under_the_cursor():
    axes = manipulation_axes(np.eye(4), local=False)
    n = plane_normal(axes, (0, 2))                       # L+R: the horizontal xz plane
    assert np.allclose(np.abs(n), [0, 1, 0])
    c0 = np.array([0.5, 0.0, 0.0])
    eye = np.array([0.0, 2.0, 3.0])
    hit_press = ray_plane_hit(eye, unit(np.array([0.6, 0.0, 0.1]) - eye), c0, n)
    assert np.allclose(planar_translation(c0, n, hit_press, eye, unit(hit_press - eye)), c0)
    target = np.array([-0.4, 0.0, 0.9])
    moved = planar_translation(c0, n, hit_press, eye, unit(target - eye))
    assert np.allclose(moved, c0 + target - hit_press)
    assert moved[1] == pytest.approx(0.0)
    assert np.allclose(planar_translation(c0, n, c0, eye, unit(target - eye)), target)  # literal


# ------------------------------------------------------------------ rotation wheel
def test_signed_angle_right_hand_rule():
    x, y, z = np.eye(3)
    assert signed_angle(x, y, z) == pytest.approx(np.pi / 2)
    assert signed_angle(x, y, -z) == pytest.approx(-np.pi / 2)
    assert signed_angle(x, x + 5 * z, z) == pytest.approx(0.0)  # off-plane parts do not count


def test_spoke_angle_in_the_plane_of_rotation():
    center, axis = np.array([0.0, 1.0, 0.0]), np.array([0.0, 1.0, 0.0])
    eye = np.array([0.0, 3.0, 0.5])
    h0 = wheel_hit(center, axis, eye, unit(np.array([1.0, 1.0, 0.0]) - eye))
    h1 = wheel_hit(center, axis, eye, unit(np.array([0.0, 1.0, -1.0]) - eye))
    assert np.allclose(h0, [1, 1, 0]) and np.allclose(h1, [0, 1, -1])
    assert spoke_angle(center, axis, h0, h1) == pytest.approx(np.pi / 2)  # x to -z about +y


def test_wheel_hit_edge_on_falls_back_to_projection():
    center, axis = np.zeros(3), np.array([0.0, 1.0, 0.0])
    o, d = np.array([0.3, 0.5, 5.0]), np.array([0.0, 0.0, -1.0])  # ray parallel to the plane
    hit = wheel_hit(center, axis, o, d)
    assert np.allclose(hit, [0.3, 0.0, 0.0])


def test_unwrap_lets_the_user_keep_cranking():
    total = 0.0
    for k in range(1, 61):  # three full turns in steps of 18 degrees
        true = k * np.pi / 10
        raw = float(np.arctan2(np.sin(true), np.cos(true)))
        total = unwrap_angle(total, raw)
    assert total == pytest.approx(6 * np.pi)
    assert unwrap_angle(3.0, -3.0) == pytest.approx(2 * np.pi - 3.0)


def test_rotation_matrix_is_rodrigues():
    R = rotation_matrix(np.array([0.0, 0.0, 2.0]), np.pi / 2)
    assert np.allclose(R @ [1.0, 0, 0], [0, 1.0, 0])
    axis, angle = unit(RNG.normal(size=3)), 0.7
    R = rotation_matrix(axis, angle)
    assert np.allclose(R @ R.T, np.eye(3)) and np.allclose(R @ axis, axis)


def test_global_and_local_rotation_of_M():
    M0 = np.eye(4)
    M0[:3, :3] = rotation_matrix(np.array([0.0, 0.0, 1.0]), np.pi / 2)  # M's x axis is world y
    M0[:3, 3] = [1.0, 2.0, 3.0]
    g = rotate_manipulation(M0, 0, 0.3, local=False)
    loc = rotate_manipulation(M0, 0, 0.3, local=True)
    assert np.allclose(g[:3, 3], M0[:3, 3]) and np.allclose(loc[:3, 3], M0[:3, 3])
    assert np.allclose(g[:3, :3], rotation_matrix(np.array([1.0, 0, 0]), 0.3) @ M0[:3, :3])
    assert np.allclose(loc[:3, 0], M0[:3, 0])                 # local x stays put
    assert np.allclose(loc[:3, :3], rotation_matrix(M0[:3, 0], 0.3) @ M0[:3, :3])


# ------------------------------------------------------------------ joint limits
def test_applied_joint_angle_is_clamped():
    assert clamp_joint_angle(0.2, 0.5, -1.0, 0.6) == pytest.approx(0.6)
    assert clamp_joint_angle(0.2, -2.0, -1.0, 0.6) == pytest.approx(-1.0)
    assert clamp_joint_angle(0.2, 0.1, -1.0, 0.6) == pytest.approx(0.3)


def test_red_sector_is_exactly_the_forbidden_wheel_angles():
    theta, lower, upper = 0.3, -0.5, 1.2
    start, end = limit_sector(theta, lower, upper)
    assert (start, end) == pytest.approx((0.9, 2 * np.pi - 0.8))
    assert end - start == pytest.approx(2 * np.pi - (upper - lower))
    for phi in np.linspace(-np.pi, np.pi, 361):
        forbidden = not (lower <= theta + phi <= upper)
        if min(abs(theta + phi - lower), abs(theta + phi - upper)) > 1e-9:
            assert in_sector(phi, (start, end)) == forbidden
    assert in_sector(start + 0.01 + 4 * np.pi, (start, end))  # any winding
    assert limit_sector(0.0, -np.pi, np.pi) is None
    assert not in_sector(1.0, None)


def test_wheel_arc_lies_on_the_wheel():
    center, axis, spoke = np.array([1.0, 2.0, 3.0]), unit([0.0, 1.0, 1.0]), np.array([1.0, 0.0, 0.0])
    pts = wheel_arc(center, axis, spoke, 0.5, 0.0, np.pi / 2, segments=8)
    assert pts.shape == (9, 3)
    assert np.allclose(np.linalg.norm(pts - center, axis=1), 0.5)
    assert np.allclose((pts - center) @ axis, 0.0)
    assert np.allclose(pts[0], center + 0.5 * spoke)
    assert signed_angle(pts[0] - center, pts[-1] - center, axis) == pytest.approx(np.pi / 2)


# ------------------------------------------------------------------ orientation ratchet
def test_ratchet_reseats_goal_on_the_achieved_orientation():
    R_M, R_ee = random_rotation(), random_rotation()
    O = orientation_offset(R_M, R_ee)
    assert np.allclose(goal_orientation(R_M, O), R_ee)
    assert np.allclose(O @ O.T, np.eye(3))
    # a later rotation of M turns the goal by the same world rotation, starting from R_ee
    turn = rotation_matrix(np.array([0.0, 1.0, 0.0]), 0.4)
    assert np.allclose(goal_orientation(turn @ R_M, O), turn @ R_ee)
