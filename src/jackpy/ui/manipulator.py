"""The Jack direct-manipulation operator as a state machine (spec manipulation-and-ik.md §2).

Held buttons and modifiers select a primitive (:func:`operator_math.select_primitive`: left,
middle, right = x, y, z; one button linear, two planar, CONTROL rotation, SHIFT local axes). Each
mouse move turns the mouse ray into a new manipulation transform ``M`` that the *target* applies
(an end-effector goal, an object's placement). A change of buttons or modifiers ends the current
primitive and starts a new one at the cursor; every primitive end calls the target's
:meth:`Target.end_primitive` (the orientation ratchet of §2.10).

Grab offset: by default the grabbed point stays under the cursor (no jump at button-down); with
``literal=True`` the origin jumps to the closest point of the axis / the plane hit, as Jack did.

A :class:`JointTarget` rotates one joint DOF with CONTROL-drag: the wheel keeps turning past a limit
(drawn red) while the joint stops at the limit.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from jackpy.ui import operator_math as om
from jackpy.ui.operator_math import Button, Primitive, PrimitiveKind
from jackpy.render import Lines, Triad

Ray = tuple[np.ndarray, np.ndarray]
"""A mouse ray: origin and unit direction in world (m)."""

WHEEL_RADIUS = 0.15
"""Radius of the drawn rotation wheel (m)."""
MIN_SPOKE = 1e-3
"""Spokes shorter than this (m) are ignored: the angle is undefined at the wheel centre."""


class Target(Protocol):
    """Something the operator moves through a manipulation transform ``M`` (4x4, world)."""

    def transform(self) -> np.ndarray:
        """The current manipulation transform."""

    def apply(self, M: np.ndarray) -> None:
        """Take the new manipulation transform (set a goal, move an object)."""

    def end_primitive(self) -> None:
        """A translation or rotation ended (button or modifier change)."""


class JointTarget(Protocol):
    """A joint rotated DOF by DOF with CONTROL-drag."""

    def dof_count(self) -> int:
        """Number of the joint's rotational DOFs."""

    def dof_axis(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """World (unit axis, point on axis) of rotational DOF ``k``; turning about the axis by the
        right-hand rule increases the angle."""

    def dof_value(self, k: int) -> float:
        """Current angle (rad)."""

    def dof_limits(self, k: int) -> tuple[float, float]:
        """(lower, upper) in rad."""

    def set_dof_value(self, k: int, value: float) -> None:
        """Set the angle (rad); the caller has clamped it."""


@dataclass
class _Drag:
    """Press-time state of the current primitive."""

    primitive: Primitive
    M0: np.ndarray
    axes: np.ndarray
    t_press: float | None = None
    hit_press: np.ndarray | None = None
    normal: np.ndarray | None = None
    angle: float = 0.0
    dof: int = -1
    theta_press: float = 0.0
    center: np.ndarray = field(default_factory=lambda: np.zeros(3))
    wheel_axis: np.ndarray = field(default_factory=lambda: np.array([0.0, 1.0, 0.0]))


class Manipulator:
    """The operator: feed it button/modifier changes and mouse rays; it drives its target."""

    def __init__(self, literal: bool = False) -> None:
        self.literal = literal
        self.target: Target | None = None
        self.joint: JointTarget | None = None
        self.buttons: frozenset[Button] = frozenset()
        self.shift = False
        self.control = False
        self._drag: _Drag | None = None
        self._last_ray: Ray | None = None

    # ------------------------------------------------------------------ state
    @property
    def active(self) -> bool:
        """Whether a drag is under way (some button held on a target)."""
        return bool(self.buttons) and (self.target is not None or self.joint is not None)

    @property
    def primitive(self) -> Primitive:
        """The running primitive (``NONE`` when idle or for an invalid button combination)."""
        return self._drag.primitive if self._drag is not None else Primitive(PrimitiveKind.NONE)

    @property
    def wheel_angle(self) -> float:
        """Accumulated (unclamped) wheel angle of the running rotation, rad."""
        return self._drag.angle if self._drag is not None else 0.0

    def attach(self, target: Target | None = None, joint: JointTarget | None = None) -> None:
        """Choose what the next drag moves: a transform target, or a joint for CONTROL-rotation."""
        self.finish()
        self.target, self.joint = target, joint

    # ------------------------------------------------------------------ input
    def set_buttons(self, buttons: frozenset[Button] | set[Button], shift: bool, control: bool,
                    ray: Ray) -> None:
        """Buttons or modifiers changed: end the running primitive, start the new one at ``ray``."""
        buttons = frozenset(buttons)
        if (buttons, shift, control) == (self.buttons, self.shift, self.control):
            return
        self._end_primitive()
        self.buttons, self.shift, self.control = buttons, shift, control
        self._last_ray = ray
        if buttons:
            self._start(ray)

    def move(self, ray: Ray) -> bool:
        """Mouse moved to ``ray``; returns whether the target changed."""
        self._last_ray = ray
        d = self._drag
        if d is None:
            return False
        o, dv = (np.asarray(v, float) for v in ray)
        kind = d.primitive.kind
        if kind is PrimitiveKind.LINEAR:
            if d.t_press is None:
                return False
            origin = om.linear_translation(d.M0[:3, 3], d.axes[:, d.primitive.axes[0]], d.t_press, o, dv)
            return self._apply_origin(d, origin)
        if kind is PrimitiveKind.PLANAR:
            if d.hit_press is None:
                return False
            origin = om.planar_translation(d.M0[:3, 3], d.normal, d.hit_press, o, dv)
            return self._apply_origin(d, origin)
        if kind is PrimitiveKind.ROTATE:
            return self._rotate(d, o, dv)
        return False

    def finish(self) -> None:
        """End the drag (all buttons up, or the operator left with ESCAPE)."""
        self._end_primitive()
        self.buttons = frozenset()
        self.shift = self.control = False

    # ------------------------------------------------------------------ primitives
    def _start(self, ray: Ray) -> None:
        prim = om.select_primitive(self.buttons, self.shift, self.control)
        if prim.kind is PrimitiveKind.NONE:
            return
        o, dv = (np.asarray(v, float) for v in ray)
        if prim.kind is PrimitiveKind.ROTATE and self.joint is not None:
            self._drag = self._start_joint(prim, o, dv)
            return
        if self.target is None:
            return
        M0 = np.array(self.target.transform(), dtype=float)
        axes = om.manipulation_axes(M0, prim.local)
        d = _Drag(prim, M0, axes)
        c0 = M0[:3, 3]
        if prim.kind is PrimitiveKind.LINEAR:
            d.t_press = 0.0 if self.literal else om.axis_parameter(c0, axes[:, prim.axes[0]], o, dv)
        elif prim.kind is PrimitiveKind.PLANAR:
            d.normal = om.plane_normal(axes, (prim.axes[0], prim.axes[1]))
            d.hit_press = c0.copy() if self.literal else om.ray_plane_hit(o, dv, c0, d.normal)
        else:
            d.center, d.wheel_axis = c0.copy(), axes[:, prim.axes[0]].copy()
            d.hit_press = om.wheel_hit(d.center, d.wheel_axis, o, dv)
        self._drag = d

    def _start_joint(self, prim: Primitive, o: np.ndarray, dv: np.ndarray) -> _Drag | None:
        """CONTROL-drag on a joint. Global: the DOF whose axis best matches the button's world
        axis turns; local (SHIFT): the button picks the DOF by index (left first, clamped)."""
        j = self.joint
        assert j is not None
        n = j.dof_count()
        if n == 0:
            return None
        k = prim.axes[0]
        if prim.local:
            best = min(k, n - 1)
        else:
            best = max(range(n), key=lambda i: abs(float(j.dof_axis(i)[0][k])))
        axis_world, point = j.dof_axis(best)
        frame = np.eye(4)
        frame[:3, 3] = point
        d = _Drag(prim, frame, np.eye(3), dof=best, theta_press=j.dof_value(best),
                  center=np.asarray(point, float), wheel_axis=np.asarray(axis_world, float))
        d.hit_press = om.wheel_hit(d.center, d.wheel_axis, o, dv)
        return d

    def _apply_origin(self, d: _Drag, origin: np.ndarray | None) -> bool:
        if origin is None or self.target is None:
            return False
        M = d.M0.copy()
        M[:3, 3] = origin
        self.target.apply(M)
        return True

    def _rotate(self, d: _Drag, o: np.ndarray, dv: np.ndarray) -> bool:
        if d.hit_press is None or np.linalg.norm(d.hit_press - d.center) < MIN_SPOKE:
            d.hit_press = om.wheel_hit(d.center, d.wheel_axis, o, dv)
            return False
        hit = om.wheel_hit(d.center, d.wheel_axis, o, dv)
        if np.linalg.norm(hit - d.center) < MIN_SPOKE:
            return False
        d.angle = om.unwrap_angle(d.angle, om.spoke_angle(d.center, d.wheel_axis, d.hit_press, hit))
        if d.dof >= 0:
            assert self.joint is not None
            lo, hi = self.joint.dof_limits(d.dof)
            self.joint.set_dof_value(d.dof, om.clamp_joint_angle(d.theta_press, d.angle, lo, hi))
            return True
        if self.target is None:
            return False
        self.target.apply(om.rotate_manipulation(d.M0, d.primitive.axes[0], d.angle, d.primitive.local))
        return True

    def _end_primitive(self) -> None:
        d, self._drag = self._drag, None
        if d is not None and d.dof < 0 and self.target is not None:
            self.target.end_primitive()

    # ------------------------------------------------------------------ feedback
    def overlay(self) -> tuple[list[Triad], list[Lines]]:
        """Triads and on-top lines showing M, the active axis/plane, and the wheel with its red sector."""
        triads: list[Triad] = []
        lines: list[Lines] = []
        if self.target is not None and self.joint is None:
            triads.append(Triad(np.array(self.target.transform(), float), 0.12))
        d = self._drag
        if d is None:
            return triads, lines
        kind = d.primitive.kind
        colors = ((1.0, 0.3, 0.3, 0.9), (0.3, 1.0, 0.3, 0.9), (0.35, 0.5, 1.0, 0.9))
        c = (self.target.transform()[:3, 3] if self.target is not None and d.dof < 0 else d.center)
        if kind is PrimitiveKind.LINEAR:
            k = d.primitive.axes[0]
            a = d.axes[:, k]
            lines.append(Lines(np.array([[c - 0.5 * a, c + 0.5 * a]]), colors[k], on_top=True))
        elif kind is PrimitiveKind.PLANAR:
            u, v = d.axes[:, d.primitive.axes[0]] * 0.15, d.axes[:, d.primitive.axes[1]] * 0.15
            corners = [c + u + v, c - u + v, c - u - v, c + u - v]
            segs = [[corners[i], corners[(i + 1) % 4]] for i in range(4)]
            lines.append(Lines(np.array(segs), (1.0, 0.9, 0.3, 0.9), on_top=True))
        elif kind is PrimitiveKind.ROTATE and d.hit_press is not None:
            lines.extend(self._wheel_lines(d))
        return triads, lines

    def _wheel_lines(self, d: _Drag) -> list[Lines]:
        spoke0 = d.hit_press - d.center
        if np.linalg.norm(spoke0 - np.dot(spoke0, d.wheel_axis) * d.wheel_axis) < MIN_SPOKE:
            return []
        arc = om.wheel_arc(d.center, d.wheel_axis, spoke0, WHEEL_RADIUS, 0.0, 2.0 * np.pi, 48)
        out = [Lines(np.stack([arc[:-1], arc[1:]], axis=1), (0.9, 0.9, 0.9, 0.8), on_top=True)]
        spokes = om.wheel_arc(d.center, d.wheel_axis, spoke0, WHEEL_RADIUS, 0.0, 2.0 * np.pi, 8)[:-1]
        out.append(Lines(np.stack([np.broadcast_to(d.center, spokes.shape), spokes], axis=1),
                         (0.8, 0.8, 0.8, 0.5), on_top=True))
        live = om.wheel_arc(d.center, d.wheel_axis, spoke0, WHEEL_RADIUS * 1.3, d.angle, d.angle, 1)[0]
        out.append(Lines(np.array([[d.center, live]]), (1.0, 1.0, 0.3, 1.0), on_top=True))
        if d.dof >= 0 and self.joint is not None:
            sector = om.limit_sector(d.theta_press, *self.joint.dof_limits(d.dof))
            if sector is not None:
                red = om.wheel_arc(d.center, d.wheel_axis, spoke0, WHEEL_RADIUS * 0.97, *sector, 32)
                segs = np.stack([np.broadcast_to(d.center, red.shape), red], axis=1)
                out.append(Lines(segs, (1.0, 0.15, 0.1, 0.55), on_top=True))
        return out
