"""The shoulder complex (book §2.4): clavicle and shoulder joints driven by elevation, abduction, twist.

Group angles (radians): **elevation** ϕ (0 = arm hanging, π = straight up), **abduction** θ (0 = the arm
in the body's lateral plane, +π/2 = forward) and **twist** τ (about the arm; positive = internal
rotation). **τ = 0 is the anatomical neutral rotation**: the upper arm's orientation is the pure swing
(the shortest rotation) from the zero pose (hanging, palm to the thigh, thumb forward) to the arm
direction, so a horizontal forward arm has the thumb up and a sideways arm has the palm down. With the
allocation below this is exactly ``τ_book = τ - θ_c - τ₀`` against the book's twist (τ₀ = default twist),
i.e. the shoulder's first member angle is ``τ - θ`` (checked by FK in tests/body/test_body_shoulder.py). The allocation to the clavicle (Otani, eqs 2.2-2.7, in degrees):

    ϕ_c = cos θ · β₁ + (1 - cos θ) · β₂ - 90,   θ_c = 0.2 θ,   ϕ_s = ϕ - ϕ_c,   θ_s = θ - θ_c
    β₁ = 0.2514 ϕ + 91.076 (ϕ ≤ 131.4) else -0.035 ϕ + 128.7
    β₂ = 0.21066 ϕ + 92.348 (ϕ ≤ 130) else 120

Joints, in the book's shoulder frame (x forward, y to the figure's right, z down; for the left arm that
is world x_b = +z, y_b = -x, z_b = -y; the right arm mirrors the axes):

* clavicle ``R(x_b) * R(z_b)`` with displacement ``(ϕ_c, θ_c)`` (D = R_z(θ_c) R_x(ϕ_c): the clavicle
  elevates, then swings forward about the thorax vertical). **[proposal]**: the book's form 2.18 is in a
  clavicle site frame it only shows in a figure; this order makes the arm direction exactly (ϕ, θ).
* shoulder ``R(z_b) * R(x_b) * R(z_b) * R(x_b)`` (2.21) with displacement
  ``(τ_book + (ϕ/90 - 1) θ_s, ϕ, θ_s, -ϕ_c)`` (2.23): τ₀ = (ϕ/90) θ_s removes the twist that abduction
  brings; with the anatomical zero above the first angle is ``τ - θ``.
  A joint has at most 3 DOFs here, so 2.21 is the chain ``<side>_shoulder_tilt`` (``R(x_b)``, -ϕ_c, acting
  first) to the zero-mass ``<side>_shoulder_frame`` then ``<side>_shoulder`` (``R(z_b) * R(x_b) * R(z_b)``).
  The driver's output order is clavicle (ϕ_c, θ_c), tilt (-ϕ_c), shoulder (τ - θ, ϕ, θ_s).

Limits are globographic **[proposal from AAOS ranges]**: 0 ≤ ϕ ≤ 180°, -90° ≤ θ ≤ 135°, twist -90°
(external) to 70° (internal) about the anatomical neutral (AAOS 1965: external rotation 90, internal
70); across the body elevation falls to 150° at θ = 135° (the linear row ϕ + 2/3 θ ≤ 240°). Behind
the body the boundary runs through AAOS extension (θ = -90°, ϕ = 60°), horizontal extension at 90°
elevation (θ = -45°, ϕ = 90°) and abduction (θ = 0°, ϕ = 180°); those three bend the boundary the
way no convex set can, so it is the non-convex limit ``ϕ ≤ max(120° + 2/3 θ, 180° + 2 θ)``: two
limit pieces (:attr:`ShoulderDriver.limit_pieces`, see :class:`jackpy.peabody.groups.JointGroup`),
each one row, the angles inside at least one.
"""

from __future__ import annotations

import math

import numpy as np

from jackpy.peabody.groups import JointGroup, register_driver

#: group angle names and box limits (radians)
SHOULDER_ANGLES = ("elevation", "abduction", "twist")
SHOULDER_LOWER = np.radians([0.0, -90.0, -90.0])
SHOULDER_UPPER = np.radians([180.0, 135.0, 70.0])
SHOULDER_A = np.array([[1.0, 2.0 / 3.0, 0.0]])
SHOULDER_B = np.radians([240.0])
#: the boundary behind the body as two convex pieces (ϕ - 2/3 θ ≤ 120° or ϕ - 2 θ ≤ 180°): through
#: AAOS (1965) extension 60°, horizontal extension 45° at 90° elevation, abduction 180°
SHOULDER_PIECES = ((np.array([[1.0, -2.0 / 3.0, 0.0]]), np.radians([120.0])),
                   (np.array([[1.0, -2.0, 0.0]]), np.radians([180.0])))


def allocate(phi_deg: float, theta_deg: float) -> tuple[float, float, float, float]:
    """Otani's allocation (degrees): ``(ϕ_c, θ_c, ϕ_s, θ_s)`` for total elevation and abduction."""
    b1 = 0.2514 * phi_deg + 91.076 if phi_deg <= 131.4 else -0.035 * phi_deg + 128.7
    b2 = 0.21066 * phi_deg + 92.348 if phi_deg <= 130.0 else 120.0
    c = np.cos(np.radians(theta_deg))
    phi_c = c * b1 + (1.0 - c) * b2 - 90.0
    theta_c = 0.2 * theta_deg
    return float(phi_c), float(theta_c), float(phi_deg - phi_c), float(theta_deg - theta_c)


