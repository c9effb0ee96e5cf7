"""Kinematic walking of any N-legged figure over terrain (Sims Ch. 10), baked to a motion.

Per frame: the **body** is placed on its path (heading turned towards the goal at most
``max_turn_rate``, speed ramped down over ``slow_down_distance``), at the height and tilt of a
plane fitted to the terrain under its neutral footprint, ``body_height`` above it, plus a
gait-phased bounce of amplitude ``bounciness``; it is lifted further if any vertex of the body's
surface would otherwise touch the terrain. Each **foot** follows the gait schedule: in stance it
holds its world foothold; at lift-off its next foothold is planned (10.2): the neutral stance
offset under the body at the middle of the next stance, backed off towards the current foothold
in ``foot_radius / 2`` steps while it lies in a forbidden zone (none safe: the foot steps in
place), and a swing path that clears the highest terrain between the footholds by
``swing_clearance`` lands it exactly at its foot-down time. The **legs** are solved by
:class:`~jackpy.locomotion.legs.LegSolver` every frame.

World frame: y up; the body frame is the figure's root site (``+z`` forward, ``+x`` left).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from jackpy.errors import FigureError
from jackpy.locomotion.config import WalkConfig
from jackpy.locomotion.events import EventLog
from jackpy.locomotion.gaits import Gait, assign, bounce
from jackpy.locomotion.legs import Leg, LegSolver, find_legs
from jackpy.locomotion.terrain import Terrain
from jackpy.motion.bake import Posture
from jackpy.peabody.model import Figure


def body_points(fig: Figure) -> np.ndarray:
    """Vertices of the root segment's surface (or its sites when it has none) in the body frame."""
    seg = fig.segments[fig.root_segment()]
    inv_site = np.linalg.inv(fig.root_site_location())
    mesh = seg.psurf.posed_mesh() if seg.psurf is not None else None
    pts = mesh.vertices if mesh is not None else np.array([s.location[:3, 3] for s in seg.sites.values()])
    return (inv_site[:3, :3] @ np.asarray(pts, float).T).T + inv_site[:3, 3]


def yaw_of(location: np.ndarray) -> float:
    """Heading (rad) of a body frame: 0 when its +z points along world +z, positive towards +x."""
    f = location[:3, 2]
    return math.atan2(f[0], f[2])


