"""Walk motion ([SH5] §5.2.1–5.2.3; issue 13): the figure walks a footstep plan over [t0, t1].

``plan`` is a walk plan (:mod:`jackpy.locomotion.walk_plan`: ``{"steps": [[x, z, heading_rad,
side], ...]}``, world metres; σ_0, σ_1 the standing feet). ``relative`` re-places the plan rigidly
on the floor (a yaw and a shift) so its standing feet are where the figure stands at t0; otherwise
the plan is where the figure goes, from its first two footsteps. Walk time runs from 0 at t0 to the
plan's duration at t1 (:meth:`WalkMotion.of_steps` sets ``t1`` to it; retiming the bar scales the
gait's time).

A walk is a whole-figure motion (track ``walk``; no weight, may not overlap another walk of the
figure). Like the torso motion, which the book drives by forward kinematics, it poses its joints
itself: each step the walk's targets at that time (:class:`~jackpy.locomotion.walk_path.Walk`) are
solved by the locomotion IK (:class:`~jackpy.locomotion.walk_solve.WalkSolver`, the pelvis centre
as root). While it runs the figure's behaviors are suspended except gaze (a gaze motion may aim
the head while walking); after it they resume as they were and the figure stands where the walk
ended (its feet planted there, the balance point under its COM).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.motion.base import Context, Motion, register
from jackpy.motion.interpolate import pose_lerp

if TYPE_CHECKING:
    from jackpy.locomotion.walk_path import Footstep, Walk
    from jackpy.locomotion.walk_solve import WalkSolver

#: behaviors left running during a walk (they move only the head and eyes)
KEEP = ("gaze",)
#: per figure (by id): the figure, its solver, the last walk (plan key, Walk) -- built on first use,
#: never part of the baked state (``run`` holds only plain data)
_CACHE: dict[int, list[Any]] = {}
CACHE_SIZE = 8


@register
@dataclass
class WalkMotion(Motion):
    kind = "walk"
    weighted = False
    plan: dict | None = None
    relative: bool = False

    @property
    def part(self) -> str:
        return "walk"

    def check(self) -> None:
        super().check()
        from jackpy.locomotion.walk_plan import from_data

        if self.plan is None:
            raise ValueError("walk motion: needs a plan {'steps': [[x, z, heading, side], ...]}")
        from_data(self.plan, "walk motion: plan")

    @classmethod
    def of_steps(cls, figure: str, steps: list["Footstep"], p: Any, t0: float = 0.0, **kw: Any) -> "WalkMotion":
        """The walk over ``steps`` with gait ``p`` (:class:`GaitParams`) from ``t0`` (s); ``t1`` is
        ``t0`` plus the walk's duration."""
        from jackpy.locomotion import walk_path
        from jackpy.locomotion.walk_plan import to_data

        return cls(figure=figure, t0=float(t0), t1=float(t0) + walk_path.duration(steps, p), plan=to_data(steps), **kw)

    # ----- running ----------------------------------------------------------------------------------
    def pre(self, ctx: Context) -> None:
        from jackpy.locomotion.walk_plan import from_data, to_data

        loop = ctx.loop
        steps = from_data(self.plan, "walk motion: plan")
        if self.relative:
            steps = _placed_at(steps, _standing(loop))
        steps[:2] = [_on_the_floor(loop.figure, f) for f in steps[:2]]
        self.run["steps"] = to_data(steps)["steps"]
        fig = loop.figure
        if tuple(fig.root or ()) != ("pelvis", "centre"):
            fig.reroot("pelvis", "centre")
        self.run["q0"], self.run["loc0"] = fig.q.tolist(), fig.location.tolist()
        self.run["behaviors"] = [b.enabled for b in loop.behaviors]
        for b in loop.behaviors:
            if b.name not in KEEP:
                b.enabled = False

    def sample(self, ctx: Context, s: float) -> float:
        return float(s) * self._walk(ctx)[1].duration

    def write(self, ctx: Context, value: float, weight: float) -> None:
        from jackpy.locomotion.walk_gait import START_TIME, smooth

        solver, walk = self._walk(ctx)
        fig = ctx.figure
        solver.pose(walk.at(float(value)))
        ctx.loop.state.root = "pelvis"
        w = float(smooth(float(value) / START_TIME))
        if w < 1.0:  # from the posture at t0 into the walk's, over its weight shift (feet standing)
            fig.q = (1.0 - w) * np.array(self.run["q0"]) + w * fig.q
            fig.location = pose_lerp(np.array(self.run["loc0"]), fig.location, w)

    def post(self, ctx: Context) -> None:
        loop = ctx.loop
        for b, on in zip(loop.behaviors, self.run.get("behaviors", [])):
            b.enabled = on
        loop.reset_state()

    def _walk(self, ctx: Context) -> tuple["WalkSolver", "Walk"]:
        """The solver of this figure and the walk of this run (built once, then reused)."""
        from jackpy.locomotion.walk_gait import GaitParams
        from jackpy.locomotion.walk_path import Footstep, Walk
        from jackpy.locomotion.walk_solve import WalkSolver

        fig = ctx.figure
        entry = _CACHE.get(id(fig))
        if entry is None or entry[0] is not fig:
            if tuple(fig.root or ()) != ("pelvis", "centre"):
                fig.reroot("pelvis", "centre")
            while len(_CACHE) >= CACHE_SIZE:  # the oldest (a player's earlier bakes make twins)
                del _CACHE[next(iter(_CACHE))]
            entry = _CACHE[id(fig)] = [fig, WalkSolver(fig, GaitParams.for_figure(fig)), None]
        solver = entry[1]
        key = repr(self.run["steps"])
        if entry[2] is None or entry[2][0] != key:
            entry[2] = (key, Walk([Footstep(*row) for row in self.run["steps"]], solver.p))
        return solver, entry[2][1]


