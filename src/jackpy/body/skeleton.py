"""The standard human's segments, sites, joints, limits and joint groups, sized from a :class:`BodySpec`.

Frames. World: y up, the figure faces +z, its left is +x, feet on the floor y = 0. In the *zero pose*
(every joint displacement 0) every segment frame is parallel to the world frame with its origin at its
proximal joint centre, the arms hang straight down with the palms facing the thighs and the spine is
straight. Sites are translations in the segment frame, identity-oriented unless docs/body.md says
otherwise. Right-side DOF axes are the left ones mirrored (``(a_x, -a_y, -a_z)``), so a positive angle
means the same anatomical motion on both sides (named in ``data/joint_limits.csv``).

Structure: pelvis; 17 vertebrae (``l5`` .. ``l1``, ``t12`` .. ``t1``) on 18 three-DOF joints (``l5_s1`` ..
``c7_t1``, the last one carrying the neck); neck; head; two eyes; per side clavicle, upper arm, forearm in
three twist sub-segments, palm and five digits of three segments, thigh, shank, foot and toes.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from jackpy.body.limits import limits, spine_levels
from jackpy.body.sass import BodySpec
from jackpy.body.shoulder import shoulder_group
from jackpy.body.spine import SPINE_AXES, SPINE_DOFS, spine_group
from jackpy.peabody.groups import JointGroup, LinearDriver
from jackpy.peabody.model import Dof, Figure, Joint, Segment
from jackpy.peabody.transforms import translation

SIDES = (("left", 1.0), ("right", -1.0))
FINGERS = ("index", "middle", "ring", "little")
DIGITS = ("thumb",) + FINGERS
#: Buchholz, Armstrong & Goldstein (1992) J. Biomech. 25(2):149-163: segment lengths as fractions of
#: hand length (metacarpal, proximal, middle, distal phalanx; thumb: metacarpal, proximal, distal)
BUCHHOLZ = {"thumb": (0.251, 0.196, 0.158), "index": (0.374, 0.265, 0.143, 0.097),
            "middle": (0.373, 0.277, 0.170, 0.108), "ring": (0.336, 0.259, 0.165, 0.107),
            "little": (0.295, 0.206, 0.117, 0.093)}
#: wrist joint centre to the carpometacarpal row, fraction of hand length [proposal]
CARPAL = 0.072
#: across-the-palm position of each finger's MCP joint, fraction of hand breadth (+ = thumb side)
MCP_ACROSS = {"index": 0.31, "middle": 0.1, "ring": -0.1, "little": -0.29}
#: the forearm's twist sub-segments as fractions of its length, elbow first
FOREARM_PARTS = (0.4, 0.3, 0.3)
#: neutral arm elevation (degrees) so the hanging arms clear the hips
NEUTRAL_ARM_ELEVATION = 7.0
#: clavicle joint to shoulder joint centre at 415 mm biacromial breadth (book 2.4: fitted sphere 6.05 cm)
CLAVICLE_RADIUS = 0.0605
#: half the distance between the ischial tuberosities at 1.756 m stature, m (about 11 cm apart; Dempster
#: 1955 / Schneider et al. 1983 seat-pressure peaks 10-13 cm apart) [proposal]
ISCHIAL_HALF_SPACING = 0.055
#: acromion tip lateral to the shoulder (glenohumeral) joint centre at 415 mm biacromial breadth, m:
#: the humeral head's radius plus the greater tubercle [proposal; with it the span-true arms come
#: out at de Leva's joint-centre lengths and ANSUR II's elbow-to-fingertip length]
ACROMION_LATERAL = 0.040
#: acromion above the shoulder (glenohumeral) joint centre at 415 mm biacromial breadth, m [proposal]
ACROMION_ABOVE_SHOULDER = 0.035


#: DOF names in type order per joint kind (the keys of joint_limits.csv and strength.csv)
DOF_NAMES = {
    "spine": SPINE_DOFS, "atlanto_occipital": SPINE_DOFS, "eye": ("pitch", "yaw"),
    "clavicle": ("elevation", "protraction"), "shoulder_tilt": ("clavicle_undo",),
    "shoulder": ("twist", "elevation", "abduction"), "elbow": ("flexion",), "forearm_twist": ("pronation",),
    "wrist": ("deviation", "flexion"), "finger_mcp": ("spread", "flexion"), "finger_pip": ("flexion",),
    "finger_dip": ("flexion",), "thumb_cmc": ("abduction", "flexion"), "thumb_mcp": ("flexion",),
    "thumb_ip": ("flexion",), "hip": ("rotation", "abduction", "flexion"), "knee": ("flexion",),
    "ankle": ("inversion", "flexion"), "toes": ("flexion",),
}


def joint_kind(joint: str) -> str:
    """The kind of a human joint: ``left_index_pip`` -> ``finger_pip``, ``l4_l5`` -> ``spine``."""
    for side in ("left_", "right_"):
        joint = joint.removeprefix(side)
    first, last = joint.split("_")[0], joint.split("_")[-1]
    if first in FINGERS:
        return f"finger_{last}"
    if first == "thumb":
        return f"thumb_{last}"
    if joint.startswith("forearm_twist"):
        return "forearm_twist"
    if first[0] in "lct" and first[1:].isdigit():
        return "spine"
    return joint


def dof_names_of(joint: Joint) -> tuple[str, ...]:
    """Anatomical names of a human joint's DOFs in type order (e.g. ``("rotation", "abduction", "flexion")``)."""
    return DOF_NAMES[joint_kind(joint.name)]


