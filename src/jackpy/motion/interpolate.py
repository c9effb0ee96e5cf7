"""Interpolation of goal targets: points (lerp, Catmull-Rom cubic), rotations (quaternion slerp,
weighted mean) and poses (4x4: position and rotation separately). Rotations are 3x3 world
matrices; quaternions (w, x, y, z)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.spatial.transform import Rotation, Slerp


def lerp(a: np.ndarray, b: np.ndarray, s: float) -> np.ndarray:
    """Linear interpolation of arrays, s in [0, 1]."""
    return (1.0 - s) * np.asarray(a, dtype=float) + s * np.asarray(b, dtype=float)


def slerp(ra: np.ndarray, rb: np.ndarray, s: float) -> np.ndarray:
    """Spherical interpolation of 3x3 rotations (the shorter arc)."""
    rots = Rotation.from_matrix(np.stack([ra, rb]))
    return Slerp([0.0, 1.0], rots)([float(s)]).as_matrix()[0]


def pose_lerp(pa: np.ndarray, pb: np.ndarray, s: float) -> np.ndarray:
    """4x4 pose between ``pa`` and ``pb``: position lerp, rotation slerp."""
    out = np.eye(4)
    out[:3, :3] = slerp(pa[:3, :3], pb[:3, :3], s)
    out[:3, 3] = lerp(pa[:3, 3], pb[:3, 3], s)
    return out


def mean_rotation(rots: Sequence[np.ndarray], weights: Sequence[float]) -> np.ndarray:
    """Weighted mean of 3x3 rotations (Markley's quaternion average); equal weights if all are 0."""
    w = np.asarray(weights, dtype=float)
    if not np.any(w > 0):
        w = np.ones(len(rots))
    return Rotation.from_matrix(np.stack(rots)).mean(w).as_matrix()


def mean_pose(poses: Sequence[np.ndarray], weights: Sequence[float]) -> np.ndarray:
    """Weighted mean of 4x4 poses (positions averaged, rotations by :func:`mean_rotation`)."""
    w = np.asarray(weights, dtype=float)
    if not np.any(w > 0):
        w = np.ones(len(poses))
    out = np.eye(4)
    out[:3, 3] = np.einsum("i,ij->j", w, np.stack([p[:3, 3] for p in poses])) / w.sum()
    out[:3, :3] = mean_rotation([p[:3, :3] for p in poses], w)
    return out


def mean_array(values: Sequence[np.ndarray], weights: Sequence[float]) -> np.ndarray:
    """Weighted mean of arrays; equal weights if all are 0."""
    w = np.asarray(weights, dtype=float)
    if not np.any(w > 0):
        w = np.ones(len(values))
    return np.tensordot(w, np.stack([np.asarray(v, dtype=float) for v in values]), axes=1) / w.sum()


def catmull_rom(p0: np.ndarray, p1: np.ndarray, p2: np.ndarray, p3: np.ndarray, s: float) -> np.ndarray:
    """Uniform Catmull-Rom cubic between ``p1`` (s = 0) and ``p2`` (s = 1)."""
    s2, s3 = s * s, s * s * s
    return 0.5 * ((2.0 * p1) + (-p0 + p2) * s + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * s2
                  + (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * s3)
