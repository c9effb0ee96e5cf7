"""Staged posture planning (issue 16; book §5.5, spec §6.1 item 5): minimum disturbance.

The stages, each tried only when the one before has not reached the target, every posture
collision-free (:mod:`jackpy.planning.collision_reach`) and balanced (centre of mass over the
support polygon of the feet):

1. ``arm``: the arm chain from the clavicle (torso, pelvis and feet fixed);
2. ``torso``: the chain from the lowest spine joint (the spine bends and twists, pelvis fixed);
3. ``pelvis`` (knees bent, balance kept): the figure rooted at the heel of the foot on the reaching
   side, a strict-priority IK keeps the other foot where it stands (level 0), the centre of mass
   above the middle of the feet (level 1) and drives the hand over the whole chain from the
   standing ankle through knee, hip and spine to the arm (level 2); then the collision-free arm
   search from that posture. When that does not reach, the pelvis is lowered in 5 cm steps (up to
   :data:`MAX_DROP`) and, as in a squat, moved back by 0, 0.5 or 1 times the drop (the ankles
   dorsiflex only 20°), both feet held by the IK (level 0), the centre of mass over the feet by the
   spine (level 1), the hand by the torso and arm (level 2); the smallest drop that reaches wins;
4. ``step``: the whole body through the behaviors with stepping on (the current balance stepper,
   :func:`jackpy.analysis.reach.point_reach` mode ``"step"``).

:func:`staged_reach` returns the stage that succeeded (None when none did, with the nearest
posture of all stages) and every attempt.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from jackpy import ik
from jackpy.analysis.parts import figure_parts
from jackpy.analysis.reach import REACH_TOLERANCE, PointReach, Posture, _com_margin, point_reach
from jackpy.peabody.model import Figure

#: how the torso and pelvis stages solve their priority levels (``ik.solve``'s ``priorities``):
#: the bounded default. (With bounds frozen on the met feet and COM levels' in-tolerance gradient,
#: the pelvis stage's 40 cm reach below the hand ended with both knees straight; the bounded step
#: no longer freezes while the held levels are met, docs/ik.md)
PRIORITIES = "bounded"
STAGES = ("arm", "torso", "pelvis", "step")
#: how the report names each stage
STAGE_TEXT = {"arm": "arm only", "torso": "arm and torso", "pelvis": "knees bent (pelvis lowered), balanced",
              "step": "a step towards the target"}
#: the pelvis stage lowers the pelvis by up to this much (m), in :data:`DROP_STEP` steps
MAX_DROP = 0.45
DROP_STEP = 0.05
#: the feet may slide at most this much (m) in the pelvis stage
FEET_TOLERANCE = 0.01


@dataclass
class StagedReach:
    """The ``stage`` that reached the target (None: none did), its ``result`` (else the nearest
    attempt's) and every ``(stage, result)`` attempt in order."""

    stage: str | None
    result: PointReach
    attempts: list[tuple[str, PointReach]] = field(default_factory=list)

    def describe(self) -> str:
        how = f"by the {self.stage} stage ({STAGE_TEXT[self.stage]})" if self.stage else "by no stage"
        return f"{self.result.describe()} {how}"


def _torso_joint(figure: Figure, hand_segment: str) -> str:
    """The first joint on the way from the root to the hand (the lowest spine joint of a human)."""
    kin = figure.kinematics()
    path = kin.seg_moved_by_dof[kin.segment_index[hand_segment]]
    joints = [kin.joint_names[j] for j in np.unique(kin.dof_joint[path])]
    return min(joints, key=lambda n: int(np.flatnonzero(kin.dof_joint == kin.joint_names.index(n))[0]))


def _balanced(figure: Figure, r: PointReach) -> bool:
    if r.posture is None:
        return False
    if r.com_margin is None:
        r.com_margin = _com_margin(figure, r.posture)
    return r.com_margin <= 0.0


def staged_reach(figure: Figure, target: np.ndarray, hand: str = "right", obstacles: Sequence[Figure] = (),
                 target_object: str | None = None, stages: Sequence[str] = STAGES,
                 tolerance: float = REACH_TOLERANCE, restarts: int = 8,
                 contact_tolerance: float | None = None) -> StagedReach:
    """Reach ``target`` (world, metres) with ``hand`` by the cascade of ``stages`` (module
    docstring) against ``obstacles`` (no segment deeper than ``contact_tolerance`` metres into one,
    default :data:`jackpy.planning.collision_reach.CONTACT_TOLERANCE`); the figure's posture is
    left unchanged."""
    target = np.asarray(target, dtype=float).reshape(3)
    obstacles = list(obstacles)
    h = figure_parts(figure).hands[hand]
    attempts: list[tuple[str, PointReach]] = []
    for stage in stages:
        if stage == "arm":
            r = point_reach(figure, target, hand, obstacles=obstacles, target_object=target_object,
                            tolerance=tolerance, restarts=restarts, contact_tolerance=contact_tolerance)
        elif stage == "torso":
            r = point_reach(figure, target, hand, start_joint=_torso_joint(figure, h.segment), obstacles=obstacles,
                            target_object=target_object, tolerance=tolerance, restarts=restarts,
                            contact_tolerance=contact_tolerance)
        elif stage == "pelvis":
            r = _pelvis_stage(figure, target, hand, obstacles, target_object, tolerance, contact_tolerance)
        elif stage == "step":
            r = point_reach(figure, target, hand, mode="step", obstacles=obstacles, target_object=target_object,
                            tolerance=tolerance, restarts=restarts, contact_tolerance=contact_tolerance)
        else:
            raise ValueError(f"reach stage must be one of {STAGES}, not {stage!r}")
        r.mode = stage
        attempts.append((stage, r))
        if r.reached and _balanced(figure, r):
            return StagedReach(stage, r, attempts)
    best = min((r for _, r in attempts if r.posture is not None), key=lambda r: r.shortfall, default=attempts[-1][1])
    return StagedReach(None, best, attempts)


def _pelvis_stage(figure: Figure, target: np.ndarray, hand: str, obstacles: list[Figure],
                  target_object: str | None, tolerance: float, contact_tolerance: float | None) -> PointReach:
    """The whole-body knee-bend IK (:func:`_knees_ik`); when that posture does not reach (or
    passes into an object), the pelvis-drop search (:func:`_pelvis_drops`)."""
    r = _knees_ik(figure, target, hand, obstacles, target_object, tolerance, contact_tolerance)
    if r is not None and r.reached:
        return r
    drops = _pelvis_drops(figure, target, hand, obstacles, target_object, tolerance, contact_tolerance)
    if r is not None and r.posture is not None and (drops.posture is None or r.shortfall < drops.shortfall):
        return r
    return drops


def _knees_ik(figure: Figure, target: np.ndarray, hand: str, obstacles: list[Figure],
              target_object: str | None, tolerance: float, contact_tolerance: float | None) -> PointReach | None:
    """Rooted at the heel of the foot on the reaching side (as Jack roots a figure at the dominant
    foot), a strict-priority IK: the other foot's heel pose (level 0: it stays where it stands),
    the centre of mass above the middle of the feet (level 1), the hand on the target over the
    whole chain from the standing ankle: ankle, knee, hip, spine, arm (level 2). Then the
    collision-free arm search from that posture. None when the other foot slides or the posture
    is not balanced."""
    from jackpy.behaviors.anatomy import human_anatomy

    h = figure_parts(figure).hands[hand]
    feet = human_anatomy(figure).feet
    if hand not in feet or len(feet) != 2:
        return None
    other = next(s for s in feet if s != hand)
    fig = copy.deepcopy(figure)
    heel = {s: fig.site_world(*f.heel).copy() for s, f in feet.items()}
    middle = np.mean([heel[s][:3, 3] for s in feet] + [fig.site_world(*f.toe)[:3, 3] for f in feet.values()], axis=0)
    fig.reroot(*feet[hand].heel)
    ankle = f"{hand}_ankle" if f"{hand}_ankle" in fig.joints else feet[hand].joints[-2]
    problem = ik.Problem(fig)
    problem.add(ik.PositionOrientation(".".join(feet[other].heel), heel[other], chain=ankle), level=0)
    problem.add(ik.CentreOfMass(middle), level=1)
    problem.add(ik.Position(f"{h.segment}.{h.site}", target, chain=ankle), level=2)
    ik.solve(problem, max_iterations=300, tol_position=tolerance / 5, priorities=PRIORITIES)
    slid = float(np.linalg.norm(fig.site_world(*feet[other].heel)[:3, 3] - heel[other][:3, 3]))
    if slid > FEET_TOLERANCE or _com_margin(fig, Posture.of(fig)) > 0.0:
        return None
    r = point_reach(fig, target, hand, obstacles=obstacles, target_object=target_object, tolerance=tolerance,
                    restarts=4, contact_tolerance=contact_tolerance)
    if r.posture is None:
        return None
    r.com_margin = _com_margin(fig, r.posture)
    return r if r.com_margin <= 0.0 else None


def _pelvis_drops(figure: Figure, target: np.ndarray, hand: str, obstacles: list[Figure],
                  target_object: str | None, tolerance: float, contact_tolerance: float | None) -> PointReach:
    from jackpy.behaviors.anatomy import human_anatomy

    h = figure_parts(figure).hands[hand]
    feet = human_anatomy(figure).feet
    fig = copy.deepcopy(figure)
    start = Posture.of(fig)
    heel = {s: fig.site_world(*f.heel).copy() for s, f in feet.items()}
    middle = np.mean([heel[s][:3, 3] for s in feet] + [fig.site_world(*f.toe)[:3, 3] for f in feet.values()], axis=0)
    torso = _torso_joint(fig, h.segment)
    best: PointReach | None = None
    forward = np.mean([f.forward for f in feet.values()], axis=0)
    forward = heel[next(iter(feet))][:3, :3] @ forward
    forward[1] = 0.0
    forward /= max(np.linalg.norm(forward), 1e-9)
    spine = [j for j in fig.joints if j.startswith(("l", "t", "c")) and j[1].isdigit()]
    tries = [(d, b) for d in np.arange(DROP_STEP, MAX_DROP + 1e-9, DROP_STEP) for b in (0.0, 0.5, 1.0)]
    for drop, back in tries:
        start.apply(fig)
        loc = fig.location.copy()
        loc[:3, 3] += np.array([0.0, -drop, 0.0]) - back * drop * forward
        fig.location = loc
        problem = ik.Problem(fig)
        for s, f in feet.items():
            problem.add(ik.PositionOrientation(f"{f.heel[0]}.{f.heel[1]}", heel[s], chain=f.joints[0]), level=0)
        problem.add(ik.CentreOfMass(middle, chain=spine), level=1)
        problem.add(ik.Position(f"{h.segment}.{h.site}", target, chain=torso), level=2)
        ik.solve(problem, max_iterations=200, tol_position=tolerance / 5, priorities=PRIORITIES)
        slid = max(float(np.linalg.norm(fig.site_world(*f.heel)[:3, 3] - heel[s][:3, 3])) for s, f in feet.items())
        q = fig.q
        if slid > FEET_TOLERANCE or np.any(q < fig.lower - 1e-9) or np.any(q > fig.upper + 1e-9):
            continue
        r = point_reach(fig, target, hand, obstacles=obstacles, target_object=target_object, tolerance=tolerance,
                        restarts=4, contact_tolerance=contact_tolerance)
        if r.posture is None:
            continue
        r.com_margin = _com_margin(fig, r.posture)
        if r.com_margin > 0.0:
            continue
        if best is None or r.shortfall < best.shortfall:
            best = r
        if r.reached:
            break
    if best is None:
        r = point_reach(figure, target, hand, obstacles=obstacles, target_object=target_object, tolerance=tolerance,
                        restarts=0, contact_tolerance=contact_tolerance)
        r.reached = False
        return r
    return best