@dataclass
class BodyPath:
    """The body's planar path (centre xz and heading per fine time step) and its 3-D pose."""

    terrain: Terrain
    legs: Sequence[Leg]
    config: WalkConfig
    body_height: float
    gait: Gait
    points: np.ndarray  # body surface points in the body frame
    dt: float
    xz: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    heading: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def plan(self, start_xz: np.ndarray, start_heading: float, goal: np.ndarray, duration: float) -> None:
        c = self.config
        n = int(math.ceil(duration / self.dt)) + 1
        xz, psi = np.zeros((n, 2)), np.zeros(n)
        p, h = np.asarray(start_xz, float).copy(), float(start_heading)
        for i in range(n):
            xz[i], psi[i] = p, h
            d = goal - p
            dist = float(np.hypot(*d))
            if dist < 0.01:
                continue
            want = math.atan2(d[0], d[1])
            err = (want - h + math.pi) % (2 * math.pi) - math.pi
            turn = max(-c.max_turn_rate * self.dt, min(c.max_turn_rate * self.dt, err))
            h += turn
            v = c.speed * max(0.2, min(1.0, dist / c.slow_down_distance)) * max(0.0, math.cos(err))
            step = min(v * self.dt, dist)
            p = p + step * np.array([math.sin(h), math.cos(h)])
        self.xz, self.heading = xz, psi

    def planar(self, t: float) -> tuple[np.ndarray, float]:
        s = min(max(t / self.dt, 0.0), len(self.heading) - 1.0)
        i = min(int(s), len(self.heading) - 2)
        f = s - i
        dh = (self.heading[i + 1] - self.heading[i] + math.pi) % (2 * math.pi) - math.pi
        return self.xz[i] * (1 - f) + self.xz[i + 1] * f, float(self.heading[i] + f * dh)

    def pose(self, t: float) -> np.ndarray:
        """World 4x4 of the body frame at time ``t`` (s)."""
        c, T = self.config, self.terrain
        centre, psi = self.planar(t)
        fwd = np.array([math.sin(psi), 0.0, math.cos(psi)])
        left = np.array([math.cos(psi), 0.0, -math.sin(psi)])
        r = c.terrain_sample_radius
        local = [g.neutral_body[[0, 2]] for g in self.legs] + [(0, 0), (r, 0), (-r, 0), (0, r), (0, -r)]
        local = np.asarray(local, float)
        wx = centre[0] + local[:, 0] * left[0] + local[:, 1] * fwd[0]
        wz = centre[1] + local[:, 0] * left[2] + local[:, 1] * fwd[2]
        h = T.height(wx, wz)
        A = np.column_stack([np.ones(len(local)), local])
        (a, bl, bf), *_ = np.linalg.lstsq(A, h, rcond=None)
        up = np.array([0.0, 1.0, 0.0]) - bl * left - bf * fwd
        up /= np.linalg.norm(up)
        f2 = fwd - (fwd @ up) * up
        f2 /= np.linalg.norm(f2)
        l2 = np.cross(up, f2)
        M = np.eye(4)
        M[:3, 0], M[:3, 1], M[:3, 2] = l2, up, f2
        y = a + self.body_height + c.bounciness * bounce(self.gait.phase(t))
        M[:3, 3] = (centre[0], y, centre[1])
        world = (M[:3, :3] @ self.points.T).T + M[:3, 3]
        gap = float(np.min(world[:, 1] - T.height(world[:, 0], world[:, 2])))
        if gap < c.body_clearance_min:
            M[1, 3] += c.body_clearance_min - gap
        return M


@dataclass
class Swing:
    p0: np.ndarray
    p1: np.ndarray
    t0: float
    t1: float
    peak: float


@dataclass
class Landing:
    """One planned foothold: at lift-off ``frame`` leg ``leg`` plans to land at ``foothold``;
    ``desired`` is where it wanted to (before backing off forbidden zones); ``safe`` is false when no
    safe point existed and the foot steps in place."""

    frame: int
    leg: int
    foothold: np.ndarray
    desired: np.ndarray
    safe: bool


@dataclass
class WalkResult:
    """A baked walk: per frame the posture, every foot's world position (from forward kinematics
    of the solved posture), which feet the schedule puts in stance, the body's least clearance over
    the terrain, and the footstep events."""

    figure: Figure
    legs: list[Leg]
    gait: Gait
    terrain: Terrain
    config: WalkConfig
    goal: np.ndarray
    fps: float
    postures: list[Posture]
    feet: np.ndarray  # (N, n_legs, 3)
    stance: np.ndarray  # (N, n_legs) bool
    swing_u: np.ndarray  # (N, n_legs) progress of the swing in [0, 1] (1 in stance)
    body_clearance: np.ndarray  # (N,)
    ik_error: np.ndarray  # (N, n_legs)
    events: EventLog
    landings: list["Landing"]

    @property
    def times(self) -> np.ndarray:
        return np.arange(len(self.postures)) / self.fps

    def body_xz(self, i: int = -1) -> np.ndarray:
        return self.postures[i].location[[0, 2], 3]

    def to_motion_file(self):
        from jackpy.motion.motion_file import BakedFigure, MotionFile
        from jackpy.motion.timeline import Timeline

        return MotionFile(Timeline(), self.fps, {self.figure.name: BakedFigure.from_postures(self.figure, self.postures)})


