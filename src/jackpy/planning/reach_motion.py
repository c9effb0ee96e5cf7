"""Collision-free reach motion (issue 16; book §5.4, spec §6.2): from the current posture to a
reach posture through openings and around obstacles, planned by OMPL's RRT-Connect over the arm's
joint space (:class:`~jackpy.planning.arm_space.ArmSpace`: shoulder complex, elbow, forearm twist,
wrist, with the figure's limits).

1. **Goal by IK.** The IK over the arm chain from the start posture and from ``goal_restarts``
   random postures of the chain (fixed seed); every end posture that puts the hand within the reach
   tolerance and passes the collision check is a goal state (up to :data:`MAX_GOALS`); RRT-Connect
   grows a tree from the start and one from the goals.
2. **Collision check of every state** (:class:`ArmCollision`): the arm's segments (full figure
   geometry, python-fcl BVHs, ``ClearanceChecker``) against the workplace objects, shrunk by the
   contact tolerance (default 0: no contact at all), the palm allowed on the target's own object.
   OMPL checks each edge at a joint-space resolution of :data:`RESOLUTION` of the space's extent.
3. **Shortcut and smooth:** OMPL's path simplifier (vertex reduction, partial shortcuts, B-spline
   smoothing; every change re-checked), a fixed number of steps, so the same seed gives the same
   path.
4. **Checked at hand steps:** the path is cut into frames no more than ``step`` (5 mm) of hand
   travel apart (:func:`frames_at_hand_steps`) and every frame is checked; a path that fails
   (a collision between OMPL's edge checks) is planned again with a resolution four times finer.

Seed OMPL's generator (:func:`plan_reach_motion` does, from ``seed``) for a repeatable plan.
Self-collision is not checked (as in the reach verdicts: the joint limits keep the arm off the body).
"""

from __future__ import annotations

import copy
import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from jackpy.analysis.clearance import ClearanceChecker
from jackpy.analysis.reach import REACH_TOLERANCE, Posture
from jackpy.errors import JackpyError
from jackpy.peabody.model import Figure
from jackpy.planning.arm_space import ArmSpace

#: at most this many IK goal postures are handed to the planner
MAX_GOALS = 4
#: OMPL edge-check resolution, a fraction of the joint space's extent (about 2.5 cm of hand travel
#: at full stretch)
RESOLUTION = 0.005
#: the planner grows the arm's segments by this much (m), so that nothing slips into an object
#: between its edge checks; the checked frames use the arm as it is
PLAN_MARGIN = 0.005
#: RRT-Connect's extension step (joint-space distance, rad; about 15 cm of hand travel): OMPL's
#: default (a fifth of the extent) cannot grow the goal tree out of the box through the hole
RANGE = 0.25
#: the planner samples the joint ranges of the start and the goals widened by these (rad), one
#: after the other until a path is found (None: the whole range of the limits)
SEARCH_WIDEN = (None,)
#: frames of the checked motion are at most this far apart in hand travel (m)
HAND_STEP = 0.005
#: simplifier steps (fixed, for a repeatable path)
SHORTCUT_STEPS = 200
SMOOTH_STEPS = 5


def _ompl():
    try:
        from ompl import base as ob, geometric as og, util as ou
    except ImportError as exc:  # pragma: no cover - the planning extra is installed in CI
        raise JackpyError("reach motion planning needs OMPL: pip install 'jackpy[planning]' (the 'ompl' wheel)") from exc
    return ob, og, ou


class ArmCollision:
    """Is the arm at ``x`` clear of ``obstacles``? The arm's segments (those the chain moves) of a
    private copy of the space's figure, shrunk by ``tolerance`` (m) and grown by ``margin`` (m),
    against every object;
    ``(segment, object)`` pairs in ``allowed`` are ignored. Counts its checks in ``checks``."""

    def __init__(self, space: ArmSpace, obstacles: Sequence[Figure], tolerance: float = 0.0,
                 margin: float = 0.0) -> None:
        self.space = space
        fig = space.figure
        kin = fig.kinematics()
        moved = kin.seg_moved_by_dof[:, np.unique(np.concatenate(
            [space.free_dofs] + [g.dofs for g in space.groups]))].any(axis=1)
        self.segments = {kin.segment_names[i] for i in np.flatnonzero(moved)}
        self.checker = ClearanceChecker(fig, list(obstacles), self_collision=False,
                                        erode=tolerance - margin, segments=self.segments)
        self.allowed: set[tuple[str, str]] = set()
        self.checks = 0

    def allow(self, segment: str, body_prefix: str | None) -> None:
        """Let ``segment`` meet the object ``body_prefix`` (its bodies too)."""
        if body_prefix is None:
            return
        self.allowed |= {(segment, b) for b in self.checker.body_names
                         if b == body_prefix or b.startswith(body_prefix + ".")}

    def collisions(self, x: np.ndarray) -> list[tuple[str, str]]:
        """``(segment, object)`` pairs in collision at ``x`` (allowed pairs left out)."""
        self.checks += 1
        self.checker.update(self.space.q(x))
        return [p for p in self.checker.object_collisions() if p not in self.allowed]

    def free(self, x: np.ndarray) -> bool:
        return self.space.feasible(x) and not self.collisions(x)


