"""BVH import with retargeting onto a standard jackpy human (behaviors.md §4; issue 12).

The captured skeleton's joints are found by a **name map** from jackpy's landmarks to BVH joint
names: built in for the CMU MotionBuilder-friendly convention (``Hips``, ``LeftUpLeg``,
``LeftLeg``, ...) and Bandai-Namco's (``UpperLeg_L``, ...), or given in a user's JSON map file::

    {"joints": {"hips": "Hips", "left_hip": "LeftUpLeg", ...}, "reference_frame": 0, "skip_frames": 1}

(landmarks: see :data:`LANDMARKS`; ``reference_frame`` is unused by the solve and kept for
information; ``skip_frames`` drops leading frames such as CMU's added T-pose). A BVH written by
:mod:`.bvh_export` (the figure's own segment names) is read back joint for joint instead
(:func:`jackpy.motion.bvh_export.import_own`).

The figure is driven by **goals**, never by copying angles across unlike rest poses:

- the size ratio ``s`` = the human's thigh + shank length over the capture's, so strides and
  heights scale with the body (units cancel: CMU's 1/0.45 inch, Bandai's cm);
- **pelvis**: the root; its hip centre goes to ``s`` x the captured one (height above the captured
  floor) and it turns with the frame of the captured hips (left-right hip axis, trunk up);
- **feet**: toe (ball) and ankle position goals at ``s`` x the captured points, knees hinted;
  **planted feet do not slide**: a foot is in stance while its ball is within 4 cm of the floor and
  slower than 0.3 m/s (for at least 0.1 s); during a stance its goal is held at one spot, and the
  root is shifted by what the planted feet still miss, so they land exactly;
- **trunk and head**: orientation goals on the chest (shoulder axis, chest-to-neck up) and head;
- **hands**: elbow and wrist goals along the captured upper-arm and forearm directions at the
  human's own arm lengths (so they are reachable), solved after the body.

Every solve keeps the joints within their limits. The floor of the capture is the 5th percentile
of the lower ball height over the frames.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from jackpy.errors import JackpyError, ParseError
from jackpy.motion.bvh import BVH, read

#: jackpy landmarks and where they sit on the standard human (segment, site)
LANDMARKS: dict[str, tuple[str, str]] = {
    "hips": ("pelvis", "centre"),
    "left_hip": ("pelvis", "left_hip"), "right_hip": ("pelvis", "right_hip"),
    "left_knee": ("left_shank", "base"), "right_knee": ("right_shank", "base"),
    "left_ankle": ("left_foot", "base"), "right_ankle": ("right_foot", "base"),
    "left_ball": ("left_foot", "ball"), "right_ball": ("right_foot", "ball"),
    "chest": ("t7", "base"), "neck": ("neck", "base"), "head": ("head", "base"),
    "left_shoulder": ("left_upper_arm", "base"), "right_shoulder": ("right_upper_arm", "base"),
    "left_elbow": ("left_forearm", "base"), "right_elbow": ("right_forearm", "base"),
    "left_wrist": ("left_palm", "base"), "right_wrist": ("right_palm", "base"),
}

BUILTIN_MAPS: dict[str, dict] = {
    "cmu": {"skip_frames": 1, "joints": {
        "hips": "Hips", "left_hip": "LeftUpLeg", "right_hip": "RightUpLeg", "left_knee": "LeftLeg",
        "right_knee": "RightLeg", "left_ankle": "LeftFoot", "right_ankle": "RightFoot", "left_ball": "LeftToeBase",
        "right_ball": "RightToeBase", "chest": "Spine1", "neck": "Neck1", "head": "Head",
        "left_shoulder": "LeftArm", "right_shoulder": "RightArm", "left_elbow": "LeftForeArm",
        "right_elbow": "RightForeArm", "left_wrist": "LeftHand", "right_wrist": "RightHand"}},
    "bandai": {"skip_frames": 0, "joints": {
        "hips": "Hips", "left_hip": "UpperLeg_L", "right_hip": "UpperLeg_R", "left_knee": "LowerLeg_L",
        "right_knee": "LowerLeg_R", "left_ankle": "Foot_L", "right_ankle": "Foot_R", "left_ball": "Toes_L",
        "right_ball": "Toes_R", "chest": "Chest", "neck": "Neck", "head": "Head", "left_shoulder": "UpperArm_L",
        "right_shoulder": "UpperArm_R", "left_elbow": "LowerArm_L", "right_elbow": "LowerArm_R",
        "left_wrist": "Hand_L", "right_wrist": "Hand_R"}},
}

SIDES = ("left", "right")
#: stance: ball within this height (m) of the floor and slower than STANCE_SPEED (m/s) ...
STANCE_HEIGHT = 0.04
STANCE_SPEED = 0.3
#: ... for at least this long (s)
STANCE_MIN = 0.1
#: solver iterations per pass and frame (warm-started from the last frame)
ITERATIONS = 15
#: at most this many leg solves per frame, the root shifted onto the planted feet between them
ROOT_ROUNDS = 4


@dataclass
class NameMap:
    """Landmark -> BVH joint name, and how many leading frames to drop."""

    joints: dict[str, str]
    skip_frames: int = 0
    name: str = "custom"


def load_map(path: str | os.PathLike) -> NameMap:
    """A user's map file (JSON, see the module docstring); errors name the file and key."""
    from jackpy import jsonfile

    p = str(path)
    try:
        data = jsonfile.load(path, ParseError)
    except FileNotFoundError:
        raise ParseError("no such map file", p) from None
    try:
        d = jsonfile.obj(data, "")
        joints = jsonfile.obj(jsonfile.required(d, "joints", ""), "joints")
        out = {}
        for k, v in joints.items():
            if k not in LANDMARKS:
                raise jsonfile.Invalid(f"joints.{k}", f"unknown landmark (one of {', '.join(LANDMARKS)})")
            out[k] = jsonfile.string(v, f"joints.{k}")
        skip = jsonfile.integer(d.get("skip_frames", 0), "skip_frames", 0)
    except jsonfile.Invalid as exc:
        raise jsonfile.schema_error(ParseError, p, exc) from None
    return NameMap(out, skip, Path(p).name)


