"""The one-euro filter (Casiez, Roussel & Vogel, CHI 2012) for positions and poses.

A low-pass filter whose cut-off rises with speed: little jitter at rest, little lag when moving.
``min_cutoff`` (Hz) sets smoothing at rest, ``beta`` (s/m for positions) how fast the cut-off
grows with speed, ``d_cutoff`` (Hz) the smoothing of the speed estimate. Time in seconds.
"""

from __future__ import annotations

import math

import numpy as np

from jackpy.devices.flock.protocol import matrix_to_quaternion, quaternion_to_matrix
from jackpy.errors import DeviceError


def _alpha(cutoff: float, dt: float) -> float:
    tau = 1.0 / (2.0 * math.pi * cutoff)
    return 1.0 / (1.0 + tau / dt)


class OneEuroFilter:
    """One-euro filter of a scalar or vector signal (any numpy shape)."""

    def __init__(self, min_cutoff: float = 1.0, beta: float = 0.0, d_cutoff: float = 1.0) -> None:
        if min_cutoff <= 0 or d_cutoff <= 0 or beta < 0:
            raise DeviceError("one-euro filter needs min_cutoff > 0, d_cutoff > 0, beta >= 0")
        self.min_cutoff, self.beta, self.d_cutoff = min_cutoff, beta, d_cutoff
        self._x: np.ndarray | None = None
        self._dx: np.ndarray | None = None
        self._t = 0.0

    def __call__(self, x, t: float) -> np.ndarray:
        """Filtered value of sample ``x`` taken at time ``t`` (seconds, increasing)."""
        x = np.asarray(x, dtype=float)
        if self._x is None or t <= self._t:
            if self._x is None:
                self._x, self._dx = x.copy(), np.zeros_like(x)
                self._t = t
            return self._x.copy()
        dt = t - self._t
        dx = (x - self._x) / dt
        self._dx = self._dx + _alpha(self.d_cutoff, dt) * (dx - self._dx)
        speed = float(np.linalg.norm(self._dx))
        a = _alpha(self.min_cutoff + self.beta * speed, dt)
        self._x = self._x + a * (x - self._x)
        self._t = t
        return self._x.copy()


class OneEuroPoseFilter:
    """One-euro filter of a 4×4 rigid transform: position as a vector, orientation by slerp
    with an alpha driven by the angular speed (rad/s, scaled by ``beta_rot``)."""

    def __init__(self, min_cutoff: float = 1.0, beta: float = 0.5, beta_rot: float = 0.1,
                 d_cutoff: float = 1.0) -> None:
        self.position = OneEuroFilter(min_cutoff, beta, d_cutoff)
        self.min_cutoff, self.beta_rot, self.d_cutoff = min_cutoff, beta_rot, d_cutoff
        self._q: np.ndarray | None = None
        self._w = 0.0
        self._t = 0.0

    def __call__(self, pose: np.ndarray, t: float) -> np.ndarray:
        """Filtered pose (4×4) of ``pose`` sampled at ``t`` seconds."""
        q = matrix_to_quaternion(pose[:3, :3])
        out = np.eye(4)
        out[:3, 3] = self.position(pose[:3, 3], t)
        if self._q is None or t <= self._t:
            if self._q is None:
                self._q, self._t = q, t
            out[:3, :3] = quaternion_to_matrix(self._q)
            return out
        dt = t - self._t
        if np.dot(q, self._q) < 0:
            q = -q
        angle = 2.0 * math.acos(min(1.0, abs(float(np.dot(q, self._q)))))
        self._w += _alpha(self.d_cutoff, dt) * (angle / dt - self._w)
        a = _alpha(self.min_cutoff + self.beta_rot * self._w, dt)
        self._q = _slerp(self._q, q, a)
        self._t = t
        out[:3, :3] = quaternion_to_matrix(self._q)
        return out


def _slerp(q0: np.ndarray, q1: np.ndarray, a: float) -> np.ndarray:
    d = float(np.clip(np.dot(q0, q1), -1.0, 1.0))
    if d > 0.9995:
        q = q0 + a * (q1 - q0)
    else:
        th = math.acos(d)
        q = (math.sin((1 - a) * th) * q0 + math.sin(a * th) * q1) / math.sin(th)
    return q / np.linalg.norm(q)