def mirror_axis(axis: tuple[float, float, float], sx: float) -> np.ndarray:
    """A left-side DOF axis carried to the side with x sign ``sx`` (the same anatomical sense)."""
    a = np.asarray(axis, dtype=float)
    return a if sx > 0 else np.array([a[0], -a[1], -a[2]])


@dataclass
class Skeleton:
    """The built figure and, per segment, its origin in world coordinates in the zero pose (m)."""

    figure: Figure
    origins: dict[str, np.ndarray] = field(default_factory=dict)
    #: named landmark points in world coordinates, zero pose (used by the shape generator)
    points: dict[str, np.ndarray] = field(default_factory=dict)


class _Builder:
    def __init__(self, name: str) -> None:
        self.sk = Skeleton(Figure(name))

    def segment(self, name: str, origin: np.ndarray) -> Segment:
        seg = Segment(name)
        seg.add_site("base")
        self.sk.figure.add_segment(seg)
        self.sk.origins[name] = np.asarray(origin, dtype=float)
        return seg

    def site(self, seg: str, name: str, world: np.ndarray, rot: np.ndarray | None = None) -> None:
        t = translation(*(np.asarray(world, dtype=float) - self.sk.origins[seg]))
        if rot is not None:
            t[:3, :3] = rot
        self.sk.figure.segment(seg).add_site(name, t)

    def joint(self, name: str, parent: str, site: str, child: str, dofs: list[Dof]) -> None:
        self.site(parent, site, self.sk.origins[child])
        self.sk.figure.add_joint(Joint(name, parent, site, child, "base", dofs))


def _dofs(kind: str, spec: list[tuple[str, tuple[float, float, float]]], sx: float = 1.0) -> list[Dof]:
    return [Dof("R", mirror_axis(axis, sx), *limits(kind, name)) for name, axis in spec]


def _moving_axis(d: np.ndarray, toward: np.ndarray) -> np.ndarray:
    """Unit axis of the rotation that swings direction ``d`` toward ``toward`` (positive angle)."""
    v = toward - np.dot(toward, d) * d
    a = np.cross(d, v)
    return a / np.linalg.norm(a)


