"""Orbit camera for the 3-D viewport, and the mouse mappings that drive it.

World frame: right-handed, y up, metres, radians. Matrices are 4x4 float64 for column vectors
(``p_view = view @ p_world``) with OpenGL clip conventions (camera looks down its -z axis, NDC
depth in [-1, 1]). Pixel coordinates have their origin at the top-left corner of the viewport,
x to the right and y downwards, as window systems report the cursor.

The camera is parameterised by a target point, a distance from it, and two angles:

* ``yaw`` turns about world +y; at ``yaw = 0`` the camera sits on the +z side of the target
  (a front view of a figure that faces +z).
* ``pitch`` raises the camera; ``+pi/2`` looks straight down (top view, screen-up = world -z).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum
from typing import Literal

import numpy as np

from jackpy.render.projection import orthographic_matrix, perspective_matrix

Button = Literal["left", "middle", "right"]
"""A mouse button by its position on the mouse."""

ViewPreset = Literal["front", "back", "left", "right", "side", "top", "bottom", "iso"]

_PITCH_LIMIT = 0.5 * np.pi

_PRESETS: dict[str, tuple[float, float]] = {
    # name: (yaw, pitch) in radians
    "front": (0.0, 0.0),
    "back": (np.pi, 0.0),
    "right": (0.5 * np.pi, 0.0),
    "side": (0.5 * np.pi, 0.0),
    "left": (-0.5 * np.pi, 0.0),
    "top": (0.0, 0.5 * np.pi),
    "bottom": (0.0, -0.5 * np.pi),
    "iso": (0.25 * np.pi, float(np.arctan(1.0 / np.sqrt(2.0)))),
}


def _rot_x(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def _rot_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


@dataclass
class OrbitCamera:
    """A camera orbiting ``target`` at ``distance`` metres, angles ``yaw``/``pitch`` in radians.

    In orthographic mode the visible height equals the height that the perspective frustum
    shows at the target's depth, so switching modes keeps the target's apparent size.
    """

    target: np.ndarray = field(default_factory=lambda: np.array([0.0, 1.0, 0.0]))
    distance: float = 4.0
    yaw: float = 0.0
    pitch: float = 0.0
    fov_y: float = float(np.radians(40.0))
    orthographic: bool = False
    min_distance: float = 0.05
    max_distance: float = 500.0

    def __post_init__(self) -> None:
        self.target = np.asarray(self.target, dtype=float).copy()

    # ----------------------------------------------------------------- frames and matrices
    def rotation(self) -> np.ndarray:
        """3x3 rotation whose columns are the camera's right, up and backward axes in world."""
        return _rot_y(self.yaw) @ _rot_x(-self.pitch)

    def eye(self) -> np.ndarray:
        """Camera position in world (m)."""
        return self.target + self.rotation() @ np.array([0.0, 0.0, self.distance])

    def camera_to_world(self) -> np.ndarray:
        """4x4 pose of the camera in world (the inverse of :meth:`view_matrix`)."""
        m = np.eye(4)
        m[:3, :3] = self.rotation()
        m[:3, 3] = self.eye()
        return m

    def view_matrix(self) -> np.ndarray:
        """4x4 world-to-camera transform."""
        r = self.rotation()
        m = np.eye(4)
        m[:3, :3] = r.T
        m[:3, 3] = -r.T @ self.eye()
        return m

    def clip_range(self) -> tuple[float, float]:
        """Near and far clip distances (m), scaled with the orbit distance."""
        return max(1e-3, 0.01 * self.distance), 100.0 * self.distance + 100.0

    def half_height_at_target(self) -> float:
        """Half the visible height (m) at the target's depth."""
        return self.distance * float(np.tan(0.5 * self.fov_y))

    def projection_matrix(self, aspect: float) -> np.ndarray:
        """4x4 projection for a viewport of ``aspect`` = width / height."""
        near, far = self.clip_range()
        if self.orthographic:
            # Push the near plane behind the eye so that nothing between eye and target clips.
            return orthographic_matrix(self.half_height_at_target(), aspect, -far, far)
        return perspective_matrix(self.fov_y, aspect, near, far)

    # ---------------------------------------------------------------- navigation
    def orbit(self, d_yaw: float, d_pitch: float) -> None:
        """Turn about the target by ``d_yaw`` and ``d_pitch`` radians; pitch stays within ±90°."""
        self.yaw = float((self.yaw + d_yaw + np.pi) % (2.0 * np.pi) - np.pi)
        self.pitch = float(np.clip(self.pitch + d_pitch, -_PITCH_LIMIT, _PITCH_LIMIT))

    def orbit_pixels(self, dx: float, dy: float, radians_per_pixel: float = 0.008) -> None:
        """Orbit by a mouse drag of (dx, dy) pixels: right drag turns the scene right."""
        self.orbit(-dx * radians_per_pixel, dy * radians_per_pixel)

    def pan(self, dx: float, dy: float, viewport_height: int) -> None:
        """Move the target so that the scene at the target's depth follows a drag of (dx, dy) px."""
        metres_per_pixel = 2.0 * self.half_height_at_target() / max(1, viewport_height)
        r = self.rotation()
        self.target = self.target - r[:, 0] * dx * metres_per_pixel + r[:, 1] * dy * metres_per_pixel

    def zoom(self, steps: float, factor: float = 0.9) -> None:
        """Dolly towards the target: each positive wheel step scales the distance by ``factor``."""
        self.distance = float(
            np.clip(self.distance * factor**steps, self.min_distance, self.max_distance)
        )

    def set_preset(self, name: ViewPreset) -> None:
        """Look from a named direction: front (+z), back, right/side (+x), left, top, bottom, iso."""
        self.yaw, self.pitch = _PRESETS[name]

    def frame(self, bbox_min: np.ndarray, bbox_max: np.ndarray, aspect: float = 1.0,
              margin: float = 1.1) -> None:
        """Aim at the centre of a world box and back off until its bounding sphere fits."""
        lo, hi = np.asarray(bbox_min, float), np.asarray(bbox_max, float)
        self.target = 0.5 * (lo + hi)
        radius = max(0.5 * float(np.linalg.norm(hi - lo)), 1e-3) * margin
        half_fov = 0.5 * self.fov_y
        if aspect < 1.0:
            half_fov = float(np.arctan(np.tan(half_fov) * aspect))
        self.distance = float(np.clip(radius / np.sin(half_fov), self.min_distance, self.max_distance))

    # ---------------------------------------------------------------- picking
    def ray_from_pixel(self, x: float, y: float, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
        """World ray (origin, unit direction) through pixel (x, y), origin at the top-left.

        The pixel is unprojected at NDC depth -1 and +1 through ``inv(proj @ view)``; for a
        perspective camera the origin is the eye, for an orthographic one it lies on the near plane.
        """
        ndc_x = 2.0 * x / width - 1.0
        ndc_y = 1.0 - 2.0 * y / height
        inv = np.linalg.inv(self.projection_matrix(width / height) @ self.view_matrix())
        near = inv @ np.array([ndc_x, ndc_y, -1.0, 1.0])
        far = inv @ np.array([ndc_x, ndc_y, 1.0, 1.0])
        near, far = near[:3] / near[3], far[:3] / far[3]
        origin = self.eye() if not self.orthographic else near
        direction = far - origin
        return origin, direction / np.linalg.norm(direction)


# ------------------------------------------------------------------------ mouse mappings
class NavAction(Enum):
    """What a mouse drag does to the camera."""

    ORBIT = "orbit"
    PAN = "pan"
    ZOOM = "zoom"


@dataclass(frozen=True)
class MouseBinding:
    """A drag with ``button`` while exactly ``modifiers`` are held performs ``action``."""

    button: Button
    modifiers: frozenset[str]
    action: NavAction


def _binding(button: Button, action: NavAction, *modifiers: str) -> MouseBinding:
    return MouseBinding(button, frozenset(modifiers), action)


MOUSE_MAPPINGS: dict[str, tuple[MouseBinding, ...]] = {
    # left orbit, right pan, wheel zoom (p5.js, MuJoCo, most viewers); shift-left pans for trackpads
    "default": (
        _binding("left", NavAction.ORBIT),
        _binding("right", NavAction.PAN),
        _binding("left", NavAction.PAN, "shift"),
        _binding("middle", NavAction.ZOOM),
    ),
    # Blender: middle orbit, shift-middle pan, ctrl-middle zoom
    "blender": (
        _binding("middle", NavAction.ORBIT),
        _binding("middle", NavAction.PAN, "shift"),
        _binding("middle", NavAction.ZOOM, "ctrl"),
    ),
    # Maya: Alt-left tumble, Alt-middle track, Alt-right dolly
    "maya": (
        _binding("left", NavAction.ORBIT, "alt"),
        _binding("middle", NavAction.PAN, "alt"),
        _binding("right", NavAction.ZOOM, "alt"),
    ),
}
"""Named navigation presets; the mouse wheel zooms in every preset. A binding with ``alt`` moves the
camera even when the press is on a pickable thing (Alt is none of the Jack operator's modifiers)."""


def navigation_action(mapping: str, button: Button, modifiers: frozenset[str] | set[str] = frozenset()
                      ) -> NavAction | None:
    """The camera action bound to a drag with ``button`` and ``modifiers`` in preset ``mapping``."""
    mods = frozenset(modifiers)
    for b in MOUSE_MAPPINGS[mapping]:
        if b.button == button and b.modifiers == mods:
            return b.action
    return None