def choose_map(bvh: BVH) -> NameMap:
    """The built-in map whose joint names the file has (ParseError naming what is missing)."""
    names = set(bvh.names)
    best = None
    for key, m in BUILTIN_MAPS.items():
        missing = [v for v in m["joints"].values() if v not in names]
        if not missing:
            return NameMap(dict(m["joints"]), m["skip_frames"], key)
        if best is None or len(missing) < len(best[1]):
            best = (key, missing)
    raise ParseError(f"joint names match no known convention (closest: {best[0]}, missing "
                     f"{', '.join(best[1][:5])}); give a map file with --map", bvh.file)


def _unit(v: np.ndarray) -> np.ndarray:
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.maximum(n, 1e-12)


def body_frame(lateral: np.ndarray, up: np.ndarray) -> np.ndarray:
    """Rotation(s) with columns (lateral, up', forward) from a left-pointing lateral and an up."""
    x = _unit(lateral)
    y = _unit(up - np.sum(up * x, axis=-1, keepdims=True) * x)
    z = np.cross(x, y)
    return np.stack([x, y, z], axis=-1)


def resample(n_src: int, fps_src: float, fps: float, skip: int) -> np.ndarray:
    """Source frame indices nearest to times k / fps, from frame ``skip`` on."""
    duration = (n_src - 1 - skip) / fps_src
    n = int(np.floor(duration * fps + 1e-9)) + 1
    return np.clip(skip + np.rint(np.arange(n) / fps * fps_src).astype(int), skip, n_src - 1)


def stances(ball: np.ndarray, fps: float) -> list[tuple[int, int]]:
    """Frame ranges [a, b] in which a foot's ball (N, 3; m, above floor) is planted."""
    speed = np.zeros(len(ball))
    if len(ball) > 1:
        v = np.linalg.norm(np.diff(ball[:, [0, 2]], axis=0), axis=1) * fps
        speed[1:] = v
        speed[0] = v[0]
        speed[1:-1] = np.minimum(v[:-1], v[1:])
    planted = (ball[:, 1] < STANCE_HEIGHT) & (speed < STANCE_SPEED)
    out, start = [], None
    for i, p in enumerate(np.append(planted, False)):
        if p and start is None:
            start = i
        elif not p and start is not None:
            if (i - start) / fps >= STANCE_MIN:
                out.append((start, i - 1))
            start = None
    return out


