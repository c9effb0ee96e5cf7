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


def _deg(x: float) -> float:
    return float(np.degrees(x))


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
    the thorax's midsagittal plane toward the other side (m, 0 if it does not). ``finger_flexion``:
    mean MCP + PIP flexion of the four fingers (from the phalanges' world directions).
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
    finger_flexion: float
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
    """World transforms of the segments a measurement needs, from one forward pass."""

    def __init__(self, figure: Figure, fk: FKResult | None) -> None:
        kin = figure.kinematics()
        missing = [s for s in REQUIRED_SEGMENTS if s not in kin.segment_index]
        if missing:
            raise FigureError(f"figure {figure.name!r} is not a standard human (no segment {missing[0]!r}); "
                              "the ergonomic assessments measure jackpy.body.make_human figures")
        if fk is None:
            fk = kin.forward(figure.q, figure.location)
        self.kin, self.fk, self.figure = kin, fk, figure

    def T(self, seg: str) -> np.ndarray:
        return self.fk.segments[self.kin.segment_index[seg]]

    def p(self, seg: str) -> np.ndarray:
        return self.fk.segments[self.kin.segment_index[seg]][:3, 3]

    def site(self, seg: str, site: str) -> np.ndarray:
        return (self.T(seg) @ self.figure.site_location(seg, site))[:3, 3]


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    c = float(np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b)))
    return _deg(np.arccos(min(1.0, max(-1.0, c))))


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def _flexion_range(a: float) -> float:
    """Arm flexion in (-90, 270]: an arm straight up is 180° (not -180°); the shoulder cannot extend
    past 90° behind the trunk."""
    return a + 360.0 if a <= -90.0 else a


def _finger_flexion(fr: _Frames, side: str) -> float:
    """Mean over the four fingers of the angle between the palm's long axis and the middle
    phalanx (MCP + PIP flexion together), degrees."""
    palm = fr.T(f"{side}_palm")[:3, :3] @ np.array([0.0, -1.0, 0.0])
    out = []
    for f in _FINGERS:
        name = f"{side}_{f}_2"
        if name not in fr.kin.segment_index:
            return 0.0
        a = fr.p(name)
        b = fr.site(name, "tip")
        out.append(_angle(palm, b - a))
    return float(np.mean(out))


def _arm(fr: _Frames, side: str, thorax: np.ndarray) -> ArmAngles:
    s = _SIGN[side]
    sh, el, wr = fr.p(f"{side}_upper_arm"), fr.p(f"{side}_forearm"), fr.p(f"{side}_palm")
    u = thorax.T @ (el - sh)
    w = thorax.T @ (wr - el)
    c = thorax.T @ (sh - fr.p(f"{side}_clavicle"))
    fd = fr.T(f"{side}_forearm_distal")[:3, :3]
    hand = fd.T @ fr.T(f"{side}_palm")[:3, :3] @ np.array([0.0, -1.0, 0.0])
    twist = fr.T(f"{side}_forearm")[:3, :3].T @ fd[:, 0]
    mid = thorax.T @ (wr - fr.p("t1"))
    un, wn = np.linalg.norm(u), np.linalg.norm(w)
    return ArmAngles(
        upper_arm_flexion=_flexion_range(_deg(np.arctan2(u[2], -u[1]))),
        upper_arm_abduction=_deg(np.arcsin(np.clip(s * u[0] / un, -1.0, 1.0))),
        shoulder_elevation=_deg(np.arcsin(np.clip(c[1] / np.linalg.norm(c), -1.0, 1.0))),
        elbow_flexion=_angle(u, w),
        forearm_out=_deg(np.arcsin(np.clip(s * w[0] / wn, -1.0, 1.0))),
        wrist_flexion=_deg(np.arctan2(-s * hand[0], -hand[1])),
        wrist_deviation=_deg(np.arctan2(hand[2], -hand[1])),
        forearm_pronation=_deg(np.arctan2(s * twist[2], twist[0])),
        hand_across_midline_m=float(max(0.0, -s * mid[0])),
        finger_flexion=_finger_flexion(fr, side),
        wrist_height_m=float(wr[1]), elbow_height_m=float(el[1]), shoulder_height_m=float(sh[1]),
    )


def measure(figure: Figure, fk: FKResult | None = None) -> Posture:
    """Measure ``figure``'s current posture (or the one ``fk`` holds); see :class:`Posture`."""
    fr = _Frames(figure, fk)
    up = np.array([0.0, 1.0, 0.0])
    pelvis = fr.T("pelvis")[:3, :3]
    left = pelvis[:, 0] - pelvis[1, 0] * up  # the hip axis stays level however far the pelvis pitches
    if np.linalg.norm(left) < 1e-6:  # pelvis rolled on its side: fall back on its forward axis
        left = np.cross(up, pelvis[:, 2])
    left = _unit(left)
    fwd = np.cross(left, up)
    # trunk
    trunk = fr.p("neck") - fr.p("l5")
    tl = np.linalg.norm(trunk)
    trunk_flex = _deg(np.arctan2(trunk @ fwd, trunk @ up))
    trunk_side = _deg(np.arcsin(np.clip(trunk @ left / tl, -1.0, 1.0)))
    axis = trunk / tl
    thorax = fr.T("t1")[:3, :3]
    a = thorax[:, 0] - (thorax[:, 0] @ axis) * axis
    b = pelvis[:, 0] - (pelvis[:, 0] @ axis) * axis
    twist = _deg(np.arctan2(np.cross(b, a) @ axis, a @ b))
    # neck: head against thorax
    head = thorax.T @ fr.T("head")[:3, :3]
    hu, hf = head[:, 1], head[:, 2]
    neck_flex = _deg(np.arctan2(hu[2], hu[1]))
    neck_side = _deg(np.arcsin(np.clip(hu[0], -1.0, 1.0)))
    neck_twist = _deg(np.arctan2(hf[0], hf[2]))
    arms = {s: _arm(fr, s, thorax) for s in SIDES}
    # legs
    lows = {}
    for s in SIDES:
        lows[s] = min(float(fr.site(f"{s}_foot", n)[1]) for n in ("heel", "ball", "toe"))
    floor = min(lows.values())
    knee, hip, knee_h = {}, {}, {}
    for s in SIDES:
        h, k, an = fr.p(f"{s}_thigh"), fr.p(f"{s}_shank"), fr.p(f"{s}_foot")
        knee[s] = _angle(k - h, an - k)
        thigh = k - h
        hip[s] = _deg(np.arctan2(thigh @ fwd, -(thigh @ up))) + trunk_flex
        knee_h[s] = float(k[1] - floor)
    grips = {s: fr.site(f"{s}_palm", "grip") for s in SIDES}
    return Posture(trunk_flex, trunk_side, twist, neck_flex, neck_side, neck_twist, arms, knee, hip,
                   {s: lows[s] - floor for s in SIDES}, knee_h, floor, (grips["left"] + grips["right"]) / 2,
                   grips, (fr.p("left_foot") + fr.p("right_foot")) / 2, fwd, left)