#: a planned standing foot this near the figure's own (m) is taken where the figure's foot is
SNAP = 0.15


def _on_the_floor(fig: Any, f: "Footstep") -> "Footstep":
    """Standing footstep ``f`` moved onto the figure's own foot of that side (ankle floor point,
    heel-to-toe heading) when that is within ``SNAP``: the walk then starts without sliding it."""
    from jackpy.locomotion.walk_path import Footstep

    a = fig.site_world(f"{f.side}_shank", "ankle")[:3, 3][[0, 2]]
    if np.linalg.norm(a - f.point) > SNAP:
        return f
    d = fig.site_world(f"{f.side}_foot", "toe")[:3, 3] - fig.site_world(f"{f.side}_foot", "heel")[:3, 3]
    return Footstep(float(a[0]), float(a[1]), float(np.arctan2(d[0], d[2])), f.side)


def _standing(loop: Any) -> tuple[np.ndarray, float]:
    """Floor point (x, z) between the ankles and the mean heel-to-toe heading (rad) of the
    figure's feet now."""
    fig = loop.figure
    pts, yaws = [], []
    for side in ("left", "right"):
        pts.append(fig.site_world(f"{side}_shank", "ankle")[:3, 3][[0, 2]])
        d = fig.site_world(f"{side}_foot", "toe")[:3, 3] - fig.site_world(f"{side}_foot", "heel")[:3, 3]
        yaws.append(float(np.arctan2(d[0], d[2])))
    d = (yaws[1] - yaws[0] + np.pi) % (2 * np.pi) - np.pi
    return 0.5 * (pts[0] + pts[1]), float(yaws[0] + 0.5 * d)


def _placed_at(steps: list["Footstep"], stand: tuple[np.ndarray, float]) -> list["Footstep"]:
    """``steps`` turned and shifted on the floor so their standing feet's middle and heading are
    ``stand`` ((x, z), heading)."""
    from jackpy.locomotion.walk_path import Footstep

    c0 = 0.5 * (steps[0].point + steps[1].point)
    d = (steps[1].psi - steps[0].psi + np.pi) % (2 * np.pi) - np.pi
    turn = stand[1] - (steps[0].psi + 0.5 * d)
    c, s = np.cos(turn), np.sin(turn)
    R = np.array([[c, s], [-s, c]])  # yaw by ``turn`` about +y, top view (x, z)
    out = []
    for f in steps:
        q = stand[0] + R @ (f.point - c0)
        out.append(Footstep(float(q[0]), float(q[1]), float(f.psi + turn), f.side))
    return out
