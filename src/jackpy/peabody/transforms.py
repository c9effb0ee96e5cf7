"""4x4 homogeneous transforms (column vectors: ``p_world = T @ p_local``), metres and radians."""

from __future__ import annotations

import numpy as np

AXES = {"x": np.array([1.0, 0.0, 0.0]), "y": np.array([0.0, 1.0, 0.0]), "z": np.array([0.0, 0.0, 1.0])}


def identity() -> np.ndarray:
    """The 4x4 identity."""
    return np.eye(4)


def translation(x: float, y: float, z: float) -> np.ndarray:
    """Translation by (x, y, z) metres."""
    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t


def scaling(sx: float, sy: float, sz: float) -> np.ndarray:
    """Non-uniform scale along the local axes."""
    return np.diag([sx, sy, sz, 1.0])


def rotation(axis: np.ndarray | str, angle: float) -> np.ndarray:
    """Right-handed rotation by ``angle`` radians about a unit ``axis`` (or "x", "y", "z")."""
    a = AXES[axis] if isinstance(axis, str) else np.asarray(axis, dtype=float)
    t = np.eye(4)
    t[:3, :3] = rotation_matrix(a, angle)
    return t


def rotation_matrix(axis: np.ndarray, angle: float) -> np.ndarray:
    """3x3 rotation about a unit axis by ``angle`` radians (Rodrigues)."""
    x, y, z = axis / np.linalg.norm(axis)
    c, s = np.cos(angle), np.sin(angle)
    C = 1.0 - c
    return np.array([
        [c + x * x * C, x * y * C - z * s, x * z * C + y * s],
        [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
        [z * x * C - y * s, z * y * C + x * s, c + z * z * C],
    ])


def batch_rotations(axes: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Rotation matrices (n,3,3) for unit axes (n,3) and angles (n,) radians, vectorised Rodrigues."""
    c = np.cos(angles)[:, None, None]
    s = np.sin(angles)[:, None, None]
    x, y, z = axes[:, 0], axes[:, 1], axes[:, 2]
    zero = np.zeros_like(x)
    K = np.stack([zero, -z, y, z, zero, -x, -y, x, zero], axis=1).reshape(-1, 3, 3)
    outer = axes[:, :, None] * axes[:, None, :]
    return c * np.eye(3) + s * K + (1.0 - c) * outer


def rigid_inverse(t: np.ndarray) -> np.ndarray:
    """Inverse of a rigid transform (rotation + translation), or a stack of them (...,4,4)."""
    out = np.zeros_like(t)
    rt = np.swapaxes(t[..., :3, :3], -1, -2)
    out[..., :3, :3] = rt
    out[..., :3, 3] = -np.einsum("...ij,...j->...i", rt, t[..., :3, 3])
    out[..., 3, 3] = 1.0
    return out


def is_rigid(t: np.ndarray, tol: float = 1e-9) -> bool:
    """True when ``t`` is a proper rigid transform (orthonormal rotation, det +1, last row 0001)."""
    r = t[:3, :3]
    return (np.allclose(r.T @ r, np.eye(3), atol=tol) and abs(np.linalg.det(r) - 1.0) < tol
            and np.allclose(t[3], (0, 0, 0, 1), atol=tol))


def rotation_angle_between(ra: np.ndarray, rb: np.ndarray) -> float:
    """Angle (radians) of the rotation taking 3x3 ``ra`` to ``rb``."""
    c = (np.trace(ra.T @ rb) - 1.0) / 2.0
    return float(np.arccos(np.clip(c, -1.0, 1.0)))


def euler_xyz(angles_rad: tuple[float, float, float]) -> np.ndarray:
    """Rotation Rx(a) then Ry(b) then Rz(c) about fixed axes, i.e. ``Rz @ Ry @ Rx`` (4x4)."""
    a, b, c = angles_rad
    return rotation("z", c) @ rotation("y", b) @ rotation("x", a)


def close(a: np.ndarray | tuple[float, ...], b: np.ndarray | tuple[float, ...] | float, atol: float,
          rtol: float = 0.0) -> bool:
    """``np.allclose(a, b, atol=atol, rtol=rtol)`` for small arrays, without its overhead (the
    writer asks it a few times per site): ``|a - b| <= atol + rtol * |b|`` everywhere, equal
    infinities close, NaN never."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    with np.errstate(invalid="ignore", over="ignore"):
        ok = np.abs(a - b) <= (atol + rtol * np.abs(b) if rtol else atol)
        if rtol:
            ok &= np.isfinite(b)
    return bool((ok | (a == b)).all())