@dataclass
class Targets:
    """Per output frame, world goal targets (m) for the figure."""

    hips: np.ndarray  # (N, 3) hip centre
    pelvis_rot: np.ndarray  # (N, 3, 3) pelvis-site world rotation
    chest_rot: np.ndarray
    head_rot: np.ndarray
    points: dict[str, np.ndarray]  # landmark -> (N, 3)
    dirs: dict[str, np.ndarray]  # "left_upper", "left_fore" ... -> (N, 3) unit
    stance: dict[str, list[tuple[int, int]]]


def _landmark(figure, name: str) -> np.ndarray:
    return figure.site_world(*LANDMARKS[name])


def targets_for(figure, bvh: BVH, nmap: NameMap, fps: float) -> tuple[Targets, float, np.ndarray]:
    """Goal targets for ``figure`` (standing neutral) from ``bvh``; returns them, the size ratio
    and the source frame index of each output frame."""
    idx = resample(bvh.frames.shape[0], bvh.fps, fps, nmap.skip_frames)
    _, wp = bvh.world(bvh.frames[idx])
    J = {k: bvh.index(v) for k, v in nmap.joints.items()}

    def P(k: str) -> np.ndarray:
        return wp[:, J[k]]

    # size ratio from the capture's bone lengths (offsets) and the human's
    def bone(a: str, b: str) -> float:
        return float(np.median(np.linalg.norm(P(a) - P(b), axis=1)))

    def jbone(a: str, b: str) -> float:
        return float(np.linalg.norm(_landmark(figure, a)[:3, 3] - _landmark(figure, b)[:3, 3]))

    cap = np.mean([bone(f"{s}_hip", f"{s}_knee") + bone(f"{s}_knee", f"{s}_ankle") for s in SIDES])
    own = np.mean([jbone(f"{s}_hip", f"{s}_knee") + jbone(f"{s}_knee", f"{s}_ankle") for s in SIDES])
    if cap <= 0:
        raise ParseError("the legs have zero length", bvh.file)
    s = own / cap
    balls = np.minimum(P("left_ball")[:, 1], P("right_ball")[:, 1])
    floor = float(np.percentile(balls, 5))
    ball0 = float(np.mean([_landmark(figure, f"{side}_ball")[1, 3] for side in SIDES]))

    def world(k: str) -> np.ndarray:
        p = s * P(k)
        p[:, 1] = s * (P(k)[:, 1] - floor) + ball0
        return p

    hips = 0.5 * (world("left_hip") + world("right_hip"))
    points = {k: world(k) for k in ("left_knee", "right_knee", "left_ankle", "right_ankle", "left_ball", "right_ball")}
    dirs = {}
    for side in SIDES:
        dirs[f"{side}_upper"] = _unit(P(f"{side}_elbow") - P(f"{side}_shoulder"))
        dirs[f"{side}_fore"] = _unit(P(f"{side}_wrist") - P(f"{side}_elbow"))

    # frames: pelvis (hip axis, trunk up), chest (shoulder axis, chest-neck up), head (neck-head up)
    def frames_cap() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        hc = 0.5 * (P("left_hip") + P("right_hip"))
        fp = body_frame(P("left_hip") - P("right_hip"), P("chest") - hc)
        lat = P("left_shoulder") - P("right_shoulder")
        fc = body_frame(lat, P("neck") - P("chest"))
        fh = body_frame(lat, P("head") - P("neck"))
        return fp, fc, fh

    def frames_own() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        g = {k: _landmark(figure, k)[:3, 3] for k in LANDMARKS}
        hc = 0.5 * (g["left_hip"] + g["right_hip"])
        fp = body_frame(g["left_hip"] - g["right_hip"], g["chest"] - hc)
        lat = g["left_shoulder"] - g["right_shoulder"]
        return fp, body_frame(lat, g["neck"] - g["chest"]), body_frame(lat, g["head"] - g["neck"])

    cp, cc, ch = frames_cap()
    op, oc, oh = frames_own()
    site_rot = {k: _landmark(figure, k)[:3, :3] for k in ("hips", "chest", "head")}
    pelvis_rot = cp @ (op.T @ site_rot["hips"])
    chest_rot = cc @ (oc.T @ site_rot["chest"])
    head_rot = ch @ (oh.T @ site_rot["head"])
    stance = {side: stances(points[f"{side}_ball"] - [0.0, ball0, 0.0], fps) for side in SIDES}
    for side in SIDES:
        ball, ankle = points[f"{side}_ball"], points[f"{side}_ankle"]
        for a, b in stance[side]:
            spot = np.median(ball[a:b + 1], axis=0)
            spot[1] = ball0
            shift = spot - ball[a:b + 1]
            ball[a:b + 1] = spot
            ankle[a:b + 1] += shift
    return Targets(hips, pelvis_rot, chest_rot, head_rot, points, dirs, stance), s, idx


