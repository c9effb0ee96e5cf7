"""Which segments, sites and joints of a figure the behaviors use (feet, pelvis, chest, head, hands).

Behaviors never hard-code names; they read an :class:`Anatomy`. :func:`synthetic_anatomy` fits
:func:`jackpy.peabody.synthetic.human_like_tree` (adding the few sites it lacks);
:func:`human_anatomy` fits :func:`jackpy.body.make_human`. Local vectors are in the named segment's
base frame; lengths in metres, angles in radians.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from jackpy.peabody.model import Figure
from jackpy.peabody.transforms import translation

SIDES = ("left", "right")


@dataclass
class FootSpec:
    """One foot: ``ball`` carries the toe constraint and is the root site when this foot roots the
    figure; ``heel`` carries the heel-height constraint; ``heel``, ``ball`` and ``toe`` spread by
    ``half_width`` sideways give the footprint. ``forward``/``up`` are the foot's local axes."""

    segment: str
    ball: tuple[str, str]
    heel: tuple[str, str]
    toe: tuple[str, str]
    half_width: float
    forward: np.ndarray
    up: np.ndarray
    joints: list[str]


@dataclass
class Digit:
    """One finger or the thumb: its flexion DOFs proximal to distal as (joint, DOF index, sign
    that closes), its segments, and its radius (m) for contact."""

    name: str
    flex: list[tuple[str, int, float]]
    segments: list[str]
    radius: float = 0.008


@dataclass
class HandSpec:
    """One hand: ``palm`` site (palm centre; ``normal``, ``fingers`` and ``thumb_side`` are local unit
    vectors of its segment: out of the palm, along the fingers, towards the thumb), the arm's joints
    (proximal to distal) and the digits (thumb first)."""

    palm: tuple[str, str]
    normal: np.ndarray
    fingers: np.ndarray
    thumb_side: np.ndarray
    arm_joints: list[str]
    digits: list[Digit]
    shoulder: tuple[str, str]


@dataclass
class Anatomy:
    """The named parts behaviors act on.

    ``chest`` is an upper-torso site kept vertical (``chest_up`` its segment-local up);
    ``view`` the between-the-eyes site whose local ``view_forward`` the head aims;
    ``eyes`` a site at each eyeball's centre (segment-local forward ``eye_forward``), ``eye_joints``
    their joints;
    ``springs`` are (joint, DOF index, extension angle, sign of flexion) of knees and elbows.
    """

    pelvis: str
    pelvis_site: str
    pelvis_forward: np.ndarray
    pelvis_up: np.ndarray
    chest: tuple[str, str]
    chest_up: np.ndarray
    view: tuple[str, str]
    view_forward: np.ndarray
    neck_joints: list[str]
    eyes: dict[str, tuple[str, str]]
    eye_joints: dict[str, str]
    eye_forward: np.ndarray
    feet: dict[str, FootSpec]
    hands: dict[str, HandSpec]
    springs: list[tuple[str, int, float, float]]
    leg_length: float
    spine_group: str | None = None
    spine_joints: list[str] = field(default_factory=list)


def synthetic_anatomy(figure: Figure) -> Anatomy:
    """Anatomy of the synthetic 69-segment tree (adds heel, toe, view and palm sites to ``figure``)."""
    X, Y, Z = np.eye(3)
    head = figure.segment("head")
    if "view" not in head.sites:
        head.add_site("view", translation(0.0, 0.1, 0.08))
    feet, hands = {}, {}
    for side, sx in (("left", 1.0), ("right", -1.0)):
        foot = figure.segment(f"foot_{side}")
        if "heel" not in foot.sites:
            foot.add_site("heel", translation(0.0, -0.08, -0.04))
        feet[side] = FootSpec(f"foot_{side}", (f"foot_{side}", "ball"), (f"foot_{side}", "heel"),
                              (f"toes_{side}", "tip"), 0.045, Z.copy(), Y.copy(),
                              [f"hip_{side}", f"knee_{side}", f"ankle_{side}", f"toes_{side}"])
        palm = figure.segment(f"palm_{side}")
        if "centre" not in palm.sites:
            palm.add_site("centre", translation(0.0, -0.05, 0.0))
        digits = [Digit(f"d{d}", [(f"finger{d}{p}_{side}", 0, 1.0) for p in range(3)],
                        [f"finger{d}{p}_{side}" for p in range(3)]) for d in range(5)]
        hands[side] = HandSpec((f"palm_{side}", "centre"), -Z.copy(), -Y.copy(), sx * X,
                               [f"clavicle_{side}", f"shoulder_{side}", f"elbow_{side}", f"wrist_{side}"],
                               digits, (f"upperarm_{side}", "base"))
    figure.topology_changed()
    springs = [(f"knee_{s}", 0, 0.0, 1.0) for s in SIDES] + [(f"elbow_{s}", 0, 0.0, -1.0) for s in SIDES]
    return Anatomy(
        pelvis="pelvis", pelvis_site="base", pelvis_forward=Z.copy(), pelvis_up=Y.copy(),
        chest=("vertebra17", "base"), chest_up=Y.copy(), view=("head", "view"), view_forward=Z.copy(),
        neck_joints=["neck", "head"], eyes={s: (f"eye_{s}", "base") for s in SIDES},
        eye_joints={s: f"eye_{s}" for s in SIDES}, eye_forward=Z.copy(), feet=feet, hands=hands,
        springs=springs, leg_length=0.94, spine_joints=[f"spine{k + 1}" for k in range(17)])