def frames_at_hand_steps(space: ArmSpace, waypoints: np.ndarray, step: float = HAND_STEP) -> np.ndarray:
    """The joint-space polyline through ``waypoints`` (N, ndim) cut so that the hand moves at most
    ``step`` metres between consecutive frames (each edge halved until it does); (M, ndim)."""
    out = [waypoints[0]]
    for a, b in zip(waypoints[:-1], waypoints[1:]):
        todo = [(a, b, space.hand_position(a), space.hand_position(b))]
        edge = []
        while todo:
            u, v, pu, pv = todo.pop()
            if np.linalg.norm(pv - pu) <= step:
                edge.append(v)
                continue
            m = (u + v) / 2
            pm = space.hand_position(m)
            todo.append((m, v, pm, pv))  # popped last: the first half is done first
            todo.append((u, m, pu, pm))
        out.extend(edge)
    return np.array(out)


@dataclass
class ReachMotion:
    """A planned reach: ``status`` (``"planned"``, ``"start in collision"``, ``"no free goal"``,
    ``"no path"``), the simplified ``waypoints`` (arm variables), the ``frames`` checked at hand
    steps, the hand's positions along them, the final ``shortfall`` (m), planner ``stats`` and the
    ``space`` (variable names, limits, the figure copy)."""

    status: str
    space: ArmSpace
    target: np.ndarray
    waypoints: np.ndarray
    frames: np.ndarray
    hand: np.ndarray
    shortfall: float
    stats: dict = field(default_factory=dict)
    collisions: list = field(default_factory=list)

    @property
    def planned(self) -> bool:
        return self.status == "planned"

    @property
    def hand_travel(self) -> float:
        """Length (m) of the hand's path."""
        return float(np.linalg.norm(np.diff(self.hand, axis=0), axis=1).sum()) if len(self.hand) > 1 else 0.0

    def postures(self, xs: np.ndarray | None = None) -> list[Posture]:
        """Whole-figure postures for the frames (or for ``xs``)."""
        sp = self.space
        root, loc = tuple(sp.figure.root), sp.figure.location.copy()
        out = []
        for x in self.frames if xs is None else xs:
            groups = {g.group.name: np.array(x[g.x], dtype=float) for g in sp.groups}
            out.append(Posture(root, loc, sp.q(x), groups))
        return out

    def timed(self, fps: float = 30.0, speed: float = 0.5) -> np.ndarray:
        """Arm variables at ``fps`` frames a second with the hand moving at ``speed`` m/s along its
        path (linear in the variables between the checked frames)."""
        if len(self.frames) < 2:
            return self.frames.copy()
        s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(self.hand, axis=0), axis=1))]
        n = max(int(np.ceil(s[-1] / speed * fps)), 1) + 1
        at = np.linspace(0.0, s[-1], n)
        return np.array([np.interp(at, s, self.frames[:, k]) for k in range(self.frames.shape[1])]).T

    def key_tracks(self, fps: float = 30.0, speed: float = 0.5, figure_name: str | None = None) -> list:
        """The motion as the timeline's joint-angle key tracks (``joint:NAME``, one per joint of the
        arm chain, a key per frame of :meth:`timed`, linear between keys): what the workbench's
        timeline plays and edits."""
        from jackpy.motion.keyframes import KeyTrack

        fig = self.space.figure
        xs = self.timed(fps, speed)
        qs = np.array([self.space.q(x) for x in xs]).reshape(len(xs), -1)
        tracks = []
        for jn in self.space.joints:
            sl = fig.joint_dof_slice(jn)
            keys = [(k / fps, qs[k, sl].copy()) for k in range(len(xs))]
            tracks.append(KeyTrack(figure_name or fig.name, f"joint:{jn}", keys))
        return tracks

    def motion_file(self, fps: float = 30.0, speed: float = 0.5, human: str | None = None):
        """A :class:`~jackpy.motion.motion_file.MotionFile` of the motion baked at ``fps`` with the
        hand at ``speed`` m/s (:meth:`timed`), with its timeline of joint key tracks
        (:meth:`key_tracks`; ``human`` as ``male:50`` names the figure's cast)."""
        from jackpy.motion.bake import Posture as Frame
        from jackpy.motion.motion_file import BakedFigure, MotionFile
        from jackpy.motion.timeline import Timeline

        fig = self.space.figure
        xs = self.timed(fps, speed)
        frames = [Frame(self.space.q(x), tuple(fig.root), fig.location.copy()) for x in xs]
        tl = Timeline()
        for track in self.key_tracks(fps, speed):
            tl.add(track)
        if human is not None:
            tl.cast[fig.name] = {"human": human}
        tl.duration = max(len(frames) - 1, 0) / fps
        return MotionFile(tl, fps, {fig.name: BakedFigure.from_postures(fig, frames, human)})

    def describe(self) -> str:
        if not self.planned:
            return f"no reach motion: {self.status}"
        return (f"planned reach motion: {len(self.waypoints)} waypoints, hand travel {self.hand_travel * 100:.0f} cm, "
                f"ends {self.shortfall * 1e3:.0f} mm from the target, {len(self.frames)} frames checked")

    def to_dict(self) -> dict:
        return {"status": self.status, "text": self.describe(), "variables": self.space.names,
                "waypoints": self.waypoints.tolist(), "hand_travel_m": self.hand_travel,
                "shortfall_m": self.shortfall, "frames_checked": len(self.frames), "stats": self.stats,
                "collisions": [list(p) for p in self.collisions]}


