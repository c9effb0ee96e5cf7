"""Camera matrices, the one set every picture uses (the window, screenshots, reports, visibility).

4x4 float64 matrices for column vectors with OpenGL clip conventions: ``view`` maps world to camera
(the camera looks down its -z axis, y up), ``projection`` camera to clip space (NDC depth in
[-1, 1]). Metres and radians.
"""

from __future__ import annotations

import numpy as np


def perspective_matrix(fov_y: float, aspect: float, near: float, far: float) -> np.ndarray:
    """OpenGL perspective projection; ``fov_y`` in radians, ``aspect`` = width / height."""
    f = 1.0 / np.tan(0.5 * fov_y)
    m = np.zeros((4, 4))
    m[0, 0] = f / aspect
    m[1, 1] = f
    m[2, 2] = (far + near) / (near - far)
    m[2, 3] = 2.0 * far * near / (near - far)
    m[3, 2] = -1.0
    return m


def orthographic_matrix(half_height: float, aspect: float, near: float, far: float) -> np.ndarray:
    """OpenGL orthographic projection of a view volume ``2*half_height`` metres tall."""
    half_width = half_height * aspect
    m = np.eye(4)
    m[0, 0] = 1.0 / half_width
    m[1, 1] = 1.0 / half_height
    m[2, 2] = -2.0 / (far - near)
    m[2, 3] = -(far + near) / (far - near)
    return m


def look_at(eye: np.ndarray, target: np.ndarray, up: np.ndarray = np.array([0.0, 1.0, 0.0])) -> np.ndarray:
    """World-to-camera transform of a camera at ``eye`` looking at ``target`` (metres)."""
    eye, target, up = (np.asarray(a, dtype=float) for a in (eye, target, up))
    f = target - eye
    f /= np.linalg.norm(f)
    s = np.cross(f, up)
    if np.linalg.norm(s) < 1e-9:  # looking along up: pick any perpendicular
        s = np.cross(f, np.array([1.0, 0.0, 0.0]) if abs(f[0]) < 0.9 else np.array([0.0, 0.0, 1.0]))
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def linear_depth(depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """Camera-space distance along the view axis (metres) from depth-buffer values in [0, 1]."""
    z = 2.0 * depth - 1.0
    return 2.0 * near * far / (far + near - z * (far - near))
