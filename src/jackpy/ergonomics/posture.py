"""Posture measurements for the assessments, taken from the figure's world transforms.

Every angle is in degrees, in the frame its docstring names; a measurement never reads joint
displacements, so it works for any pose the IK, behaviors or a motion produce.

Frames (the standard human of :func:`jackpy.body.make_human`; zero pose: every segment frame parallel
to the world, x to the figure's left, y up, z forward):

* **body frame**: up = world +y (against gravity), left = the pelvis's x axis (the hip axis)
  projected on the horizontal plane, forward = left x up.
* **thorax frame**: the world rotation of segment ``t1`` (the upper thoracic vertebra that carries the
  clavicles and the neck).
* **forearm frame**: segment ``<side>_forearm_distal`` (after the forearm's twist joints).

The trunk line runs from the L5/S1 joint centre (origin of ``l5``) to the C7/T1 joint centre (origin of
``neck``); it is vertical in the zero pose.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import asdict, dataclass

import numpy as np

from jackpy.errors import FigureError
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

SIDES = ("left", "right")
_SIGN = {"left": 1.0, "right": -1.0}
_FINGERS = ("index", "middle", "ring", "little")
#: segments the measurements need (the standard human's names)
REQUIRED_SEGMENTS = ("pelvis", "l5", "t1", "neck", "head") + tuple(
    f"{s}_{p}" for s in SIDES for p in ("clavicle", "upper_arm", "forearm", "forearm_distal", "palm",
                                          "thigh", "shank", "foot"))


@dataclass
class ArmAngles:
    """One arm (degrees).

    In the thorax frame: ``upper_arm_flexion`` is the upper arm's angle from hanging in the thorax's
    sagittal plane (its projection on it; + forward, - extension behind the trunk; in (-90, 270], 180 =
    straight up);
    ``upper_arm_abduction`` the angle of the upper arm out of that plane (+ away from the body);
    ``shoulder_elevation`` the angle of the clavicle (sterno-clavicular joint to shoulder joint centre)
    above the thorax's transverse plane; ``forearm_out`` the forearm's angle out of the sagittal
    plane (+ lateral). ``elbow_flexion``: 180° minus the angle at the elbow between the upper arm and
    the forearm (0 straight). In the forearm frame: ``wrist_flexion`` (+ palm-ward, - extension) and
    ``wrist_deviation`` (+ radial, - ulnar) of the hand's long axis (wrist to middle finger) and
    ``forearm_pronation`` (+ pronation, - supination; 0 = thumb forward with the arm hanging) of the
    distal forearm against the elbow segment. ``hand_across_midline_m``: how far the wrist lies past
    the thorax's midsagittal plane toward the other side (m, 0 if it does not).
    ``wrist_height_m``, ``elbow_height_m``, ``shoulder_height_m``: world heights (m)."""

    upper_arm_flexion: float
    upper_arm_abduction: float
    shoulder_elevation: float
    elbow_flexion: float
    forearm_out: float
    wrist_flexion: float
    wrist_deviation: float
    forearm_pronation: float
    hand_across_midline_m: float
    wrist_height_m: float
    elbow_height_m: float
    shoulder_height_m: float


@dataclass
class Posture:
    """The measured posture (degrees; metres where named).

    Body frame: ``trunk_flexion`` (the trunk line's angle from vertical in the body's sagittal plane,
    + forward), ``trunk_side_bend`` (its angle out of that plane, + to the figure's left),
    ``trunk_twist`` (thorax against pelvis about the trunk line: the angle between their lateral
    axes, + shoulders turned to the left). Thorax frame: ``neck_flexion`` (the head's up axis in the
    thorax's sagittal plane, + forward, - extension), ``neck_side_bend`` (+ left), ``neck_twist``
    (head's forward axis about the thorax's vertical, + to the left). Per leg: ``knee_flexion``
    (180° minus the hip-knee-ankle angle) and ``hip_flexion`` (thigh against the trunk line in the
    body's sagittal plane, + forward); ``foot_height_m`` of the lowest heel/ball/toe site above the
    lowest of all of them, ``knee_height_m`` above that floor. ``hands_*``: the midpoint between the
    two grip sites in the world (m) and ``ankles_mid`` the midpoint of the ankle joint centres;
    ``forward`` / ``left``: the body frame's horizontal axes (unit world vectors)."""

    trunk_flexion: float
    trunk_side_bend: float
    trunk_twist: float
    neck_flexion: float
    neck_side_bend: float
    neck_twist: float
    arms: dict[str, ArmAngles]
    knee_flexion: dict[str, float]
    hip_flexion: dict[str, float]
    foot_height_m: dict[str, float]
    knee_height_m: dict[str, float]
    floor_m: float
    hands_mid: np.ndarray
    grips: dict[str, np.ndarray]
    ankles_mid: np.ndarray
    forward: np.ndarray
    left: np.ndarray

    FRAME = ("body frame: up = world +y, left = pelvis x (hip axis) projected on the floor; thorax frame: segment t1; "
             "forearm frame: <side>_forearm_distal; degrees")

    def finger_flexion(self, side: str) -> float:
        """Mean MCP + PIP flexion of the four fingers of ``side`` (the angle between the palm's long
        axis and each middle phalanx, degrees); measured on first use."""
        cache = self.__dict__.setdefault("_fingers", {})
        if side not in cache:
            cache[side] = _finger_flexion(self.__dict__["_frames"], side)
        return cache[side]

    def feet_bearing(self) -> list[str]:
        """The sides whose foot touches the floor (within :data:`constants.FOOT_CONTACT_M`)."""
        from jackpy.ergonomics.constants import FOOT_CONTACT_M

        return [s for s in SIDES if self.foot_height_m[s] <= FOOT_CONTACT_M]

    def to_dict(self) -> dict:
        """Angles and heights as a JSON-ready dict (no vectors)."""
        d = {k: v for k, v in asdict(self).items()
             if k not in ("arms", "hands_mid", "grips", "ankles_mid", "forward", "left")}
        d["arms"] = {s: asdict(a) for s, a in self.arms.items()}
        d["frame"] = self.FRAME
        return d


class _Frames:
    """World transforms of the segments a measurement needs, from one forward pass, as nested lists
    (the measurement is a few hundred scalar operations: plain floats beat numpy on 3-vectors)."""

    #: per flattened tree (rebuilt by the figure whenever its sites or topology change)
    _plans: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()

    def __init__(self, figure: Figure, fk: FKResult | None) -> None:
        kin = figure.kinematics()
        plan = self._plans.get(kin)
        if plan is None:
            plan = self._plan(figure, kin)
        if fk is None:
            fk = kin.forward(figure.q, figure.location)
        idx, self.slot, self.sites = plan
        self.M = fk.segments[idx].tolist()

    @classmethod
    def _plan(cls, figure: Figure, kin) -> tuple:
        missing = [s for s in REQUIRED_SEGMENTS if s not in kin.segment_index]
        if missing:
            raise FigureError(f"figure {figure.name!r} is not a standard human (no segment {missing[0]!r}); "
                              "the ergonomic assessments measure jackpy.body.make_human figures")
        fingers = [f"{s}_{f}_2" for s in SIDES for f in _FINGERS if f"{s}_{f}_2" in kin.segment_index]
        names = list(REQUIRED_SEGMENTS) + fingers
        sites = {}
        for s in SIDES:
            for n in ("heel", "ball", "toe"):
                sites[(f"{s}_foot", n)] = figure.site_location(f"{s}_foot", n)[:3, 3].tolist()
            sites[(f"{s}_palm", "grip")] = figure.site_location(f"{s}_palm", "grip")[:3, 3].tolist()
        for f in fingers:
            sites[(f, "tip")] = figure.site_location(f, "tip")[:3, 3].tolist()
        plan = (np.array([kin.segment_index[n] for n in names]), {n: k for k, n in enumerate(names)}, sites)
        cls._plans[kin] = plan
        return plan

    def p(self, seg: str) -> list[float]:
        m = self.M[self.slot[seg]]
        return [m[0][3], m[1][3], m[2][3]]

    def col(self, seg: str, j: int) -> list[float]:
        m = self.M[self.slot[seg]]
        return [m[0][j], m[1][j], m[2][j]]

    def rot(self, seg: str) -> list[list[float]]:
        m = self.M[self.slot[seg]]
        return [m[0][:3], m[1][:3], m[2][:3]]

    def has(self, seg: str) -> bool:
        return seg in self.slot

    def site(self, seg: str, site: str) -> list[float]:
        m = self.M[self.slot[seg]]
        x, y, z = self.sites[(seg, site)]
        return [m[r][0] * x + m[r][1] * y + m[r][2] * z + m[r][3] for r in range(3)]


def _sub(a: list[float], b: list[float]) -> list[float]:
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def _dot(a: list[float], b: list[float]) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _norm(a: list[float]) -> float:
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def _cross(a: list[float], b: list[float]) -> list[float]:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _tmul(r: list[list[float]], v: list[float]) -> list[float]:
    """``R^T v`` for a rotation given by rows."""
    return [r[0][c] * v[0] + r[1][c] * v[1] + r[2][c] * v[2] for c in range(3)]


def _asin_deg(x: float) -> float:
    return math.degrees(math.asin(min(1.0, max(-1.0, x))))


def _angle(a: list[float], b: list[float]) -> float:
    c = _dot(a, b) / (_norm(a) * _norm(b))
    return math.degrees(math.acos(min(1.0, max(-1.0, c))))


def _flexion_range(a: float) -> float:
    """Arm flexion in (-90, 270]: an arm straight up is 180° (not -180°); the shoulder cannot extend
    past 90° behind the trunk."""
    return a + 360.0 if a <= -90.0 else a


def _finger_flexion(fr: _Frames, side: str) -> float:
    """Mean over the four fingers of the angle between the palm's long axis and the middle
    phalanx (MCP + PIP flexion together), degrees; 0 for a hand without fingers."""
    palm = [-x for x in fr.col(f"{side}_palm", 1)]
    out = []
    for f in _FINGERS:
        name = f"{side}_{f}_2"
        if not fr.has(name):
            return 0.0
        out.append(_angle(palm, _sub(fr.site(name, "tip"), fr.p(name))))
    return sum(out) / len(out)


def _arm(fr: _Frames, side: str, thorax: list[list[float]]) -> ArmAngles:
    s = _SIGN[side]
    sh, el, wr = fr.p(f"{side}_upper_arm"), fr.p(f"{side}_forearm"), fr.p(f"{side}_palm")
    u = _tmul(thorax, _sub(el, sh))
    w = _tmul(thorax, _sub(wr, el))
    c = _tmul(thorax, _sub(sh, fr.p(f"{side}_clavicle")))
    fd = fr.rot(f"{side}_forearm_distal")
    hand = _tmul(fd, [-x for x in fr.col(f"{side}_palm", 1)])
    twist = _tmul(fr.rot(f"{side}_forearm"), fr.col(f"{side}_forearm_distal", 0))
    mid = _tmul(thorax, _sub(wr, fr.p("t1")))
    return ArmAngles(
        upper_arm_flexion=_flexion_range(math.degrees(math.atan2(u[2], -u[1]))),
        upper_arm_abduction=_asin_deg(s * u[0] / _norm(u)),
        shoulder_elevation=_asin_deg(c[1] / _norm(c)),
        elbow_flexion=_angle(u, w),
        forearm_out=_asin_deg(s * w[0] / _norm(w)),
        wrist_flexion=math.degrees(math.atan2(-s * hand[0], -hand[1])),
        wrist_deviation=math.degrees(math.atan2(hand[2], -hand[1])),
        forearm_pronation=math.degrees(math.atan2(s * twist[2], twist[0])),
        hand_across_midline_m=max(0.0, -s * mid[0]),
        wrist_height_m=wr[1], elbow_height_m=el[1], shoulder_height_m=sh[1],
    )


def measure(figure: Figure, fk: FKResult | None = None) -> Posture:
    """Measure ``figure``'s current posture (or the one ``fk`` holds); see :class:`Posture`."""
    fr = _Frames(figure, fk)
    up = [0.0, 1.0, 0.0]
    left = fr.col("pelvis", 0)
    left[1] = 0.0  # the hip axis stays level however far the pelvis pitches
    if _norm(left) < 1e-6:  # pelvis rolled on its side: fall back on its forward axis
        left = _cross(up, fr.col("pelvis", 2))
    n = _norm(left)
    left = [x / n for x in left]
    fwd = _cross(left, up)
    # trunk
    trunk = _sub(fr.p("neck"), fr.p("l5"))
    tl = _norm(trunk)
    trunk_flex = math.degrees(math.atan2(_dot(trunk, fwd), trunk[1]))
    trunk_side = _asin_deg(_dot(trunk, left) / tl)
    axis = [x / tl for x in trunk]
    thorax = fr.rot("t1")
    tx, px = fr.col("t1", 0), fr.col("pelvis", 0)
    ta, pa = _dot(tx, axis), _dot(px, axis)
    a = [tx[i] - ta * axis[i] for i in range(3)]
    b = [px[i] - pa * axis[i] for i in range(3)]
    twist = math.degrees(math.atan2(_dot(_cross(b, a), axis), _dot(a, b)))
    # neck: head against thorax
    hu = _tmul(thorax, fr.col("head", 1))
    hf = _tmul(thorax, fr.col("head", 2))
    neck_flex = math.degrees(math.atan2(hu[2], hu[1]))
    neck_side = _asin_deg(hu[0])
    neck_twist = math.degrees(math.atan2(hf[0], hf[2]))
    arms = {s: _arm(fr, s, thorax) for s in SIDES}
    # legs
    lows = {s: min(fr.site(f"{s}_foot", n)[1] for n in ("heel", "ball", "toe")) for s in SIDES}
    floor = min(lows.values())
    knee, hip, knee_h = {}, {}, {}
    for s in SIDES:
        h, k, an = fr.p(f"{s}_thigh"), fr.p(f"{s}_shank"), fr.p(f"{s}_foot")
        thigh = _sub(k, h)
        knee[s] = _angle(thigh, _sub(an, k))
        hip[s] = math.degrees(math.atan2(_dot(thigh, fwd), -thigh[1])) + trunk_flex
        knee_h[s] = k[1] - floor
    grips = {s: np.array(fr.site(f"{s}_palm", "grip")) for s in SIDES}
    p = Posture(trunk_flex, trunk_side, twist, neck_flex, neck_side, neck_twist, arms, knee, hip,
                {s: lows[s] - floor for s in SIDES}, knee_h, floor, (grips["left"] + grips["right"]) / 2,
                grips, (np.array(fr.p("left_foot")) + np.array(fr.p("right_foot"))) / 2, np.array(fwd),
                np.array(left))
    p._frames = fr
    return p
