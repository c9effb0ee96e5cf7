"""Geometry of the Jack direct-manipulation operator (spec manipulation-and-ik.md §2).

Pure numpy, no state and no OpenGL. Everything is in world coordinates: points and lengths in
metres, angles in radians, rotations as 3x3 matrices, transforms as 4x4 column-vector matrices.
A mouse ray is ``(o, d)``: origin ``o`` and unit direction ``d`` (see
:meth:`jackpy.ui.camera.OrbitCamera.ray_from_pixel`).

The caller (the operator loop) keeps the press-time state: the manipulation transform ``M0`` at
button-down, the frozen axes, and the press parameter of the primitive (``t_press``,
``hit_press`` or the start spoke), and calls these functions on every mouse move.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Iterable, Literal

import numpy as np

Button = Literal["left", "middle", "right"]

EPS_PARALLEL = 1e-6
"""Below this, ``1 - (a.d)^2`` or ``|d.n|`` count as parallel / edge-on and the motion is ignored."""

BUTTON_AXIS: dict[str, int] = {"left": 0, "middle": 1, "right": 2}
"""Jack's mapping (prose of §3.1.4, Table 3.1 corrected): left, middle, right = x, y, z."""


class PrimitiveKind(Enum):
    """The motion primitive selected by buttons and CONTROL."""

    NONE = "none"
    LINEAR = "linear"
    PLANAR = "planar"
    ROTATE = "rotate"


@dataclass(frozen=True)
class Primitive:
    """A primitive and its axis indices (0, 1, 2 = x, y, z); ``local`` means M's own axes."""

    kind: PrimitiveKind
    axes: tuple[int, ...] = ()
    local: bool = False


def select_primitive(buttons: Iterable[Button], shift: bool = False, control: bool = False) -> Primitive:
    """Map held buttons and modifiers to a primitive (Table 3.1 of the spec, corrected).

    One button: linear translation along its axis; two buttons: planar translation in the plane
    of their axes; three buttons: no effect. With CONTROL, exactly one button rotates about its
    axis and more buttons are a no-op. SHIFT selects local instead of global axes.
    """
    axes = tuple(sorted({BUTTON_AXIS[b] for b in buttons}))
    if control:
        if len(axes) == 1:
            return Primitive(PrimitiveKind.ROTATE, axes, shift)
        return Primitive(PrimitiveKind.NONE)
    if len(axes) == 1:
        return Primitive(PrimitiveKind.LINEAR, axes, shift)
    if len(axes) == 2:
        return Primitive(PrimitiveKind.PLANAR, axes, shift)
    return Primitive(PrimitiveKind.NONE)


def manipulation_axes(M: np.ndarray, local: bool) -> np.ndarray:
    """3x3 matrix whose columns are the unit x, y, z axes used for a drag.

    Global axes are the world basis; local (SHIFT) axes are the columns of M's rotation,
    normalised. Call this at button-down and keep the result, so that the axes stay frozen
    while the drag rotates M.
    """
    if not local:
        return np.eye(3)
    r = np.asarray(M, float)[:3, :3]
    return r / np.linalg.norm(r, axis=0)


# ---------------------------------------------------------------------- linear translation
def axis_parameter(c0: np.ndarray, a: np.ndarray, o: np.ndarray, d: np.ndarray,
                   eps: float = EPS_PARALLEL) -> float | None:
    """Parameter ``t`` (m) of the point ``c0 + t a`` on the axis closest to the mouse ray.

    ``a`` and ``d`` are unit vectors. Returns None when the axis is nearly parallel to the ray
    (``1 - (a.d)^2 < eps``), where the closest point is ill-defined.
    """
    w = np.asarray(c0, float) - np.asarray(o, float)
    b = float(np.dot(a, d))
    denom = 1.0 - b * b
    if denom < eps:
        return None
    return (b * float(np.dot(d, w)) - float(np.dot(a, w))) / denom


def closest_point_on_axis(c0: np.ndarray, a: np.ndarray, o: np.ndarray, d: np.ndarray) -> np.ndarray | None:
    """The point of the axis ``c0 + t a`` closest to the mouse ray (m), or None if parallel."""
    t = axis_parameter(c0, a, o, d)
    return None if t is None else np.asarray(c0, float) + t * np.asarray(a, float)


