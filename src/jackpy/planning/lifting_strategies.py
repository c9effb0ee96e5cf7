"""The path planning scheme of strength-guided motion (book §5.3.3-5.3.4): directions and joint steps.

All vectors are world metres (hand space) or radians over the *active* variables (joint space).

* :func:`project_to_cone` - the perceived-exertion cone: a direction more than ``beta`` from the
  goal axis is projected onto the cone's surface (§5.3.3; spec §2.9.3).
* :func:`weighted_step` - the joint step that moves the hand by ``dp`` with the least weighted
  joint motion, ``dx = W J^T (J W J^T + lambda^2 I)^-1 dp``: joints with a large weight (much
  torque available, §5.3.4 Available Torque: "a stiffer spring moves further") do most of the work.
* :func:`least_moment_direction` - the direction inside the cone along which the discomfort grows
  least (Reducing Moment: the ratios' gradient from virtual displacements, mapped to hand space).
"""

from __future__ import annotations

import numpy as np

#: damping (m) of the weighted least-norm step near singular arm postures
DAMPING = 0.02


def project_to_cone(v: np.ndarray, axis: np.ndarray, beta: float) -> np.ndarray:
    """Unit direction: ``v`` normalised when within ``beta`` radians of unit ``axis``, else ``v``
    projected onto the cone ``cos(beta) axis + sin(beta) w`` with ``w`` the unit part of ``v``
    normal to the axis. When ``v`` points straight away from the axis every direction on the cone is
    equally near; ``w`` is then a fixed unit normal of the axis, so the result stays on the cone."""
    n = float(np.linalg.norm(v))
    if n < 1e-12:
        return axis.copy()
    d = v / n
    c = float(d @ axis)
    if c >= np.cos(beta):
        return d
    perp = d - c * axis
    perp -= (perp @ axis) * axis  # once more: the first subtraction leaves rounding along the axis
    pn = float(np.linalg.norm(perp))
    if pn < 1e-9:
        perp = np.cross(axis, np.eye(3)[int(np.argmin(np.abs(axis)))])
        pn = float(np.linalg.norm(perp))
    out = np.cos(beta) * axis + np.sin(beta) * perp / pn
    return out / np.linalg.norm(out)


def weighted_pinv(jac: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """``W J^T (J W J^T + lambda^2 I)^-1`` (n, 3) for per-variable weights (n,) >= 0."""
    jw = jac * weights[None, :]
    a = jw @ jac.T + DAMPING ** 2 * np.eye(jac.shape[0])
    return np.linalg.solve(a, jw).T


def weighted_step(jac: np.ndarray, weights: np.ndarray, dp: np.ndarray) -> np.ndarray:
    """Joint step (n,) moving the hand by ``dp`` (3,) with the least ``W^-1``-weighted motion."""
    return weighted_pinv(jac, weights) @ dp


def least_moment_direction(jac: np.ndarray, weights: np.ndarray, grad: np.ndarray, axis: np.ndarray,
                           beta: float) -> np.ndarray:
    """The unit hand direction within ``beta`` of ``axis`` whose weighted joint step raises the
    discomfort least: ``-G`` projected onto the cone, ``G = (J^+)^T grad`` the discomfort gradient in
    hand space (``grad``: d discomfort / d x_active)."""
    g_hand = weighted_pinv(jac, weights).T @ grad
    return project_to_cone(-g_hand, axis, beta)


def availability(ratios: np.ndarray, limit: float, floor: float) -> np.ndarray:
    """Normalised torque availability per monitored DOF, ``(limit·S - |tau|) / (limit·S)`` =
    ``1 - r / limit`` clipped to ``[floor, 1]`` (§5.3.4: effective maximum strength less the torque
    now required)."""
    return np.clip(1.0 - ratios / max(limit, 1e-9), floor, 1.0)