def human_anatomy(figure: Figure) -> Anatomy:
    """Anatomy of :func:`jackpy.body.make_human` (standing in its neutral posture when called:
    local axes are read from that posture, facing from the feet's heel-to-ball direction)."""
    w = figure.world_transforms()

    def local(seg: str, v: np.ndarray) -> np.ndarray:
        u = w[seg][:3, :3].T @ v
        return u / np.linalg.norm(u)

    def at(seg: str, site: str) -> np.ndarray:
        return figure.site_world(seg, site)[:3, 3]

    up = np.array([0.0, 1.0, 0.0])
    fwd = sum(at(f"{s}_foot", "ball") - at(f"{s}_foot", "heel") for s in SIDES)
    fwd = fwd - (fwd @ up) * up
    fwd /= np.linalg.norm(fwd)
    feet, hands = {}, {}
    for side in SIDES:
        foot = f"{side}_foot"
        f_fwd = at(foot, "ball") - at(foot, "heel")
        feet[side] = FootSpec(foot, (foot, "ball"), (foot, "heel"), (foot, "toe"), 0.045,
                              local(foot, f_fwd - (f_fwd @ up) * up), local(foot, up),
                              [f"{side}_hip", f"{side}_knee", f"{side}_ankle", f"{side}_toes"])
        palm = f"{side}_palm"
        fingers = at(palm, "middle_mcp") - at(palm, "base")
        thumb = at(palm, "thumb_cmc") - at(palm, "palm_centre")
        digits = [Digit("thumb", [(f"{side}_thumb_cmc", 0, 1.0), (f"{side}_thumb_mcp", 0, 1.0),
                                  (f"{side}_thumb_ip", 0, 1.0)], [f"{side}_thumb_{k}" for k in (1, 2, 3)])]
        for name in ("index", "middle", "ring", "little"):
            digits.append(Digit(name, [(f"{side}_{name}_mcp", 1, 1.0), (f"{side}_{name}_pip", 0, 1.0),
                                       (f"{side}_{name}_dip", 0, 1.0)], [f"{side}_{name}_{k}" for k in (1, 2, 3)]))
        # the palm faces where the index tip goes when it flexes
        q0 = figure.q.copy()
        tip0 = at(f"{side}_index_3", "tip")
        figure.joint(f"{side}_index_mcp").displacement[1] += 0.1
        normal = at(f"{side}_index_3", "tip") - tip0
        figure.q = q0
        f_l = local(palm, fingers)
        n_l = local(palm, normal)
        n_l = n_l - (n_l @ f_l) * f_l
        hands[side] = HandSpec((palm, "palm_centre"), n_l / np.linalg.norm(n_l), f_l, local(palm, thumb),
                               [f"{side}_clavicle", f"{side}_shoulder_tilt", f"{side}_shoulder", f"{side}_elbow",
                                f"{side}_forearm_twist_1", f"{side}_forearm_twist_2", f"{side}_wrist"],
                               digits, (f"{side}_upper_arm", "base"))
    springs = [(f"{s}_knee", 0, 0.0, 1.0) for s in SIDES] + [(f"{s}_elbow", 0, 0.0, 1.0) for s in SIDES]
    hip = figure.site_world("pelvis", "left_hip")[:3, 3]
    spine = figure.groups["spine"]
    return Anatomy(
        pelvis="pelvis", pelvis_site="centre", pelvis_forward=local("pelvis", fwd), pelvis_up=local("pelvis", up),
        chest=("t1", "base"), chest_up=local("t1", up), view=("head", "view"), view_forward=local("head", fwd),
        neck_joints=["c7_t1", "atlanto_occipital"], eyes={s: (f"{s}_eye", "base") for s in SIDES},
        eye_joints={s: f"{s}_eye" for s in SIDES}, eye_forward=local("left_eye", fwd), feet=feet, hands=hands,
        springs=springs, leg_length=float(hip[1] - at("left_foot", "heel")[1]), spine_group="spine",
        spine_joints=list(spine.joints))