def linear_translation(c0: np.ndarray, a: np.ndarray, t_press: float, o: np.ndarray,
                       d: np.ndarray) -> np.ndarray | None:
    """New origin of M for a one-axis drag, without the initial jump.

    ``c0`` is M's origin at button-down and ``t_press`` the :func:`axis_parameter` of the press
    ray; the origin moves by ``(t - t_press) a``. Pass ``t_press = 0`` for the literal Jack
    behaviour, where the origin jumps to the closest point. None when the axis is parallel to
    the ray (ignore the motion).
    """
    t = axis_parameter(c0, a, o, d)
    if t is None:
        return None
    return np.asarray(c0, float) + (t - t_press) * np.asarray(a, float)


# ---------------------------------------------------------------------- planar translation
def ray_plane_hit(o: np.ndarray, d: np.ndarray, p0: np.ndarray, n: np.ndarray,
                  eps: float = EPS_PARALLEL) -> np.ndarray | None:
    """Point where the ray ``o + s d`` meets the plane through ``p0`` with normal ``n`` (m).

    None when the plane is seen edge-on (``|d.n| < eps``) or the hit lies behind the ray origin.
    """
    dn = float(np.dot(d, n))
    if abs(dn) < eps:
        return None
    s = float(np.dot(np.asarray(p0, float) - o, n)) / dn
    if s < 0.0:
        return None
    return np.asarray(o, float) + s * np.asarray(d, float)


def plane_normal(axes: np.ndarray, pair: tuple[int, int]) -> np.ndarray:
    """Unit normal ``a_i x a_j`` of the plane spanned by two columns of ``axes``."""
    n = np.cross(axes[:, pair[0]], axes[:, pair[1]])
    return n / np.linalg.norm(n)


def planar_translation(c0: np.ndarray, n: np.ndarray, hit_press: np.ndarray, o: np.ndarray,
                       d: np.ndarray) -> np.ndarray | None:
    """New origin of M for a two-axis drag in the plane through ``c0`` with normal ``n``.

    The origin moves by the displacement of the plane hit since the press (``hit_press``), so the
    grabbed spot stays under the cursor; pass ``hit_press = c0`` for the literal Jack behaviour
    ("the object goes to the spot under the cursor"). None when the motion must be ignored.
    """
    hit = ray_plane_hit(o, d, c0, n)
    if hit is None:
        return None
    return np.asarray(c0, float) + (hit - np.asarray(hit_press, float))


# ---------------------------------------------------------------------- rotation wheel
def wheel_hit(center: np.ndarray, axis: np.ndarray, o: np.ndarray, d: np.ndarray,
              eps: float = 1e-3) -> np.ndarray:
    """Where the mouse ray meets the wheel plane (through ``center``, normal ``axis``), in m.

    When the plane is nearly edge-on (``|d.axis| < eps``), the ray point closest to the centre
    is projected onto the plane instead, so the wheel keeps turning smoothly.
    """
    center, axis, o, d = (np.asarray(v, float) for v in (center, axis, o, d))
    hit = ray_plane_hit(o, d, center, axis) if abs(float(np.dot(d, axis))) >= eps else None
    if hit is None:
        p = o + float(np.dot(center - o, d)) * d
        hit = p - float(np.dot(p - center, axis)) * axis
    return hit


def signed_angle(v0: np.ndarray, v1: np.ndarray, axis: np.ndarray) -> float:
    """Angle (rad, in (-pi, pi]) from ``v0`` to ``v1`` about unit ``axis``, right-hand rule.

    Only the components of the vectors in the plane perpendicular to ``axis`` matter.
    """
    return float(np.arctan2(np.dot(axis, np.cross(v0, v1)), np.dot(v0, v1)))


def spoke_angle(center: np.ndarray, axis: np.ndarray, hit_press: np.ndarray, hit: np.ndarray) -> float:
    """Wheel angle (rad) between the start spoke ``hit_press - center`` and the current spoke."""
    return signed_angle(np.asarray(hit_press, float) - center, np.asarray(hit, float) - center, axis)