def build_skeleton(spec: BodySpec, name: str = "human") -> Skeleton:
    """The figure's structure for ``spec``: segments with sites, joints with limits, joint groups.

    Geometry and mass properties are added by :func:`jackpy.body.human.make_human`.
    """
    d = spec.dims
    b = _Builder(name)
    pts = b.sk.points
    s_scale = spec.stature / 1.756

    ya = d["foot.height"]
    yk = ya + d["shank.length"]
    yh = yk + d["thigh.length"]
    ys = yh + d["pelvis.length"]
    yt = ys + d["spine.length"]
    yao = yt + d["neck.length"]
    zs = -0.03 * s_scale  # vertebral bodies lie behind the hip joint centres
    hx = 0.25 * d["hip.breadth"]
    pts.update(hip_y=np.array([0.0, yh, 0.0]), spine_base=np.array([0.0, ys, zs]),
               spine_top=np.array([0.0, yt, zs]), head_joint=np.array([0.0, yao, zs]),
               vertex=np.array([0.0, spec.stature, zs + 0.01]))

    # ---- pelvis and spine ------------------------------------------------------------------------
    b.segment("pelvis", pts["hip_y"])
    b.site("pelvis", "centre", pts["hip_y"])
    # ischial tuberosities under the compressed buttock tissue: the seat contact when sitting erect,
    # seat.hip_height below the hip joint centres (ANSUR II: sitting height - stature + trochanterion
    # height), ISCHIAL_HALF_SPACING apart either side, a little behind the hip joints
    seat_y = yh - d["seat.hip_height"]
    pts["seat_y"] = np.array([0.0, seat_y, 0.0])
    for side, sx in SIDES:
        b.site("pelvis", f"{side}_ischium", [sx * ISCHIAL_HALF_SPACING * s_scale, seat_y, -0.03 * s_scale])
    levels = spine_levels()
    heights = np.array([lv["height"] for lv in levels[:-1]], dtype=float)
    heights *= d["spine.length"] / heights.sum()
    y = ys
    for lv, h in zip(levels[:-1], heights):
        b.segment(str(lv["above"]), [0.0, y, zs])
        b.joint(str(lv["joint"]), str(lv["below"]), "top" if lv["below"] != "pelvis" else "l5_s1",
                str(lv["above"]), _spine_dofs(lv))
        pts[f"joint_{lv['joint']}"] = np.array([0.0, y, zs])
        y += h
    b.site("l3", "waist", [0.0, b.sk.origins["l3"][1], 0.0])
    b.segment("neck", pts["spine_top"])
    b.joint("c7_t1", "t1", "top", "neck", _spine_dofs(levels[-1]))
    b.segment("head", pts["head_joint"])
    b.joint("atlanto_occipital", "neck", "top", "head",
            _dofs("atlanto_occipital", [(n, SPINE_AXES[n]) for n in SPINE_DOFS]))
    b.site("head", "top", pts["vertex"])
    eye_y = spec.stature - spec.eye_drop
    eye_z = zs + 0.43 * d["head.length"]
    pts["view"] = np.array([0.0, eye_y, eye_z])
    b.site("head", "view", pts["view"])
    for side, sx in SIDES:
        centre = np.array([sx * d["eyes.breadth"] / 2, eye_y, eye_z - 0.012])
        b.segment(f"{side}_eye", centre)
        b.joint(f"{side}_eye", "head", f"{side}_eye", f"{side}_eye",
                _dofs("eye", [("pitch", (1.0, 0.0, 0.0)), ("yaw", (0.0, 1.0, 0.0))]))
        b.site(f"{side}_eye", "gaze", centre + [0.0, 0.0, 0.012])

    for side, sx in SIDES:
        _arm(b, spec, side, sx, yt, s_scale)
        _leg(b, spec, side, sx, hx, yh, yk, ya)

    fig = b.sk.figure
    fig.root = ("pelvis", "centre")
    fig.location = translation(0.0, yh, 0.0)
    fig.add_group(spine_group())
    for side, _ in SIDES:
        fig.add_group(shoulder_group(side))
        lo, hi = limits("forearm_twist", "pronation")
        fig.add_group(JointGroup(f"{side}_forearm", [f"{side}_forearm_twist_1", f"{side}_forearm_twist_2"],
                                 ["pronation"], LinearDriver([[0.5], [0.5]]), [2 * lo], [2 * hi]))
    return b.sk


def _spine_dofs(level: dict) -> list[Dof]:
    return [Dof("R", np.array(SPINE_AXES[n]), *level["limits"][n]) for n in SPINE_DOFS]