class Retargeter:
    """Solves a figure's posture for each frame of :class:`Targets` (warm-started frame to frame)."""

    def __init__(self, figure) -> None:
        from jackpy.ik import Problem
        from jackpy.ik.goals import Orientation, Position

        self.figure = figure
        figure.reroot(*LANDMARKS["hips"])
        hc = 0.5 * (_landmark(figure, "left_hip")[:3, 3] + _landmark(figure, "right_hip")[:3, 3])
        root = figure.site_world(*LANDMARKS["hips"])
        self.hc_local = np.linalg.inv(root)[:3, :3] @ hc + np.linalg.inv(root)[:3, 3]
        site = lambda k: ".".join(LANDMARKS[k])  # noqa: E731
        leg_joints = {j for j in figure.joints if any(x in j for x in ("hip", "knee", "ankle", "toes"))}
        arm_joints = {j for j in figure.joints if any(x in j for x in ("clavicle", "shoulder", "elbow", "forearm",
                                                                         "wrist"))}
        neck_joints = {"c7_t1", "atlanto_occipital"} & set(figure.joints)
        groups = set(figure.groups)
        self.goals: dict[str, object] = {}
        # legs: toe (ball) and ankle positions, knees hinted; the root (pelvis) is placed directly
        self.legs = Problem(figure)
        for side in SIDES:
            self.goals[f"{side}_ball"] = self.legs.add(Position(site(f"{side}_ball"), np.zeros(3), weight=100.0), 0)
            self.goals[f"{side}_ankle"] = self.legs.add(Position(site(f"{side}_ankle"), np.zeros(3), weight=1.0), 0)
            self.goals[f"{side}_knee"] = self.legs.add(Position(site(f"{side}_knee"), np.zeros(3), weight=0.05), 0)
        self.legs.lock(*sorted(set(figure.joints) - leg_joints), *sorted(groups))
        # trunk and head: the spine group and the neck
        self.trunk = Problem(figure)
        self.goals["chest"] = self.trunk.add(Orientation(site("chest"), np.eye(3), weight=1.0), 0)
        self.goals["head"] = self.trunk.add(Orientation(site("head"), np.eye(3), weight=0.5), 0)
        spine_members = set(figure.groups["spine"].joints) if "spine" in figure.groups else set()
        self.trunk.lock(*sorted(set(figure.joints) - neck_joints - spine_members), *sorted(groups - {"spine"}))
        # arms: elbow and wrist along the captured directions
        self.arms = Problem(figure)
        for side in SIDES:
            self.goals[f"{side}_elbow"] = self.arms.add(Position(site(f"{side}_elbow"), np.zeros(3), weight=0.3), 0)
            self.goals[f"{side}_wrist"] = self.arms.add(Position(site(f"{side}_wrist"), np.zeros(3)), 0)
        arm_members = {j for g in groups - {"spine"} for j in figure.groups[g].joints}
        self.arms.lock(*sorted(set(figure.joints) - arm_joints - arm_members), "spine")
        self.lengths = {}
        for side in SIDES:
            sh, el, wr = (_landmark(figure, f"{side}_{k}")[:3, 3] for k in ("shoulder", "elbow", "wrist"))
            self.lengths[side] = (float(np.linalg.norm(el - sh)), float(np.linalg.norm(wr - el)))

    def place_root(self, hips: np.ndarray, rot: np.ndarray) -> None:
        loc = np.eye(4)
        loc[:3, :3] = rot
        loc[:3, 3] = hips - rot @ self.hc_local
        self.figure.location = loc

    def solve_frame(self, tg: Targets, i: int, planted: list[str]) -> None:
        from jackpy.ik import solve

        fig, g = self.figure, self.goals
        self.place_root(tg.hips[i], tg.pelvis_rot[i])
        for side in SIDES:
            for k in ("ball", "ankle", "knee"):
                g[f"{side}_{k}"].target = tg.points[f"{side}_{k}"][i].copy()
        g["chest"].target = tg.chest_rot[i].copy()
        g["head"].target = tg.head_rot[i].copy()
        solve(self.trunk, max_iterations=ITERATIONS, tol_position=2e-4, tol_angle=0.5)
        for _ in range(ROOT_ROUNDS):
            solve(self.legs, max_iterations=ITERATIONS, tol_position=2e-4, tol_angle=0.5)
            if not planted:
                break
            miss = np.mean([tg.points[f"{s}_ball"][i] - fig.site_world(*LANDMARKS[f"{s}_ball"])[:3, 3]
                            for s in planted], axis=0)
            if np.linalg.norm(miss) < 3e-4:
                break
            loc = fig.location.copy()
            loc[:3, 3] += miss
            fig.location = loc
        for side in SIDES:
            sh = fig.site_world(*LANDMARKS[f"{side}_shoulder"])[:3, 3]
            lu, lf = self.lengths[side]
            el = sh + lu * tg.dirs[f"{side}_upper"][i]
            g[f"{side}_elbow"].target = el
            g[f"{side}_wrist"].target = el + lf * tg.dirs[f"{side}_fore"][i]
        solve(self.arms, max_iterations=ITERATIONS, tol_position=5e-4, tol_angle=1.0)


