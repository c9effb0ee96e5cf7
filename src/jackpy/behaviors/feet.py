"""Feet: planted feet stay put ([SH4] §4.1.1 Table 4.2; [PB91] §4.1, §6; behaviors.md §2.3).

Each foot not rooting the figure gets a *toe constraint* at its ball site and a *heel constraint*:

- ``pivot`` (default): ball position + sole flat (foot up = world up), yaw free;
- ``hold``: ball position and full orientation (for a foot off the floor or one being dragged);
- heel ``floor`` (default): the heel site on the floor plane (point-to-plane, so it may slide with
  the foot); ``free``: no heel constraint, the heel may rise.

The rooted foot needs no goal: the IK cannot move the root. Feet goals are on the highest priority
level, so COM, pelvis and torso goals never pull a planted foot. After the solve a pivoting foot's
stored goal takes the yaw it turned to (its position stays), so the support polygon follows it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param
from jackpy.ik.goals import Orientation, Plane, Position

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame

UP = np.array([0.0, 1.0, 0.0])


@dataclass
class FeetParams:
    weight: float = param(10.0, "weight of the toe and heel constraints", "", (0.0, 1e4))
    level: int = param(0, "priority level of the feet goals (0 = highest)", "", (0, 3))
    anchor_rate: float = param(0.003, "largest correction per frame of a rooting foot off its planted goal",
                               "mm", (0.0, 0.1))


def foot_goals(frame: "Frame", side: str, params: FeetParams | None = None) -> list[tuple]:
    """The (goal, level) entries holding foot ``side`` at its goal for this frame: toe position,
    sole flat (pivot) or full orientation (hold), and the heel on the floor when it is kept there.
    Their names start with the foot's name (``toe left``, ``sole left``, ``heel left``...)."""
    p = params or FeetParams()
    st, spec = frame.state, frame.anatomy.feet[side]
    fs = st.feet[side]
    ball = f"{spec.ball[0]}.{spec.ball[1]}"
    out: list[tuple] = [(Position(ball, fs.target, weight=p.weight, name=f"toe {side}"), p.level)]
    if fs.mode == "hold":
        out.append((Orientation(ball, fs.target[:3, :3], weight=p.weight, name=f"toe frame {side}"), p.level))
    elif fs.mode == "free":  # a foot peeling off the floor in a step: its orientation follows the leg
        pass
    else:
        up_w = fs.target[:3, :3] @ (frame.figure.site_location(*spec.ball)[:3, :3].T @ spec.up)
        out.append((frame.keep_direction(*spec.ball, spec.up, up_w, p.weight, f"sole {side}"), p.level))
    if fs.heel == "floor":
        heel = frame.loop.heel_point(side, fs.target)
        out.append((Plane(f"{spec.heel[0]}.{spec.heel[1]}", heel, UP, weight=p.weight, name=f"heel {side}"),
                    p.level))
    return out


FOOT_GOALS = ("toe", "toe frame", "sole", "heel")


def replace_foot_goals(frame: "Frame", side: str, hold: bool) -> None:
    """Drop foot ``side``'s goals from this frame's body pass and, with ``hold``, add them again
    from its current state. A behavior that re-roots the figure or changes a foot's mode after the
    feet behavior ran this frame calls it, so the new root carries no goals (the IK cannot move
    it) and the former root is held from this very frame (else it is free for a frame and flies)."""
    names = {f"{n} {side}" for n in FOOT_GOALS}
    frame.body[:] = [(g, lv) for g, lv in frame.body if getattr(g, "name", None) not in names]
    if hold:
        params = None
        for b in frame.loop.behaviors:
            if isinstance(b, Feet):
                params = b.params
        frame.body.extend(foot_goals(frame, side, params))


class Feet(BehaviorBase):
    """Holds every non-root foot at its goal (toe constraint + heel on floor)."""

    name = "feet"
    order = 20

    def __init__(self, params: FeetParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or FeetParams(), enabled)

    def update(self, frame: "Frame") -> None:
        st, p = frame.state, self.params
        self._anchor_root(frame)
        for side in frame.anatomy.feet:
            if side != st.root:
                frame.body.extend(foot_goals(frame, side, p))

    def _anchor_root(self, frame: "Frame") -> None:
        """The IK cannot move the root ([SH4] §4.1.2), so a rooting foot that is off its planted
        goal (a foot rooted while the IK still trailed it) would stay off for good: move the
        figure, at most ``anchor_rate`` per frame, until the root foot's ball is on its goal."""
        st = frame.state
        if st.root not in frame.anatomy.feet:
            return
        spec = frame.anatomy.feet[st.root]
        err = st.feet[st.root].target[:3, 3] - frame.site(*spec.ball)[:3, 3]
        n = float(np.linalg.norm(err))
        if n < 1e-7:
            return
        loc = frame.figure.location.copy()
        loc[:3, 3] += err * min(1.0, self.params.anchor_rate / n)
        frame.figure.location = loc
        frame._refresh()

    def finish(self, frame: "Frame") -> None:
        for side, spec in frame.anatomy.feet.items():
            fs = frame.state.feet[side]
            if fs.mode == "pivot":
                now = frame.site(*spec.ball)
                fs.target = np.vstack([np.hstack([now[:3, :3], fs.target[:3, 3:4]]), [0, 0, 0, 1]])
