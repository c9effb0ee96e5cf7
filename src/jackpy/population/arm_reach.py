"""Arm-only point reach on a figure cut down to the reaching arm: the same IK problem as
:func:`jackpy.analysis.reach.point_reach` in ``"arm"`` mode (a position goal on the hand's grip
site over the chain from the clavicle, the same joints, limits and shoulder-complex and forearm
groups), solved on a figure of the eight arm segments hung from ``t1`` where the full figure holds
it. Forward kinematics then walks 8 segments instead of 74: several times faster per iteration,
and the same answer (the torso, legs and other arm do not move in arm mode).

The solve uses the IK's projected-BFGS step (:data:`STEP`). A solve may start from a given arm posture (``start``): a sweep starts every body from the mean
body's solution for that target, the same for every body whatever process evaluates it.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass

import numpy as np

from jackpy import ik
from jackpy.analysis.reach import REACH_TOLERANCE
from jackpy.peabody.model import Figure, Segment

ARM_SEGMENTS = ("clavicle", "shoulder_frame", "upper_arm", "forearm", "forearm_mid", "forearm_distal", "palm")
ARM_GROUPS = ("shoulder_complex", "forearm")
ANCHOR = "t1"
#: the IK's step rule: the book's projected BFGS. On arm targets out of reach the default bounded
#: Gauss-Newton step runs to the iteration limit (300) where BFGS stops after 40-80 iterations at
#: the same shortfall (to 0.1 mm), so a sweep uses BFGS
STEP = "bfgs"


@dataclass
class ArmReach:
    """Outcome: ``reached`` within the tolerance, ``shortfall`` (m), the arm's final displacements
    ``q`` (arm figure order) and group angles."""

    reached: bool
    shortfall: float
    q: np.ndarray
    group_angles: dict[str, np.ndarray]


def arm_figure(figure: Figure, hand: str) -> Figure:
    """The reaching arm of a standard human at its current posture, hung from ``t1`` (world fixed)."""
    side = hand
    arm = Figure(f"{figure.name}.{side}_arm")
    names = [f"{side}_{s}" for s in ARM_SEGMENTS]
    anchor = figure.segment(ANCHOR)
    arm.add_segment(Segment(ANCHOR, sites={k: anchor.sites[k] for k in ("base", f"{side}_clavicle")}))
    for n in names:
        s = figure.segment(n)
        arm.add_segment(Segment(n, sites=s.sites))
    for j in figure.joints.values():
        if j.to_seg in names:
            arm.add_joint(copy.deepcopy(j))
    arm.root = (ANCHOR, "base")
    arm.location = figure.site_world(ANCHOR, "base")
    for g in (f"{side}_{n}" for n in ARM_GROUPS):
        if g in figure.groups:
            group = copy.deepcopy(figure.groups[g])
            arm.groups[g] = group
    return arm


def reach(arm: Figure, target: np.ndarray, hand: str, tolerance: float = REACH_TOLERANCE,
          start: tuple[np.ndarray, dict[str, np.ndarray]] | None = None, max_iterations: int = 300) -> ArmReach:
    """Reach ``target`` (world, m) with the arm figure's grip; the arm is left in the final posture."""
    h = figure_parts_of_arm(hand)
    if start is not None:
        q, angles = start
        arm.q = q
        for n, a in angles.items():
            arm.groups[n].angles = a.copy()
    problem = ik.Problem(arm)
    problem.add(ik.Position(f"{h[0]}.{h[1]}", np.asarray(target, dtype=float), chain=h[2]))
    ik.solve(problem, max_iterations=max_iterations, tol_position=tolerance / 5, step=STEP)
    position = arm.site_world(h[0], h[1])[:3, 3]
    shortfall = float(np.linalg.norm(position - target))
    return ArmReach(shortfall <= tolerance, shortfall, arm.q,
                    {n: np.array(g.angles, dtype=float) for n, g in arm.groups.items()})


def apply_to_figure(arm: Figure, figure: Figure) -> None:
    """Give ``figure`` the arm figure's joint displacements and group angles (the reach posture)."""
    for name, j in arm.joints.items():
        figure.joint(name).displacement = j.displacement.copy()
    for name, g in arm.groups.items():
        figure.groups[name].angles = np.array(g.angles, dtype=float)


def figure_parts_of_arm(hand: str) -> tuple[str, str, str]:
    """(segment, site, first chain joint) of the standard human's reaching hand."""
    return f"{hand}_palm", "grip", f"{hand}_clavicle"

