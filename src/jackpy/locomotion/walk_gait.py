"""Procedural kinematic human gait ([SH5] §5.2.1; digest §2.8.2, §6.1 item 4).

The gait is a set of **profiles over one step** (heel strike to heel strike), all from the figure's
size: step length and frequency scale with the hip height ``H`` (Froude similarity, ``v ∝ √H``),
double support and swing are fractions of the cycle, the pelvis height follows Boulic's
``O_s(t) = −0.015·RV + 0.015·RV·sin(2π(2t − 0.35))`` (in hip heights, ``RV`` = speed in hip
heights per second, ``t`` the cycle fraction from heel strike), the swing ankle rises on a
``sin(πu)`` bump, the foot rolls about the heel after heel strike and about the ball of the foot
before toe-off, and the arms swing opposite the legs.

:mod:`.walk_path` applies these profiles to any planar footstep sequence and
:mod:`.walk_solve` turns the targets into postures with :mod:`jackpy.ik`.

Frames: world, metres, y up; a heading ``psi`` is the yaw of the walking direction
``(sin psi, 0, cos psi)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

#: reference values for the 50th-percentile man ([SH5] §5.2.1 defaults; issue 13)
REF_SPEED = 1.3  # m/s
REF_STEP = 0.70  # m
#: fractions of the gait cycle (Perry's normal gait: stance 60 %, swing 40 %, two 10 % double supports)
DOUBLE_SUPPORT = 0.10
#: foot-floor angle at heel strike (toe up) and at toe-off (heel up, about the ball), rad
PITCH_HS = np.radians(-10.0)
PITCH_TO = np.radians(45.0)
#: cycle fractions: foot flat after heel strike, heel-off before the other foot's heel strike
FOOT_FLAT = 0.08
HEEL_OFF = 0.38
#: lowest sole point above the floor at mid-swing (m) and the lateral pelvis sway (m) for H_REF
#: (the sway puts the COM 2.1 cm toward the stance foot: Orendurff et al. 2004 measured a 4-5 cm
#: peak-to-peak mediolateral COM excursion at 1.3 m/s)
MID_SWING_CLEARANCE = 0.025
SWAY = 0.025
#: fraction of a step (from heel strike) where the sway crosses the centre line: mid double support
SWAY_CROSSING = DOUBLE_SUPPORT
#: step width for H_REF: ankle centre to ankle centre of walking footsteps (m); normal adult gait
#: walks on a base of 7-12 cm, narrower than the standing feet (17 cm, the hips' width)
STEP_WIDTH = 0.10
#: arm swing amplitude at the shoulder (rad) for the reference speed
ARM_SWING = np.radians(16.0)
#: fraction of the swing over which the toes, bent at toe-off, straighten
TOES_RELEASE = 0.3
#: standing still before the first step and after the last (s): weight shift, settle
START_TIME = 0.35
STOP_TIME = 0.45
#: the legs may stretch to this fraction of their standing hip-ankle length
MAX_LEG = 0.995
#: the most the heel is raised to keep the ankle within reach (rad)
MAX_PITCH = np.radians(55.0)
SIDES = ("left", "right")
GRAVITY = 9.81  # m/s²


def smooth(u: np.ndarray | float) -> np.ndarray | float:
    """Minimum-jerk progress 0 → 1 (zero velocity and acceleration at both ends)."""
    u = np.clip(u, 0.0, 1.0)
    return u * u * u * (10.0 - 15.0 * u + 6.0 * u * u)


def rot_y(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_x(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


@dataclass
class FootGeometry:
    """A foot in its own floor frame (origin: the ankle's floor point, z forward, y up; m)."""

    ankle: np.ndarray
    heel: np.ndarray
    ball: np.ndarray
    toe: np.ndarray
    tip: np.ndarray
    mtp: np.ndarray  # the ball-of-foot joint (the toes' base), the pivot of the heel-up roll
    width: float  # lateral distance of the ankle from the pelvis centre (m)

    def sole(self) -> np.ndarray:
        """The sole sites (heel, ball, toe, toe tip) as rows."""
        return np.array([self.heel, self.ball, self.toe, self.tip])


@dataclass
class GaitParams:
    """Gait of one figure: step length (m), step frequency (steps/s), hip height (m) ..."""

    hip_height: float
    leg_length: float  # hip to ankle, standing (m)
    step_length: float
    step_frequency: float
    hip_half_width: float  # λ: pelvis centre to a hip (m)
    foot: FootGeometry
    step_half_width: float = 0.5 * STEP_WIDTH  # walking footstep ankle to the centre line (m)
    clearance: float = MID_SWING_CLEARANCE
    sway: float = SWAY
    arm_swing: float = ARM_SWING
    banking: bool = True  # lean into turns by eq. (5.13) (off: the unbanked walk, for comparison)
    extra: dict = field(default_factory=dict)

    @property
    def speed(self) -> float:
        return self.step_length * self.step_frequency

    @property
    def step_time(self) -> float:
        return 1.0 / self.step_frequency

    @classmethod
    def for_figure(cls, figure, speed_scale: float = 1.0) -> "GaitParams":
        """Defaults scaled from the reference man by the figure's hip height ``H`` (standing):
        step ∝ H, speed ∝ √H (equal Froude number), so frequency ∝ 1/√H."""
        H_ref = reference_hip_height()
        H, L, lam, foot = measure(figure)
        step = REF_STEP * H / H_ref
        speed = REF_SPEED * np.sqrt(H / H_ref) * speed_scale
        k = H / H_ref
        half_width = min(0.5 * STEP_WIDTH * k, foot.width)
        return cls(H, L, step, speed / step, lam, foot, half_width, MID_SWING_CLEARANCE, SWAY * k, ARM_SWING)


_REF_H: list[float] = []


def reference_hip_height() -> float:
    """The standing hip height of the standard 50th-percentile man (m), measured once."""
    if not _REF_H:
        from jackpy.motion import cast

        _REF_H.append(measure(cast.make_figure("ref", {"human": "male:50"}))[0])
    return _REF_H[0]


def measure(figure) -> tuple[float, float, float, FootGeometry]:
    """Hip height above the floor, hip-ankle length, λ and the left foot's geometry, measured on
    the figure standing in its neutral posture (temporarily)."""
    q, loc = figure.q, figure.location.copy()
    try:
        figure.q = np.zeros_like(q)
        figure.location = np.eye(4)  # measured facing +z wherever the figure stands
        w = lambda seg, site: figure.site_world(seg, site)[:3, 3]  # noqa: E731
        floor = min(w("left_foot", "heel")[1], w("left_foot", "ball")[1])
        hip = w("pelvis", "left_hip")
        centre = w("pelvis", "centre")
        ankle = w("left_shank", "ankle")
        # foot floor frame: origin under the ankle, world-aligned axes rotated to the foot's forward
        fwd = w("left_foot", "toe") - w("left_foot", "heel")
        fwd[1] = 0.0
        fwd /= np.linalg.norm(fwd)
        lat = np.cross([0.0, 1.0, 0.0], fwd)
        o = np.array([ankle[0], floor, ankle[2]])
        R = np.column_stack([lat, [0.0, 1.0, 0.0], fwd])

        def local(p: np.ndarray) -> np.ndarray:
            return R.T @ (p - o)

        foot = FootGeometry(local(ankle), local(w("left_foot", "heel")), local(w("left_foot", "ball")),
                            local(w("left_foot", "toe")), local(w("left_toes", "tip")), local(w("left_toes", "base")),
                            float(abs(ankle[0] - centre[0])))
        return (float(hip[1] - floor), float(np.linalg.norm(hip - ankle)), float(abs(hip[0] - centre[0])), foot)
    finally:
        figure.q = q
        figure.location = loc


# --------------------------------------------------------------------------------------------
# profiles over a step (shared by the 1-D walk and the 2-D layer)

def pelvis_drop(p: GaitParams, cycle_t: float) -> float:
    """Boulic's vertical waist offset (m, ≤ 0) at cycle fraction ``cycle_t`` from a heel strike."""
    rv = p.speed / p.hip_height
    return p.hip_height * (-0.015 * rv + 0.015 * rv * np.sin(2.0 * np.pi * (2.0 * cycle_t - 0.35)))


def swing_pitch(u: float, start_pitch: float, end_pitch: float = PITCH_HS) -> float:
    """Foot pitch during swing (``u`` ∈ [0, 1] from toe-off to heel strike)."""
    return (1.0 - float(smooth(u))) * start_pitch + float(smooth(u)) * end_pitch


def swing_progress(u: float) -> float:
    """Fraction of the swing ankle's horizontal travel done at swing fraction ``u``."""
    return float(smooth(u))


def foot_transform(p: GaitParams, x: float, z: float, psi: float, pitch: float, side: str) -> np.ndarray:
    """World 4x4 of a foot's floor frame (ankle floor point at ``(x, 0, z)`` when flat, heading
    ``psi``) pitched about its heel (``pitch`` < 0) or the ball-of-foot joint (> 0)."""
    f = p.foot
    mirror = np.diag([-1.0 if side == "right" else 1.0, 1.0, 1.0])
    pivot = f.heel if pitch < 0 else f.mtp
    pivot = mirror @ pivot
    T = np.eye(4)
    R = rot_y(psi)
    Rp = rot_x(pitch)
    T[:3, :3] = R @ Rp
    T[:3, 3] = np.array([x, 0.0, z]) + R @ (pivot - Rp @ pivot)
    return T


def toes_flat_tip(p: GaitParams, T: np.ndarray, side: str) -> np.ndarray:
    """World toe tip of a foot at floor frame ``T`` whose toes lie flat (bent at the ball joint)."""
    mirror = np.array([-1.0 if side == "right" else 1.0, 1.0, 1.0])
    mtp, tip = p.foot.mtp * mirror, p.foot.tip * mirror
    fwd = T[:3, 2].copy()
    yaw = float(np.arctan2(fwd[0], fwd[2]))
    R = rot_y(yaw)
    m = T[:3, :3] @ mtp + T[:3, 3]
    return m + R @ (tip - mtp)


def swing_lift(p: GaitParams, start_pitch: float, end_pitch: float = PITCH_HS) -> float:
    """Ankle lift (m) of the ``sin(πu)`` swing bump: the lowest sole point clears the floor by
    ``p.clearance`` at mid-swing and stays above it over the swing (41 samples checked)."""
    key = ("lift", round(float(start_pitch), 9), round(float(end_pitch), 9))
    if key in p.extra:
        return p.extra[key]
    T0 = foot_transform(p, 0.0, 0.0, 0.0, start_pitch, "left")
    T1 = foot_transform(p, 0.0, 0.0, 0.0, end_pitch, "left")
    a0, a1 = T0[:3, :3] @ p.foot.ankle + T0[:3, 3], T1[:3, :3] @ p.foot.ankle + T1[:3, 3]
    sole = p.foot.sole().T
    lift = p.clearance
    for _ in range(100):
        ok = True
        for u in np.linspace(0.0, 1.0, 41)[1:-1]:
            T = foot_transform(p, 0.0, 0.0, 0.0, swing_pitch(u, start_pitch, end_pitch), "left")
            a = T[:3, :3] @ p.foot.ankle + T[:3, 3]
            y = a0[1] + float(smooth(u)) * (a1[1] - a0[1]) + lift * np.sin(np.pi * u)
            pts = sole if u >= 0.5 * TOES_RELEASE else sole[:, :2]  # bent toes: held on their own goal
            low = float(np.min((T[:3, :3] @ pts)[1] + T[1, 3] + (y - a[1])))
            if low < (p.clearance if abs(u - 0.5) < 1e-9 else 0.0):
                ok = False
                break
        if ok:
            break
        lift += 0.002
    p.extra[key] = lift
    return lift
