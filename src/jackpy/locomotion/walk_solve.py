"""Postures of a walk from its targets with :mod:`jackpy.ik`, and the baked motion.

The pelvis centre is the root and is placed at its target; each leg is solved for a 6-D goal on
the foot's ball site (position and orientation of the foot), a toe-tip position goal (on the floor
while the toes bend at the ball) and a knee hint ahead of the leg; each arm for a wrist goal on
the swinging arm line (shoulder swing about the pelvis's lateral axis, elbow slightly bent).
Every solve is warm-started from the previous frame and keeps the joints within their limits.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from jackpy.locomotion.walk_gait import MAX_PITCH, SIDES, GaitParams, rot_x, toes_flat_tip
from jackpy.locomotion.walk_path import FrameTargets, Walk

ITERATIONS = 40
#: a stance foot's ball site within this of its target (m) is reached; else the heel rises by
#: HEEL_RAISE_STEP (rad) at a time
REACHED = 1e-3
HEEL_RAISE_STEP = np.radians(2.0)


class WalkSolver:
    """Poses ``figure`` (a standard human) frame by frame from :class:`FrameTargets`."""

    def __init__(self, figure, p: GaitParams) -> None:
        from jackpy.ik import Problem
        from jackpy.ik.goals import Position, PositionOrientation

        self.figure, self.p = figure, p
        q0, loc0 = figure.q, figure.location.copy()
        figure.q = np.zeros_like(q0)
        figure.reroot("pelvis", "centre")
        figure.location = np.eye(4)  # rest frames measured facing +z, whatever the figure did before
        self.pelvis_rest = figure.site_world("pelvis", "centre")[:3, :3].copy()
        floor = figure.site_world("left_foot", "heel")[1, 3]
        self.ball_rel = {}
        for side in SIDES:
            f = f"{side}_foot"
            ank = figure.site_world(f"{side}_shank", "ankle")[:3, 3]
            F = np.eye(4)
            F[:3, 3] = [ank[0], floor, ank[2]]
            self.ball_rel[side] = np.linalg.inv(F) @ figure.site_world(f, "ball")
        self.tips = {s: np.linalg.inv(self._floor_frame(figure, s, floor)) @ np.append(
            figure.site_world(f"{s}_toes", "tip")[:3, 3], 1.0) for s in SIDES}
        self.pelvis_inv = np.linalg.inv(figure.site_world("pelvis", "centre"))
        self.wrist_rel = {s: self.pelvis_inv @ np.append(figure.site_world(f"{s}_palm", "base")[:3, 3], 1.0)
                          for s in SIDES}
        self.shoulder_rel = {s: self.pelvis_inv @ np.append(figure.site_world(f"{s}_upper_arm", "base")[:3, 3], 1.0)
                             for s in SIDES}
        figure.q = q0
        figure.location = loc0
        leg = {j for j in figure.joints if any(k in j for k in ("hip", "knee", "ankle", "toes"))}
        arm = {j for j in figure.joints if any(k in j for k in ("clavicle", "shoulder", "elbow", "wrist"))}
        groups = set(figure.groups)
        self.legs = Problem(figure)
        self.goals = {}
        for s in SIDES:
            foot = PositionOrientation(f"{s}_foot.ball", np.eye(4), weight=100.0, position_weight=0.8)
            self.goals[f"{s}_foot"] = self.legs.add(foot, 0)
            self.goals[f"{s}_tip"] = self.legs.add(Position(f"{s}_toes.tip", np.zeros(3), weight=10.0), 0)
            self.goals[f"{s}_knee"] = self.legs.add(Position(f"{s}_shank.base", np.zeros(3), weight=0.005), 0)
        self.legs.lock(*sorted(set(figure.joints) - leg), *sorted(groups))
        self.arms = Problem(figure)
        for s in SIDES:
            self.goals[f"{s}_wrist"] = self.arms.add(Position(f"{s}_palm.base", np.zeros(3), weight=1.0), 0)
        arm_members = {j for g in groups - {"spine"} for j in figure.groups[g].joints}
        self.arms.lock(*sorted(set(figure.joints) - arm - arm_members), "spine")

    @staticmethod
    def _floor_frame(figure, side: str, floor: float) -> np.ndarray:
        ank = figure.site_world(f"{side}_shank", "ankle")[:3, 3]
        F = np.eye(4)
        F[:3, 3] = [ank[0], floor, ank[2]]
        return F

    def pose(self, tg: FrameTargets) -> None:
        from jackpy.ik import solve

        fig, g = self.figure, self.goals
        if tuple(fig.root or ()) != ("pelvis", "centre"):
            fig.reroot("pelvis", "centre")
        loc = np.eye(4)
        loc[:3, :3] = tg.pelvis[:3, :3] @ self.pelvis_rest
        loc[:3, 3] = tg.pelvis[:3, 3]
        fig.location = loc
        for s in SIDES:
            T = tg.feet[s]
            g[f"{s}_foot"].target = T @ self.ball_rel[s]
            tip = (T @ self.tips[s])[:3]
            bend = tg.toes_flat[s]
            if bend > 0.0:
                tip = bend * toes_flat_tip(self.p, T, s) + (1.0 - bend) * tip
            g[f"{s}_tip"].target = tip.copy()
            hip = fig.site_world("pelvis", f"{s}_hip")[:3, 3]
            ank = T[:3, 3]
            fwd = tg.pelvis[:3, 2]
            g[f"{s}_knee"].target = 0.5 * (hip + ank) + 0.04 * fwd
        solve(self.legs, max_iterations=ITERATIONS, tol_position=1e-4, tol_angle=0.2)
        for s in SIDES:
            if tg.phase[s] in ("flat", "ball"):
                self._raise_heel_until_reached(tg, s)
        for s in SIDES:
            sh = self.shoulder_rel[s]
            wr = self.wrist_rel[s] - sh
            R = rot_x(-tg.arm[s])
            w_local = sh[:3] + R @ wr[:3]
            g[f"{s}_wrist"].target = (loc @ np.append(w_local, 1.0))[:3]
        solve(self.arms, max_iterations=10, tol_position=5e-4, tol_angle=1.0)


    def _ball_error(self, tg: FrameTargets, side: str) -> float:
        """Distance (m) of the foot's ball site from its target."""
        want = (tg.feet[side] @ self.ball_rel[side])[:3, 3]
        return float(np.linalg.norm(self.figure.site_world(f"{side}_foot", "ball")[:3, 3] - want))

    def _raise_heel_until_reached(self, tg: FrameTargets, side: str) -> None:
        """The book's rule for a stance foot the leg cannot reach: roll it further about the
        ball-of-foot joint (toes flat) until the solved foot meets its target. It binds where the
        ankle reaches its dorsiflexion limit (20°) before the leg is stretched, as in the late stance
        of a turning step. The raised foot is written back into ``tg`` (phase ``"ball"``)."""
        from jackpy.ik import solve

        if self._ball_error(tg, side) <= REACHED:
            return
        T0 = tg.feet[side]
        pitch0 = float(np.arcsin(np.clip(-T0[1, 2], -1.0, 1.0)))
        mtp = self.p.foot.mtp * np.array([-1.0 if side == "right" else 1.0, 1.0, 1.0])
        pivot = T0[:3, :3] @ mtp + T0[:3, 3]
        for pitch in np.arange(pitch0 + HEEL_RAISE_STEP, MAX_PITCH + 1e-9, HEEL_RAISE_STEP):
            T = T0.copy()
            T[:3, :3] = T0[:3, :3] @ rot_x(pitch - pitch0)
            T[:3, 3] = pivot - T[:3, :3] @ mtp
            tg.feet[side] = T
            self.goals[f"{side}_foot"].target = T @ self.ball_rel[side]
            self.goals[f"{side}_tip"].target = toes_flat_tip(self.p, T, side)
            solve(self.legs, max_iterations=ITERATIONS, tol_position=1e-4, tol_angle=0.2)
            tg.phase[side] = "ball"
            tg.toes_flat[side] = 1.0
            if self._ball_error(tg, side) <= REACHED:
                return