def _arm(b: _Builder, spec: BodySpec, side: str, sx: float, yt: float, s_scale: float) -> None:
    d = spec.dims
    pts = b.sk.points
    xb, zb = (0.0, 0.0, 1.0), (0.0, -1.0, 0.0)  # the book's shoulder frame: x forward, z down
    above = ACROMION_ABOVE_SHOULDER * d["shoulder.breadth"] / 0.415
    acromion_y = yt - d["acromion.drop"]
    shoulder = np.array([sx * (d["shoulder.breadth"] / 2 - ACROMION_LATERAL * d["shoulder.breadth"] / 0.415),
                         acromion_y - above, 0.0])
    clav = shoulder - [sx * CLAVICLE_RADIUS * d["shoulder.breadth"] / 0.415, 0.0, 0.0]
    pts[f"{side}_shoulder"] = shoulder
    pts[f"{side}_clavicle"] = clav
    b.segment(f"{side}_clavicle", clav)
    # acromion: above the glenohumeral centre by the humeral-head radius plus the acromion's
    # thickness, about 35 mm at 415 mm biacromial breadth [proposal]
    b.site(f"{side}_clavicle", "acromion", shoulder + [0.0, above, 0.0])
    b.joint(f"{side}_clavicle", "t1", f"{side}_clavicle", f"{side}_clavicle",
            _dofs("clavicle", [("elevation", xb), ("protraction", zb)], sx))
    # the book's 4-rotation shoulder (2.21) as two joints (at most 3 DOFs per joint): its last rotation,
    # R(x) by -phi_c, turns the zero-mass frame segment <side>_shoulder_frame back to the thorax's tilt
    b.segment(f"{side}_shoulder_frame", shoulder)
    b.joint(f"{side}_shoulder_tilt", f"{side}_clavicle", "shoulder", f"{side}_shoulder_frame",
            _dofs("shoulder_tilt", [("clavicle_undo", xb)], sx))
    b.segment(f"{side}_upper_arm", shoulder)
    b.joint(f"{side}_shoulder", f"{side}_shoulder_frame", "shoulder", f"{side}_upper_arm",
            _dofs("shoulder", [("twist", zb), ("elevation", xb), ("abduction", zb)], sx))
    upper, fore = arm_lengths(spec, abs(shoulder[0]), abs(clav[0]))
    elbow = shoulder - [0.0, upper, 0.0]
    b.segment(f"{side}_forearm", elbow)
    b.joint(f"{side}_elbow", f"{side}_upper_arm", "elbow", f"{side}_forearm",
            _dofs("elbow", [("flexion", (-1.0, 0.0, 0.0))], sx))
    y = elbow[1]
    parent = f"{side}_forearm"
    for k, (part, frac) in enumerate(zip(("mid", "distal"), FOREARM_PARTS[:2]), start=1):
        y -= frac * fore
        child = f"{side}_forearm_{part}"
        b.segment(child, [elbow[0], y, elbow[2]])
        b.joint(f"{side}_forearm_twist_{k}", parent, "twist", child,
                _dofs("forearm_twist", [("pronation", (0.0, -1.0, 0.0))], sx))
        parent = child
    wrist = elbow - [0.0, fore, 0.0]
    pts[f"{side}_wrist"] = wrist
    palm = f"{side}_palm"
    b.segment(palm, wrist)
    b.joint(f"{side}_wrist", parent, "wrist", palm,
            _dofs("wrist", [("deviation", (-1.0, 0.0, 0.0)), ("flexion", (0.0, 0.0, -1.0))], sx))
    hl, hb = d["hand.length"], d["hand.breadth"]
    # palm-centre frame: z out of the palm (medial), y toward the fingertips, x = y cross z
    zn = np.array([-sx, 0.0, 0.0])
    yn = np.array([0.0, -1.0, 0.0])
    rot = np.column_stack([np.cross(yn, zn), yn, zn])
    thick = 0.3 * hb
    b.site(palm, "palm_centre", wrist + [-sx * 0.5 * thick, -0.27 * hl, 0.02 * hb], rot)
    b.site(palm, "grip", wrist + [-sx * (0.5 * thick + 0.02), -0.42 * hl, 0.0], rot)
    for finger in FINGERS:
        lengths = np.array(BUCHHOLZ[finger]) * hl
        mcp = wrist + [0.0, -(CARPAL * hl + lengths[0]), MCP_ACROSS[finger] * hb]
        pts[f"{side}_{finger}_mcp"] = mcp
        _digit(b, side, sx, finger, palm, mcp, np.array([0.0, -1.0, 0.0]), lengths[1:],
               [("finger_mcp", [("spread", (-1.0, 0.0, 0.0)), ("flexion", (0.0, 0.0, -1.0))]),
                ("finger_pip", [("flexion", (0.0, 0.0, -1.0))]),
                ("finger_dip", [("flexion", (0.0, 0.0, -1.0))])])
    dl = np.array([-0.25, -0.8, 0.55])
    dl /= np.linalg.norm(dl)
    flex = _moving_axis(dl, np.array([0.0, 0.0, -1.0]))
    abd = _moving_axis(dl, np.array([-1.0, 0.0, 0.0]))
    cmc = wrist + [-sx * 0.25 * thick, -0.1 * hl, 0.33 * hb]
    pts[f"{side}_thumb_cmc"] = cmc
    _digit(b, side, sx, "thumb", palm, cmc, dl * [sx, 1.0, 1.0],
           np.array(BUCHHOLZ["thumb"]) * hl,
           [("thumb_cmc", [("abduction", tuple(abd)), ("flexion", tuple(flex))]),
            ("thumb_mcp", [("flexion", tuple(flex))]),
            ("thumb_ip", [("flexion", tuple(flex))])])


