"""Knee and elbow limit springs ([SH4] §4.1.1 and footnote; behaviors.md §2.10).

A joint straightened to its limit sees a zero gradient and traps the IK; a fully extended knee or
elbow also looks like "attention" rather than "at ease". Each spring adds to the pass that moves
its joint the potential ``weight * max(0, margin - d)^2`` with ``d = sign * (theta - extension)``
the flexion (rad) away from the extension limit, so the joint stays ``margin`` (10° by default)
short of lock unless a goal explicitly pulls harder.

:class:`LimitSpring` is an IK goal (residual and exact Jacobian). The joint angle is read from the
forward pass: for a one-DOF rotational joint the displacement is the rotation between its from-
and to-site frames about its axis.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param
from jackpy.errors import FigureError
from jackpy.ik.goals import Context, Goal, GoalEval

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame
    from jackpy.peabody.model import Figure


class LimitSpring(Goal):
    """Keep the rotational DOF of one-DOF ``joint`` at least ``margin`` (rad) of flexion away from
    ``extension`` (rad); ``sign`` (+1/-1) is the direction of flexion.

    A registered goal kind, so the loop keeps a spring's compiled form across frames (the joint is
    part of its name)."""

    kind = "limit-spring"
    targets = ("extension",)
    params = ("sign", "margin")

    def __init__(self, joint: str, extension: float, sign: float, margin: float, weight: float = 1.0) -> None:
        self.joint_name = joint
        self.extension = float(extension)
        self.sign = float(sign)
        self.margin = float(margin)
        self.weight = float(weight)
        self.name = f"spring {joint}"

    def bind(self, figure: "Figure") -> None:
        j = figure.joint(self.joint_name)
        if j.ndof != 1 or j.dofs[0].kind != "R":
            raise FigureError(f"limit spring needs a one-DOF rotational joint, {j.name!r} is {j.type_text()}")
        kin = figure.kinematics()
        self.dof = figure.joint_dof_slice(j.name).start
        self.axis = j.dofs[0].axis
        self.seg_from, self.seg_to = kin.segment_index[j.from_seg], kin.segment_index[j.to_seg]
        self.L_from = figure.site_location(j.from_seg, j.from_site)
        self.L_to = figure.site_location(j.to_seg, j.to_site)
        self._mask = np.zeros(kin.ndof, dtype=bool)
        self._mask[self.dof] = True

    def chain_mask(self) -> np.ndarray:
        return self._mask

    def angle(self, ctx: Context) -> float:
        """The joint's displacement (rad) at the posture of ``ctx``."""
        a = ctx.fk.segments[self.seg_from] @ self.L_from
        b = ctx.fk.segments[self.seg_to] @ self.L_to
        d = a[:3, :3].T @ b[:3, :3]
        s = 0.5 * np.array([d[2, 1] - d[1, 2], d[0, 2] - d[2, 0], d[1, 0] - d[0, 1]]) @ self.axis
        return float(np.arctan2(s, 0.5 * (np.trace(d) - 1.0)))

    def evaluate(self, ctx: Context) -> GoalEval:
        theta = self.angle(ctx)
        short = self.margin - self.sign * (theta - self.extension)
        J = np.zeros((1, ctx.cols.size))
        if short <= 0.0:
            return GoalEval(np.zeros(1), J)
        J[0, ctx.cols == self.dof] = -self.sign
        return GoalEval(np.array([short]), J, degrees=float(np.degrees(short)))

    def to_dict(self) -> dict:
        return {**super().to_dict(), "joint": self.joint_name}


@dataclass
class LimitSpringsParams:
    margin: float = param(np.radians(10.0), "how far short of full extension knees and elbows stay", "deg",
                          (0.0, np.radians(45.0)))
    weight: float = param(0.05, "spring weight (larger: harder to straighten)", "", (0.0, 1e4))
    knees: bool = param(True, "springs on the knees")
    elbows: bool = param(True, "springs on the elbows")


class LimitSprings(BehaviorBase):
    """Adds a limit spring for each knee (body pass) and elbow (its arm pass)."""

    name = "limit springs"
    order = 90

    def __init__(self, params: LimitSpringsParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or LimitSpringsParams(), enabled)

    def update(self, frame: "Frame") -> None:
        p = self.params
        for joint, _, ext, sign in frame.anatomy.springs:
            spring = LimitSpring(joint, ext, sign, p.margin, p.weight)
            side = next((s for s, h in frame.anatomy.hands.items() if joint in h.arm_joints), None)
            if side is not None:
                if p.elbows and frame.arms[side]:
                    frame.arms[side].append((spring, max(lv for _, lv in frame.arms[side])))
            elif p.knees:
                frame.body.append((spring, 1))