def import_bvh(path: str | os.PathLike, figure_spec: str = "male:50", map_file: str | None = None,
               fps: float | None = None, progress: Callable[[int, int], None] | None = None,
               name: str | None = None):
    """Read ``path`` and retarget it onto the standard human ``figure_spec`` (``male:50``,
    ``female:5`` ...); returns a :class:`~jackpy.motion.motion_file.MotionFile` with the baked
    frames (and an empty timeline naming the figure). ``fps``: output rate (default: the file's,
    at most 30)."""
    from jackpy.motion import cast
    from jackpy.motion.bake import Posture
    from jackpy.motion.bvh_export import import_own, is_own
    from jackpy.motion.motion_file import BakedFigure, MotionFile
    from jackpy.motion.timeline import Timeline

    try:
        bvh = read(str(path))
    except FileNotFoundError:
        raise ParseError("no such BVH file", str(path)) from None
    name = name or Path(path).stem.split(".")[0]
    fig = cast.make_figure(name, {"human": figure_spec})
    if fps is None:
        fps = min(bvh.fps, 30.0)
    if not fps > 0:
        raise JackpyError(f"fps must be > 0, not {fps}")
    if is_own(fig, bvh) and map_file is None:
        postures = import_own(fig, bvh, fps, progress)
    else:
        nmap = load_map(map_file) if map_file else choose_map(bvh)
        missing = [k for k in LANDMARKS if k not in nmap.joints]
        if missing:
            raise ParseError(f"the map lacks landmarks {', '.join(missing)}", nmap.name)
        unknown = [v for v in nmap.joints.values() if v not in bvh.names]
        if unknown:
            raise ParseError(f"no joint named {unknown[0]!r} (from the map {nmap.name})", bvh.file)
        tg, _, _ = targets_for(fig, bvh, nmap, fps)
        rt = Retargeter(fig)
        n = tg.hips.shape[0]
        postures = []
        for i in range(n):
            planted = [s for s in SIDES if any(a <= i <= b for a, b in tg.stance[s])]
            rt.solve_frame(tg, i, planted)
            postures.append(Posture.of(fig))
            if progress is not None:
                progress(i + 1, n)
    tl = Timeline(cast={name: {"human": figure_spec, "position": [0.0, 0.0], "heading_deg": 0.0}})
    tl.duration = (len(postures) - 1) / fps
    baked = BakedFigure.from_postures(fig, postures, figure_spec)
    return MotionFile(tl, fps, {name: baked})


__all__ = ["BUILTIN_MAPS", "LANDMARKS", "NameMap", "Retargeter", "choose_map", "import_bvh", "load_map"]