def goal_states(space: ArmSpace, collision: ArmCollision, target: np.ndarray, tolerance: float,
                restarts: int, rng: np.random.Generator) -> list[np.ndarray]:
    """Free arm variables with the hand within ``tolerance`` of ``target``: the IK from the start
    and from ``restarts`` random starts (at most :data:`MAX_GOALS`)."""
    out: list[np.ndarray] = []
    for k in range(restarts + 1):
        x = space.solve_ik(target, space.x0 if k == 0 else space.sample(rng), tolerance)
        if np.linalg.norm(space.hand_position(x) - target) <= tolerance and collision.free(x):
            if all(np.linalg.norm(x - g) > 1e-3 for g in out):
                out.append(x)
        if len(out) >= MAX_GOALS:
            break
    space.apply(space.x0)
    return out


def straight_line(space: ArmSpace, x_goal: np.ndarray) -> np.ndarray:
    """The straight joint-space line from the start to ``x_goal`` (two waypoints)."""
    return np.array([space.x0, x_goal])


def plan_reach_motion(figure: Figure, target: np.ndarray, hand: str = "right", obstacles: Sequence[Figure] = (),
                      target_object: str | None = None, contact_tolerance: float = 0.0,
                      start_joint: str | None = None, tolerance: float = REACH_TOLERANCE, seed: int = 0,
                      goal_restarts: int = 16, time_limit: float = 60.0, step: float = HAND_STEP) -> ReachMotion:
    """Plan a collision-free motion of ``figure``'s ``hand`` arm from its posture to ``target``
    (world, m) among ``obstacles`` (module docstring); ``target_object`` may be touched by the
    palm; ``contact_tolerance`` (m) is how deep a segment may press into an object. The figure's
    posture is left unchanged; ``time_limit`` (s) bounds each RRT-Connect run."""
    ob, og, ou = _ompl()
    _seed_ompl(ou, seed)
    target = np.asarray(target, dtype=float).reshape(3)
    space = ArmSpace(copy.deepcopy(figure), hand, start_joint)
    exact = ArmCollision(space, obstacles, contact_tolerance)
    exact.allow(space.site[0], target_object)
    empty = np.zeros((0, space.ndim))
    stats: dict = {"planner": "RRTConnect", "dimensions": space.ndim, "seed": seed}
    checkers = [exact]

    def result(status: str, waypoints=empty, frames=empty, bad=()) -> ReachMotion:
        hand_path = space.hand_positions(frames) if len(frames) else np.zeros((0, 3))
        end = hand_path[-1] if len(hand_path) else space.hand_position(space.x0)
        stats["collision_checks"] = sum(c.checks for c in checkers)
        return ReachMotion(status, space, target, waypoints, frames, hand_path, float(np.linalg.norm(end - target)),
                           stats, list(bad))

    start_hits = exact.collisions(space.x0)
    if start_hits:
        return result("start in collision", bad=start_hits)
    t0 = time.perf_counter()
    # plan with the arm grown by PLAN_MARGIN (room between OMPL's edge checks); where that finds no
    # free goal or start (a target on a surface), with the arm as it is
    for margin in (PLAN_MARGIN, 0.0):
        collision = ArmCollision(space, obstacles, contact_tolerance, margin) if margin else exact
        collision.allow(space.site[0], target_object)
        checkers.append(collision)
        if not collision.free(space.x0):
            continue
        goals = goal_states(space, collision, target, tolerance, goal_restarts, np.random.default_rng(seed))
        if goals:
            break
    stats.update(goal_states=len(goals), goal_seconds=time.perf_counter() - t0, margin_m=margin)
    if not goals:
        return result("no free goal")
    resolution = RESOLUTION
    widths = list(SEARCH_WIDEN)
    waypoints = frames = empty
    bad: list = []
    while widths:
        widen = widths[0]
        waypoints, info = _rrt_connect(ob, og, space, collision, goals, resolution, time_limit,
                                       search_box(space, goals, widen))
        stats.update(info, search_widen_rad=widen)
        if waypoints is None:
            widths.pop(0)
            continue
        frames = frames_at_hand_steps(space, waypoints, step)
        bad = next((hits for x in frames if (hits := exact.collisions(x))), [])
        stats["resolution"] = resolution
        if not bad:
            return result("planned", waypoints, frames)
        resolution /= 4  # a collision between OMPL's edge checks: again, checking finer
        if resolution < RESOLUTION / 20:
            break
    return result("no path", waypoints, frames, bad)