def bake(figure, walk: Walk, fps: float, progress: Callable[[int, int], None] | None = None):
    """Postures (:class:`jackpy.motion.bake.Posture`) of ``figure`` for every frame at ``fps``."""
    from jackpy.motion.bake import Posture

    solver = WalkSolver(figure, walk.p)
    frames = walk.frames(fps)
    out = []
    for i, tg in enumerate(frames):
        solver.pose(tg)
        out.append(Posture.of(figure))
        if progress is not None:
            progress(i + 1, len(frames))
    return out, frames


def motion_file(figure, walk: Walk, fps: float, human: str | None = None, progress=None):
    """A :class:`~jackpy.motion.motion_file.MotionFile` of the walk: its timeline holds the walk as
    a walk motion (:mod:`jackpy.motion.kinds.walk`) of ``figure`` cast where it stands now (so the
    workbench plays and edits it), and the baked frames of the walk solved here."""
    from jackpy.motion.kinds.walk import WalkMotion
    from jackpy.motion.motion_file import BakedFigure, MotionFile
    from jackpy.motion.timeline import Timeline

    c = figure.site_world("pelvis", "centre")
    heading = float(np.degrees(np.arctan2(c[0, 2], c[2, 2])))
    tl = Timeline(cast={figure.name: {"human": human or "male:50", "position": [float(c[0, 3]), float(c[2, 3])],
                                      "heading_deg": heading}})
    tl.add(WalkMotion.of_steps(figure.name, walk.steps, walk.p, label="walk"))
    postures, _ = bake(figure, walk, fps, progress)
    tl.duration = (len(postures) - 1) / fps
    return MotionFile(tl, fps, {figure.name: BakedFigure.from_postures(figure, postures, human)})
