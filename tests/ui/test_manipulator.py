"""The Jack operator state machine, with stand-in targets (the geometry is tested in test_operator_math)."""

import numpy as np
import pytest

from jackpy.ui.manipulator import Manipulator
from jackpy.ui.operator_math import PrimitiveKind, rotation_matrix


class Frame:
    """A target that records every transform it is given and every primitive end."""

    def __init__(self, M=None):
        self.M = np.eye(4) if M is None else np.array(M, float)
        self.applied = []
        self.ends = 0

    def transform(self):
        return self.M

    def apply(self, M):
        self.M = np.array(M, float)
        self.applied.append(self.M)

    def end_primitive(self):
        self.ends += 1


class Hinge:
    """One rotational DOF about world z through the origin, limited to [-0.5, 1.0] rad."""

    def __init__(self):
        self.value = 0.2

    def dof_count(self):
        return 1

    def dof_axis(self, k):
        return np.array([0.0, 0.0, 1.0]), np.zeros(3)

    def dof_value(self, k):
        return self.value

    def dof_limits(self, k):
        return -0.5, 1.0

    def set_dof_value(self, k, v):
        self.value = v


def ray_to(p, eye=(0.0, 0.0, 5.0)):
    """A ray from ``eye`` through point ``p``."""
    o = np.array(eye, float)
    d = np.asarray(p, float) - o
    return o, d / np.linalg.norm(d)


def ortho(x, y):
    """A ray straight down -z through (x, y) (an orthographic view from the front)."""
    return np.array([x, y, 5.0]), np.array([0.0, 0.0, -1.0])


def test_left_button_translates_along_x_without_a_jump():
    t = Frame()
    m = Manipulator()
    m.attach(t)
    m.set_buttons({"left"}, False, False, ortho(0.3, 0.2))  # grabbed off the origin
    assert m.primitive.kind is PrimitiveKind.LINEAR and m.primitive.axes == (0,)
    m.move(ortho(0.3, 0.2))
    assert np.allclose(t.M[:3, 3], 0.0)  # no jump at the press
    m.move(ortho(0.5, 0.9))
    assert np.allclose(t.M[:3, 3], [0.2, 0.0, 0.0])  # y motion of the mouse is ignored


def test_literal_mode_jumps_to_the_closest_point():
    t = Frame()
    m = Manipulator(literal=True)
    m.attach(t)
    m.set_buttons({"left"}, False, False, ortho(0.3, 0.2))
    m.move(ortho(0.3, 0.2))
    assert np.allclose(t.M[:3, 3], [0.3, 0.0, 0.0])


def test_two_buttons_translate_in_a_plane_and_three_do_nothing():
    t = Frame()
    m = Manipulator()
    m.attach(t)
    m.set_buttons({"left", "middle"}, False, False, ray_to([0.0, 0.0, 0.0]))
    assert m.primitive.kind is PrimitiveKind.PLANAR and m.primitive.axes == (0, 1)
    m.move(ray_to([0.2, -0.1, 0.0]))
    assert np.allclose(t.M[:3, 3], [0.2, -0.1, 0.0])
    m.set_buttons({"left", "middle", "right"}, False, False, ray_to([0.2, -0.1, 0.0]))
    assert m.primitive.kind is PrimitiveKind.NONE
    assert not m.move(ray_to([0.9, 0.9, 0.0]))


def test_shift_uses_local_axes_frozen_at_press():
    R = np.eye(4)
    R[:3, :3] = rotation_matrix(np.array([0.0, 0.0, 1.0]), np.pi / 2)  # local x = world y
    t = Frame(R)
    m = Manipulator()
    m.attach(t)
    m.set_buttons({"left"}, True, False, ray_to([0.0, 0.0, 0.0]))
    m.move(ray_to([0.0, 0.3, 0.0]))
    assert np.allclose(t.M[:3, 3], [0.0, 0.3, 0.0])


def test_control_rotates_about_the_axis_and_keeps_cranking_past_half_a_turn():
    t = Frame()
    m = Manipulator()
    m.attach(t)
    m.set_buttons({"right"}, False, True, ray_to([0.3, 0.0, 0.0]))  # CONTROL + right: about z
    assert m.primitive.kind is PrimitiveKind.ROTATE and m.primitive.axes == (2,)
    for a in np.linspace(0.0, 1.5 * np.pi, 40):
        m.move(ray_to([0.3 * np.cos(a), 0.3 * np.sin(a), 0.0]))
    assert m.wheel_angle == pytest.approx(1.5 * np.pi)
    assert np.allclose(t.M[:3, :3], rotation_matrix(np.array([0.0, 0.0, 1.0]), 1.5 * np.pi))
    assert np.allclose(t.M[:3, 3], 0.0)


def test_button_change_ends_the_primitive_and_restarts_at_the_cursor():
    t = Frame()
    m = Manipulator()
    m.attach(t)
    m.set_buttons({"left"}, False, False, ray_to([0.0, 0.0, 0.0]))
    m.move(ray_to([0.2, 0.0, 0.0]))
    m.set_buttons({"left", "right"}, False, False, ray_to([0.2, 0.0, 0.0]))  # now planar xz
    assert t.ends == 1 and m.primitive.kind is PrimitiveKind.PLANAR
    m.set_buttons({"right"}, False, False, ray_to([0.2, 0.0, 0.0]))
    assert t.ends == 2 and m.primitive.axes == (2,)
    m.finish()
    assert t.ends == 3 and not m.active


def test_joint_stops_at_its_limit_while_the_wheel_turns_on():
    j = Hinge()
    m = Manipulator()
    m.attach(joint=j)
    m.set_buttons({"right"}, False, True, ray_to([0.3, 0.0, 0.0]))
    values = []
    for a in np.linspace(0.0, 1.6 * np.pi, 50):
        m.move(ray_to([0.3 * np.cos(a), 0.3 * np.sin(a), 0.0]))
        values.append(j.value)
    assert m.wheel_angle == pytest.approx(1.6 * np.pi)
    assert max(values) == pytest.approx(1.0) and j.value == pytest.approx(1.0)
    assert all(-0.5 <= v <= 1.0 for v in values)
    # cranking back turns the joint again as soon as the wheel re-enters the allowed range
    for a in np.linspace(1.6 * np.pi, 0.3, 50):
        m.move(ray_to([0.3 * np.cos(a), 0.3 * np.sin(a), 0.0]))
    assert j.value == pytest.approx(0.5)
    _, lines = m.overlay()
    assert any(np.allclose(ln.color[:3], (1.0, 0.15, 0.1)) for ln in lines)  # the red sector


def test_overlay_draws_the_frame_and_the_active_axis():
    t = Frame()
    m = Manipulator()
    m.attach(t)
    triads, lines = m.overlay()
    assert len(triads) == 1 and not lines
    m.set_buttons({"middle"}, False, False, ray_to([0.0, 0.0, 0.0]))
    _, lines = m.overlay()
    seg = lines[0].segments[0]
    assert np.allclose(np.cross(seg[1] - seg[0], [0.0, 1.0, 0.0]), 0.0)