def unwrap_angle(previous: float, raw: float) -> float:
    """The angle ``raw + 2 pi k`` nearest to ``previous`` (rad): lets the user keep cranking.

    ``raw`` is a :func:`spoke_angle` in (-pi, pi]; ``previous`` the accumulated angle of the
    last mouse event.
    """
    return previous + float((raw - previous + np.pi) % (2.0 * np.pi) - np.pi)


def rotation_matrix(axis: np.ndarray, angle: float) -> np.ndarray:
    """3x3 rotation by ``angle`` radians about unit ``axis`` (Rodrigues)."""
    x, y, z = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


def rotate_manipulation(M0: np.ndarray, axis_index: int, angle: float, local: bool) -> np.ndarray:
    """M after turning ``angle`` rad about its own origin around axis ``axis_index``.

    Global: ``R = Rot(e_k, angle) @ R0``; local: ``R = R0 @ Rot(e_k, angle)``. The origin is
    unchanged.
    """
    M = np.array(M0, dtype=float)
    e = np.eye(3)[axis_index]
    rot = rotation_matrix(e, angle)
    M[:3, :3] = M[:3, :3] @ rot if local else rot @ M[:3, :3]
    return M


# ---------------------------------------------------------------------- joint limits
def clamp_joint_angle(theta_press: float, phi: float, lower: float, upper: float) -> float:
    """Joint angle applied for wheel angle ``phi``: ``clamp(theta_press + phi, lower, upper)`` (rad)."""
    return float(np.clip(theta_press + phi, lower, upper))


def limit_sector(theta_press: float, lower: float, upper: float) -> tuple[float, float] | None:
    """The forbidden (red) arc of the wheel, ``(start, end)`` in radians from the start spoke.

    Angles are measured in the wheel plane about the rotation axis, right-hand rule, with
    ``start < end``: the arc runs from ``upper - theta_press`` to ``lower - theta_press + 2 pi``.
    None when the range covers a full turn (nothing is forbidden). ``theta_press`` is the DOF
    value at button-down, assumed within ``[lower, upper]``.
    """
    if upper - lower >= 2.0 * np.pi:
        return None
    return upper - theta_press, lower - theta_press + 2.0 * np.pi


def in_sector(angle: float, sector: tuple[float, float] | None) -> bool:
    """Whether a wheel angle (rad, any winding) lies in a sector from :func:`limit_sector`."""
    if sector is None:
        return False
    start, end = sector
    return bool((angle - start) % (2.0 * np.pi) <= end - start)


def wheel_arc(center: np.ndarray, axis: np.ndarray, start_spoke: np.ndarray, radius: float,
              start: float, end: float, segments: int = 32) -> np.ndarray:
    """(segments + 1, 3) points of a wheel arc from ``start`` to ``end`` rad off ``start_spoke``.

    The arc lies in the plane through ``center`` perpendicular to ``axis``, at ``radius`` metres;
    used to draw the wheel, the live spoke and the red limit sector.
    """
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    u = np.asarray(start_spoke, float)
    u = u - np.dot(u, axis) * axis
    u /= np.linalg.norm(u)
    v = np.cross(axis, u)
    t = np.linspace(start, end, segments + 1)[:, None]
    return np.asarray(center, float) + radius * (np.cos(t) * u + np.sin(t) * v)


# ---------------------------------------------------------------------- orientation ratchet
def orientation_offset(R_manip: np.ndarray, R_effector: np.ndarray) -> np.ndarray:
    """The ratchet at button-up: offset ``O = R_M^T R_ee`` so that ``R_M @ O`` is achieved.

    After every translation or rotation ends, the goal orientation is re-seated on the end
    effector's actual orientation, and any unachieved rotation is thrown away (spec §2.10).
    """
    return np.asarray(R_manip, float).T @ np.asarray(R_effector, float)


def goal_orientation(R_manip: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """Goal orientation handed to IK while dragging: ``R_goal = R_M @ O``."""
    return np.asarray(R_manip, float) @ np.asarray(offset, float)