def default_body_height(legs: Sequence[Leg]) -> float:
    """The figure's own body height: the root above its feet in the file posture (m)."""
    return float(-np.mean([g.neutral_body[1] for g in legs]))


def _swing_point(s: Swing, t: float, terrain: Terrain, clearance: float) -> tuple[np.ndarray, float]:
    u = min(max((t - s.t0) / max(s.t1 - s.t0, 1e-9), 0.0), 1.0)
    e = u * u * (3 - 2 * u)
    p = s.p0 + (s.p1 - s.p0) * e
    base = s.p0[1] + (s.p1[1] - s.p0[1]) * e
    lift = math.sin(math.pi * u)
    y = base + (s.peak - 0.5 * (s.p0[1] + s.p1[1])) * lift
    ground = terrain.height(p[0], p[2])
    p[1] = max(y, ground + clearance * lift)
    return p, u


def _within_reach(pose: np.ndarray, legs: Sequence[Leg], targets: Sequence[np.ndarray], fraction: float) -> np.ndarray:
    """Lower the body (vertically) just enough that every foot target lies within ``fraction`` of
    its leg's full length from its hip."""
    drop = 0.0
    for leg, t in zip(legs, targets):
        hip = (pose @ np.append(leg.hip_body, 1.0))[:3]
        reach = fraction * leg.full_length
        dxz = math.hypot(t[0] - hip[0], t[2] - hip[2])
        if dxz < reach:
            drop = max(drop, (hip[1] - t[1]) - math.sqrt(reach * reach - dxz * dxz))
    if drop <= 0.0:
        return pose
    out = pose.copy()
    out[1, 3] -= drop
    return out


def plan_foothold(terrain: Terrain, desired: np.ndarray, current: np.ndarray, step: float) -> tuple[np.ndarray, bool]:
    """Sims 10.2 step 2: ``desired`` if safe, else the first safe point marching back towards
    ``current`` by ``step``; ``(current, False)`` when none is safe. Points are on the terrain."""
    d, c = np.asarray(desired, float), np.asarray(current, float)
    n = max(1, int(math.ceil(np.hypot(*(d - c)[[0, 2]]) / step)))
    for k in range(n + 1):
        p = d + (c - d) * (k / n)
        if not terrain.is_forbidden(p[0], p[2]):
            return np.array([p[0], terrain.height(p[0], p[2]), p[2]]), True
    return np.array([c[0], terrain.height(c[0], c[2]), c[2]]), False