def arm_lengths(spec: BodySpec, shoulder_x: float, clavicle_x: float) -> tuple[float, float]:
    """Upper-arm and forearm joint-centre lengths (m) that give the figure its ANSUR II ``span``: with
    the arms outstretched sideways (elevation 90°, the clavicle raised by Otani's allocation) the
    middle fingertips are ``span`` apart. The shoulder-to-wrist length is shared in the ratio of the
    population's ``upper_arm.length`` to ``forearm.length`` (acromion-radiale and radiale-stylion
    lengths; taken alone they overstate span by about 9 cm, the landmarks being on the bone surface)."""
    from jackpy.body.shoulder import allocate

    d = spec.dims
    phi_c = np.radians(allocate(90.0, 0.0)[0])
    reach_x = clavicle_x + (shoulder_x - clavicle_x) * np.cos(phi_c)
    arm = d["span"] / 2 - reach_x - d["hand.length"]
    share = d["upper_arm.length"] / (d["upper_arm.length"] + d["forearm.length"])
    return float(arm * share), float(arm * (1.0 - share))


def _digit(b: _Builder, side: str, sx: float, digit: str, palm: str, base: np.ndarray, direction: np.ndarray,
           lengths: np.ndarray, joints: list[tuple[str, list]]) -> None:
    parent, p = palm, base
    names = {"finger_mcp": "mcp", "finger_pip": "pip", "finger_dip": "dip",
             "thumb_cmc": "cmc", "thumb_mcp": "mcp", "thumb_ip": "ip"}
    for k, (length, (kind, dofs)) in enumerate(zip(lengths, joints), start=1):
        seg = f"{side}_{digit}_{k}"
        b.segment(seg, p)
        b.joint(f"{side}_{digit}_{names[kind]}", parent, f"{digit}_{names[kind]}" if parent == palm else "tip",
                seg, _dofs(kind, dofs, sx))
        b.sk.points[f"{seg}_dir"] = direction
        p = p + direction * length
        b.site(seg, "tip", p)
        parent = seg


def _leg(b: _Builder, spec: BodySpec, side: str, sx: float, hx: float, yh: float, yk: float, ya: float) -> None:
    d = spec.dims
    fl = d["foot.length"]
    hip = np.array([sx * hx, yh, 0.0])
    b.segment(f"{side}_thigh", hip)
    b.joint(f"{side}_hip", "pelvis", f"{side}_hip", f"{side}_thigh",
            _dofs("hip", [("rotation", (0.0, -1.0, 0.0)), ("abduction", (0.0, 0.0, 1.0)),
                          ("flexion", (-1.0, 0.0, 0.0))], sx))
    b.segment(f"{side}_shank", [hip[0], yk, 0.0])
    b.joint(f"{side}_knee", f"{side}_thigh", "knee", f"{side}_shank", _dofs("knee", [("flexion", (1.0, 0.0, 0.0))], sx))
    ankle = np.array([hip[0], ya, 0.0])
    foot = f"{side}_foot"
    b.segment(foot, ankle)
    b.joint(f"{side}_ankle", f"{side}_shank", "ankle", foot,
            _dofs("ankle", [("inversion", (0.0, 0.0, -1.0)), ("flexion", (-1.0, 0.0, 0.0))], sx))
    heel, ball, toe = (np.array([hip[0], 0.0, z * fl]) for z in (-0.22, 0.51, 0.78))
    for n, p in (("heel", heel), ("ball", ball), ("toe", toe)):
        b.site(foot, n, p)
        b.sk.points[f"{side}_{n}"] = p
    b.segment(f"{side}_toes", [hip[0], 0.35 * ya, 0.51 * fl])
    b.joint(f"{side}_toes", foot, "mtp", f"{side}_toes", _dofs("toes", [("flexion", (1.0, 0.0, 0.0))], sx))
    b.site(f"{side}_toes", "tip", [hip[0], 0.3 * ya, 0.78 * fl])
