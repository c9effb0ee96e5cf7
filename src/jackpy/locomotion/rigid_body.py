"""A single rigid body (Sims 7.1 with the digest's fixes, §5.1): full 3x3 inertia tensor, torque
``tau = sum L_i x F_i``, world angular momentum as the rotational state (so a torque-free body
conserves it exactly), and per step constant accelerations: ``P' = P + V dt + A dt^2 / 2``,
``V' = V + A dt`` (exact under gravity alone), ``L' = L + tau dt``, ``omega = I_w^-1 L``,
``R' = Rot(omega dt) R`` (omega in world coordinates, so pre-multiplied). Metres, kilograms,
seconds; y up, ``g = 9.81 m/s^2``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

G = np.array([0.0, -9.81, 0.0])


def rotation(rotvec: np.ndarray) -> np.ndarray:
    """Rodrigues' rotation by ``|rotvec|`` about ``rotvec`` (digest §3.3, replacing A.3)."""
    th = float(np.linalg.norm(rotvec))
    if th < 1e-15:
        return np.eye(3)
    k = rotvec / th
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(th) * K + (1 - np.cos(th)) * (K @ K)


def point_mass_inertia(masses: np.ndarray, points: np.ndarray) -> np.ndarray:
    """``I = sum m_i (|r_i|^2 E - r_i r_i^T)`` about the masses' centre (eq. 7.10 as a tensor:
    ``n^T I n = sum m_i |n x r_i|^2``)."""
    m = np.asarray(masses, float)
    r = np.asarray(points, float) - (m[:, None] * points).sum(axis=0) / m.sum()
    return np.einsum("i,ij->", m, r * r) * np.eye(3) - np.einsum("i,ij,ik->jk", m, r, r)


class RigidBody:
    """Mass ``mass``, body-frame inertia ``inertia`` about the COM; state ``P`` (COM, world),
    ``R`` (body to world), ``V``, ``L`` (world angular momentum)."""

    def __init__(self, mass: float, inertia: np.ndarray, P: Sequence[float], R: np.ndarray | None = None,
                 V: Sequence[float] = (0.0, 0.0, 0.0), omega: Sequence[float] = (0.0, 0.0, 0.0)) -> None:
        if not mass > 0:
            raise ValueError(f"mass must be > 0, not {mass}")
        self.mass = float(mass)
        self.inertia = np.asarray(inertia, float).reshape(3, 3)
        self.inertia_inv = np.linalg.inv(self.inertia)
        self.P = np.asarray(P, float).copy()
        self.R = np.eye(3) if R is None else np.asarray(R, float).copy()
        self.V = np.asarray(V, float).copy()
        self.L = self.world_inertia() @ np.asarray(omega, float)

    def world_inertia(self) -> np.ndarray:
        return self.R @ self.inertia @ self.R.T

    @property
    def omega(self) -> np.ndarray:
        return self.R @ (self.inertia_inv @ (self.R.T @ self.L))

    def point_velocity(self, p: np.ndarray) -> np.ndarray:
        return self.V + np.cross(self.omega, np.asarray(p, float) - self.P)

    def energy(self) -> float:
        """Kinetic plus gravitational potential energy (J, zero height at y = 0)."""
        return float(0.5 * self.mass * self.V @ self.V + 0.5 * self.omega @ self.L - self.mass * G[1] * self.P[1])

    def step(self, dt: float, forces: Sequence[tuple[np.ndarray, np.ndarray]] = ()) -> None:
        """Advance ``dt`` s under gravity and ``forces`` = [(F world N, application point world m)]."""
        F = np.zeros(3)
        tau = np.zeros(3)
        for f, p in forces:
            f = np.asarray(f, float)
            F += f
            tau += np.cross(np.asarray(p, float) - self.P, f)
        A = F / self.mass + G
        self.P = self.P + self.V * dt + 0.5 * A * dt * dt
        self.V = self.V + A * dt
        self.L = self.L + tau * dt
        self.R = rotation(self.omega * dt) @ self.R
        u, _, vt = np.linalg.svd(self.R)  # keep R orthonormal
        self.R = u @ vt

    def apply_impulse(self, J: np.ndarray, p: np.ndarray) -> None:
        """An instantaneous impulse ``J`` (N s) at world point ``p``."""
        self.V = self.V + np.asarray(J, float) / self.mass
        self.L = self.L + np.cross(np.asarray(p, float) - self.P, J)