_SEEDED: list[int] = []


def _seed_ompl(ou, seed: int) -> None:
    """Seed OMPL's generator; OMPL takes a seed only before its first random number, so a process
    plans repeatably from the first seed it was given (later seeds are noted, not applied)."""
    if not _SEEDED:
        ou.RNG.setSeed(seed + 1)
        ou.setLogLevel(ou.LogLevel.LOG_WARN)
    _SEEDED.append(seed)


def search_box(space: ArmSpace, goals: list[np.ndarray], widen: float | None) -> tuple[np.ndarray, np.ndarray]:
    """The joint ranges the planner samples: those the start and the goals span, widened by
    ``widen`` rad on each side, within the limits (``widen`` None: the limits)."""
    if widen is None:
        return space.lower.copy(), space.upper.copy()
    pts = np.array([space.x0, *goals])
    return np.maximum(pts.min(axis=0) - widen, space.lower), np.minimum(pts.max(axis=0) + widen, space.upper)


def _rrt_connect(ob, og, space: ArmSpace, collision: ArmCollision, goals: list[np.ndarray], resolution: float,
                 time_limit: float, box: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray | None, dict]:
    n = space.ndim
    ss_space = ob.RealVectorStateSpace(n)
    bounds = ob.RealVectorBounds(n)
    for i in range(n):
        bounds.setLow(i, float(box[0][i]))
        bounds.setHigh(i, float(box[1][i]))
    ss_space.setBounds(bounds)
    setup = og.SimpleSetup(ss_space)

    def values(state) -> np.ndarray:
        return np.array([state[i] for i in range(n)])

    setup.setStateValidityChecker(lambda state: collision.free(values(state)))
    si = setup.getSpaceInformation()
    si.setStateValidityCheckingResolution(resolution)

    def state_of(x: np.ndarray):
        s = ss_space.allocState()
        for i in range(n):
            s[i] = float(x[i])
        return s

    setup.setStartState(state_of(space.x0))
    goal = ob.GoalStates(si)
    for g in goals:
        goal.addState(state_of(g))
    setup.setGoal(goal)
    planner = og.RRTConnect(si)
    planner.setRange(RANGE)
    setup.setPlanner(planner)
    setup.setup()
    t0 = time.perf_counter()
    status = setup.solve(time_limit)
    info = {"plan_seconds": time.perf_counter() - t0}
    if not setup.haveExactSolutionPath():
        info["ompl_status"] = str(status)
        return None, info
    path = setup.getSolutionPath()
    info["raw_waypoints"] = path.getStateCount()
    t1 = time.perf_counter()
    simplifier = og.PathSimplifier(si)
    simplifier.reduceVertices(path, SHORTCUT_STEPS)
    simplifier.partialShortcutPath(path, SHORTCUT_STEPS)
    simplifier.reduceVertices(path, SHORTCUT_STEPS)
    simplifier.smoothBSpline(path, SMOOTH_STEPS)
    info["simplify_seconds"] = time.perf_counter() - t1
    return np.array([values(path.getState(i)) for i in range(path.getStateCount())]), info