def allocate_batch(phi_deg: np.ndarray, theta_deg: np.ndarray) -> tuple[np.ndarray, ...]:
    """:func:`allocate` over arrays (degrees, any matching shapes)."""
    phi = np.asarray(phi_deg, dtype=float)
    th = np.asarray(theta_deg, dtype=float)
    b1 = np.where(phi <= 131.4, 0.2514 * phi + 91.076, -0.035 * phi + 128.7)
    b2 = np.where(phi <= 130.0, 0.21066 * phi + 92.348, 120.0)
    c = np.cos(np.radians(th))
    phi_c = c * b1 + (1.0 - c) * b2 - 90.0
    theta_c = 0.2 * th
    return phi_c, theta_c, phi - phi_c, th - theta_c


def default_twist(phi_deg: float, theta_s_deg: float) -> float:
    """The book's default twist τ₀ = (ϕ/90) θ_s, degrees (eq. 2.17 applied to the shoulder's share, as
    in 2.23); the group's anatomical twist is ``τ = τ_book + θ_c + τ₀``."""
    return phi_deg / 90.0 * theta_s_deg


def _floats(theta: np.ndarray) -> list[float]:
    """The three group angles as Python floats (scalar math is cheaper than numpy's for three)."""
    return theta.tolist() if isinstance(theta, np.ndarray) else [float(v) for v in theta]


class ShoulderDriver:
    """Group driver: (ϕ, θ, τ) radians -> clavicle (ϕ_c, θ_c) + shoulder (4 angles), radians."""

    #: the driver kind in Peabody files (``driver = shoulder()``; jackpy.peabody.groups registry)
    kind = "shoulder"
    #: the non-convex limit behind the body (the group takes it from here, so files keep it)
    limit_pieces = SHOULDER_PIECES

    def to_dict(self) -> dict[str, float]:
        """No parameters: the allocation is the book's (eq. 2.20-2.23)."""
        return {}

    @classmethod
    def from_dict(cls, d: dict) -> ShoulderDriver:
        if d:
            raise ValueError(f"the shoulder driver has no parameters, got {sorted(d)}")
        return cls()

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        # scalar math (the IK runs this per evaluation; :func:`allocate` is the same formula)
        phi_r, th_r, tau_r = _floats(theta)
        phi = math.degrees(phi_r)
        b1 = 0.2514 * phi + 91.076 if phi <= 131.4 else -0.035 * phi + 128.7
        b2 = 0.21066 * phi + 92.348 if phi <= 130.0 else 120.0
        c = math.cos(th_r)
        phi_c = math.radians(c * b1 + (1.0 - c) * b2 - 90.0)
        return np.array([phi_c, 0.2 * th_r, -phi_c, tau_r - th_r, phi_r, 0.8 * th_r])

    def batch(self, thetas: np.ndarray) -> np.ndarray:
        """(N, 3) group angles -> (N, 6) member displacements, row ``i`` equal to ``self(thetas[i])``."""
        d = np.degrees(np.atleast_2d(np.asarray(thetas, dtype=float)))
        phi, th, tau = d[:, 0], d[:, 1], d[:, 2]
        phi_c, theta_c, _, theta_s = allocate_batch(phi, th)
        return np.radians(np.stack([phi_c, theta_c, -phi_c, tau - th, phi, theta_s], axis=1))

    def jacobian(self, theta: np.ndarray) -> np.ndarray:
        """Analytic d(member displacements)/d(ϕ, θ, τ), (6, 3).

        Degrees in and out cancel, so this is the derivative of the allocation in degrees. At the
        breakpoints of β₁ (ϕ = 131.4°) and β₂ (ϕ = 130°) it is the left-hand derivative.
        """
        phi_r, th_r, _ = _floats(theta)
        phi = math.degrees(phi_r)
        b1 = 0.2514 * phi + 91.076 if phi <= 131.4 else -0.035 * phi + 128.7
        b2 = 0.21066 * phi + 92.348 if phi <= 130.0 else 120.0
        db1 = 0.2514 if phi <= 131.4 else -0.035
        db2 = 0.21066 if phi <= 130.0 else 0.0
        c, s = math.cos(th_r), math.sin(th_r)
        a, b = c * db1 + (1.0 - c) * db2, -math.pi / 180.0 * s * (b1 - b2)
        return np.array([[a, b, 0.0], [0.0, 0.2, 0.0], [-a, -b, 0.0], [0.0, -1.0, 1.0],
                         [1.0, 0.0, 0.0], [0.0, 0.8, 0.0]])

    def numerical_jacobian(self, theta: np.ndarray, h: float = 1e-7) -> np.ndarray:
        """Central-difference Jacobian (for tests)."""
        theta = np.asarray(theta, dtype=float)
        cols = []
        for k in range(3):
            e = np.zeros(3)
            e[k] = h
            cols.append((self(theta + e) - self(theta - e)) / (2 * h))
        return np.stack(cols, axis=1)


def shoulder_group(side: str) -> JointGroup:
    """The ``<side>_shoulder_complex`` group over the clavicle, shoulder-tilt and shoulder joints."""
    return JointGroup(f"{side}_shoulder_complex",
                      [f"{side}_clavicle", f"{side}_shoulder_tilt", f"{side}_shoulder"],
                      list(SHOULDER_ANGLES), ShoulderDriver(), SHOULDER_LOWER, SHOULDER_UPPER,
                      SHOULDER_A, SHOULDER_B)


register_driver(ShoulderDriver.kind, ShoulderDriver.from_dict)