def walk(fig: Figure, terrain: Terrain, goal: Sequence[float], *, seconds: float | None = None,
         config: WalkConfig | None = None, legs: Sequence[Leg] | None = None,
         start: Sequence[float] | None = None) -> WalkResult:
    """Walk ``fig`` over ``terrain`` to ``goal`` (world x, z in m), baked at ``config.fps``.

    The figure starts at its own location's xz and heading (or ``start = (x, z)``); its posture in
    the file is the neutral stance. ``seconds`` defaults to the time the path needs plus two
    cycles. The figure is left in the last frame's posture.
    """
    c = config or WalkConfig()
    if c.gait == "pronk":
        raise ValueError("the pronk gait is dynamic: use jackpy.locomotion.pronk.pronk")
    legs = list(legs) if legs is not None else find_legs(fig)
    terrain.max_slope_deg, terrain.foot_radius, terrain._forbidden = c.max_slope_deg, c.foot_radius, None
    gait = assign(legs, c.gait, c)
    bh = c.body_height if c.body_height is not None else default_body_height(legs)
    goal = np.asarray(goal, float).reshape(2)
    loc0 = fig.location.copy()
    start_xz = np.asarray(start, float) if start is not None else loc0[[0, 2], 3]
    dist = float(np.hypot(*(goal - start_xz)))
    if seconds is None:
        seconds = dist / c.speed + 2 * c.slow_down_distance / c.speed + 2 * c.cycle_time
    if not seconds > 0:
        raise ValueError(f"seconds must be > 0, not {seconds}")
    fps = float(c.fps)
    path = BodyPath(terrain, legs, c, bh, gait, body_points(fig), 0.5 / fps)
    path.plan(start_xz, yaw_of(loc0), goal, seconds + 3 * c.cycle_time)
    solver = LegSolver(fig, legs, c.ik_tolerance, c.full_extension_fraction)
    n_frames = int(math.floor(seconds * fps + 1e-9)) + 1
    nl = len(legs)
    events = EventLog(fps)

    def neutral_on_terrain(pose: np.ndarray, leg: Leg) -> np.ndarray:
        p = (pose @ np.append(leg.neutral_body, 1.0))[:3]
        return np.array([p[0], terrain.height(p[0], p[2]), p[2]])

    pose0 = path.pose(0.0)
    footholds = [neutral_on_terrain(pose0, g) for g in legs]
    swings: list[Swing | None] = [None] * nl
    prev = np.ones(nl, dtype=bool)
    postures, feet, stance_all, swing_u = [], np.zeros((n_frames, nl, 3)), np.zeros((n_frames, nl), bool), np.ones((n_frames, nl))
    clearance, ik_err, landings = np.zeros(n_frames), np.zeros((n_frames, nl)), []
    points = path.points
    kin = fig.kinematics()
    foot_idx = [kin.segment_index[g.foot[0]] for g in legs]
    foot_loc = [fig.segments[g.foot[0]].sites[g.foot[1]].location for g in legs]
    for i in range(n_frames):
        t = i / fps
        pose = path.pose(t)
        stance = gait.in_stance(t)
        targets = []
        for k, leg in enumerate(legs):
            if stance[k] and (i == 0 or not prev[k]):
                if i > 0 and swings[k] is not None:
                    footholds[k] = swings[k].p1.copy()
                    events.add(i, "footstep", leg.name, footholds[k], time=swings[k].t1)
                swings[k] = None
            elif not stance[k] and (i == 0 or prev[k]):
                t_up = 0.0 if i == 0 else gait.last_up(k, t)
                t_land = gait.next_down(k, t)
                mid = path.pose(t_land + 0.5 * gait.duty[k] * gait.cycle)
                desired = neutral_on_terrain(mid, leg)
                p1, safe = plan_foothold(terrain, desired, footholds[k], 0.5 * c.foot_radius)
                landings.append(Landing(i, k, p1, desired, safe))
                peak = max(terrain.max_height_along(footholds[k][[0, 2]], p1[[0, 2]]), footholds[k][1], p1[1]) + c.swing_clearance
                swings[k] = Swing(footholds[k].copy(), p1, t_up, t_land, peak)
                if i > 0:
                    events.add(i, "liftoff", leg.name, footholds[k], time=t_up)
            if stance[k]:
                targets.append(footholds[k])
            else:
                p, u = _swing_point(swings[k], t, terrain, c.swing_clearance)
                swing_u[i, k] = u
                targets.append(p)
        pose = _within_reach(pose, legs, targets, c.reach_fraction)
        fig.location = pose
        ik_err[i] = solver.solve(targets)
        fk = kin.forward(fig.q, fig.location)
        for k in range(nl):
            feet[i, k] = (fk.segments[foot_idx[k]] @ foot_loc[k])[:3, 3]
        world = (pose[:3, :3] @ points.T).T + pose[:3, 3]
        clearance[i] = float(np.min(world[:, 1] - terrain.height(world[:, 0], world[:, 2])))
        stance_all[i] = stance
        postures.append(Posture.of(fig))
        prev = stance
    if not np.all(np.isfinite(feet)):
        raise FigureError(f"figure {fig.name!r}: walking produced a non-finite posture")
    return WalkResult(fig, legs, gait, terrain, c, goal, fps, postures, feet, stance_all, swing_u, clearance,
                      ik_err, events, landings)
