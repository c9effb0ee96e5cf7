"""Pronking (Sims Ch. 11): all feet hop together; the body is one dynamic rigid body
(:mod:`.rigid_body`, full inertia tensor) driven by gravity and leg forces at the hips; the legs
are kinematic (IK every frame). Three phases with event-driven transitions, so it adapts to uneven
terrain:

1. **flight -> landing** when every foot has touched the terrain (each foot is tested every
   simulation step; a foot that touches keeps that point as its foothold);
2. **landing -> pushing** when the body's vertical velocity reaches zero: the landing force
   ``F = m (A - G)``, ``A = dV / dt``, ``dt = 2 dy / (v_y0 + v_y1)`` (signed, digest errata 9)
   stops the fall at the crouch height ``y_c`` above the footholds;
3. **pushing -> flight** when the takeoff velocity
   ``V_1 = (j_x / 2t, g t, j_z / 2t)``, ``t = sqrt(2 jump_height / g)`` (errata 10) is reached or any
   leg would pass ``reach_fraction`` of its full length.

Each leg applies ``F / n`` at its hip, clamped to ``max_leg_force_factor x m g / n``. In flight a
foot follows a body-relative 3-point spline lasting ``2 v_y0 / g`` (errata 8) from where it left
the ground to its landing spot: the neutral offset advanced by half the support sweep, extended
to ``landing_extension`` of the leg's length. **The body** is the root segment alone (Sims: the
legs are massless and kinematic); its inertia is its segment's tensor, or point masses at its
surface's vertices when the file gives none.

**Landing speed bound** (documented, tested): the body's vertical speed at touchdown is at most
``sqrt(2 g (jump_height + landing_speed_margin))``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from jackpy.locomotion.config import PronkConfig
from jackpy.locomotion.creature_walk import body_points, default_body_height
from jackpy.locomotion.events import EventLog
from jackpy.locomotion.legs import Leg, LegSolver, find_legs
from jackpy.locomotion.rigid_body import G, RigidBody, point_mass_inertia
from jackpy.locomotion.terrain import Terrain
from jackpy.motion.bake import Posture
from jackpy.peabody.model import Figure

FLIGHT, LANDING, PUSHING, STANDING = "flight", "landing", "pushing", "standing"
#: fraction of full leg length at which pushing stops (a leg about to lose the ground)
REACH_FRACTION = 0.95
#: fraction of full leg length the flight foot reaches out to for the landing
LANDING_EXTENSION = 0.92


def landing_speed_bound(config: PronkConfig) -> float:
    """The documented bound on the touchdown vertical speed (m/s)."""
    return math.sqrt(2.0 * -G[1] * (config.jump_height + config.landing_speed_margin))


def body_rigid(fig: Figure) -> tuple[float, np.ndarray, np.ndarray]:
    """``(mass, inertia about the COM in the body frame, COM in the body frame)`` of the root
    segment."""
    seg = fig.segments[fig.root_segment()]
    inv_site = np.linalg.inv(fig.root_site_location())
    mass = seg.mass if seg.mass > 0 else 1.0
    com = (inv_site @ np.append(seg.com, 1.0))[:3]
    if np.any(seg.inertia != 0):
        I = inv_site[:3, :3] @ seg.inertia @ inv_site[:3, :3].T
    else:
        pts = body_points(fig)
        I = point_mass_inertia(np.full(len(pts), mass / len(pts)), pts)
        com = pts.mean(axis=0)
    return mass, I, com


@dataclass
class PronkResult:
    figure: Figure
    legs: list[Leg]
    terrain: Terrain
    config: PronkConfig
    goal: np.ndarray
    fps: float
    postures: list[Posture]
    phase: list[str]  # per frame
    feet: np.ndarray  # (N, n, 3) feet after IK
    contact: np.ndarray  # (N, n) whether each foot holds a foothold at the frame
    #: per simulation step: time, phase, COM, velocity, angular momentum (world), R, omega
    steps: list[tuple[float, str, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]]
    touchdown_speeds: list[float]
    hops: int
    events: EventLog
    ik_error: np.ndarray
    mass: float
    inertia: np.ndarray

    def body_xz(self, i: int = -1) -> np.ndarray:
        return self.postures[i].location[[0, 2], 3]

    def to_motion_file(self):
        from jackpy.motion.motion_file import BakedFigure, MotionFile
        from jackpy.motion.timeline import Timeline

        return MotionFile(Timeline(), self.fps, {self.figure.name: BakedFigure.from_postures(self.figure, self.postures)})


def pronk(fig: Figure, terrain: Terrain, goal: Sequence[float], *, seconds: float | None = None,
          config: PronkConfig | None = None, legs: Sequence[Leg] | None = None) -> PronkResult:
    """Pronk ``fig`` over ``terrain`` towards ``goal`` (world x, z); stops hopping within half a
    jump of it and stands. ``seconds`` defaults to the hops the distance needs (each about twice
    ``jump_distance``: the flight plus the support sweep) plus 1.5 s."""
    c = config or PronkConfig()
    legs = list(legs) if legs is not None else find_legs(fig)
    n = len(legs)
    goal = np.asarray(goal, float).reshape(2)
    mass, I_b, com_b = body_rigid(fig)
    loc0 = fig.location.copy()
    # on the terrain under the figure
    xz0 = loc0[[0, 2], 3]
    stand = default_body_height(legs)
    feet_h = [terrain.height(*((loc0 @ np.append(g.neutral_body, 1))[[0, 2]])) for g in legs]
    loc0[1, 3] = float(np.mean(feet_h)) + c.crouch_fraction * stand  # start crouched, then push
    R0 = loc0[:3, :3]
    body = RigidBody(mass, I_b, loc0[:3, 3] + R0 @ com_b, R0)
    g = -G[1]
    t_half = math.sqrt(2.0 * c.jump_height / g)
    dist0 = float(np.hypot(*(goal - xz0)))
    if seconds is None:
        seconds = dist0 / max(2 * c.jump_distance, 1e-6) * (2 * t_half + 0.35) + 1.5
    fps, dt = float(c.fps), 1.0 / (float(c.fps) * c.substeps)
    solver = LegSolver(fig, legs)
    events = EventLog(fps)

    def location() -> np.ndarray:
        M = np.eye(4)
        M[:3, :3] = body.R
        M[:3, 3] = body.P - body.R @ com_b
        return M

    def hips(M: np.ndarray) -> list[np.ndarray]:
        return [(M @ np.append(leg.hip_body, 1))[:3] for leg in legs]

    def on_ground(p: np.ndarray) -> np.ndarray:
        return np.array([p[0], terrain.height(p[0], p[2]), p[2]])

    M = location()
    footholds: list[np.ndarray | None] = [on_ground((M @ np.append(leg.neutral_body, 1))[:3]) for leg in legs]
    phase, force = PUSHING, np.zeros(3)
    flight: dict[str, object] = {}
    support_time, support_start = 0.3, 0.0
    hops, touchdowns, steps = 0, [], []
    stopping = False

    def start_pushing(t: float) -> tuple[str, np.ndarray]:
        nonlocal stopping
        to_goal = goal - body.P[[0, 2]]
        d = float(np.hypot(*to_goal))
        if d < 0.5 * c.jump_distance or stopping:
            stopping = True
            return STANDING, np.zeros(3)
        j = to_goal / d * min(c.jump_distance, d)
        V1 = np.array([j[0] / (2 * t_half), g * t_half, j[1] / (2 * t_half)])
        M = location()
        y1 = math.inf
        for leg, hip, fh in zip(legs, hips(M), footholds):
            reach = REACH_FRACTION * leg.full_length
            dxz = math.hypot(*(hip - fh)[[0, 2]])
            top = fh[1] + math.sqrt(max(reach * reach - dxz * dxz, 0.0))
            y1 = min(y1, top - (hip[1] - body.P[1]))
        dy = max(y1 - body.P[1], 1e-3)
        span = 2 * dy / max(body.V[1] + V1[1], 1e-6)
        F = mass * ((V1 - body.V) / span - G)
        flight["V1"] = V1
        return PUSHING, F

    phase, force = start_pushing(0.0)
    n_steps = int(round(seconds / dt))
    per_frame = c.substeps
    postures, phases, feet_out, ik_err, contact = [], [], [], [], []
    max_leg = c.max_leg_force_factor * mass * g / n
    crouch = c.crouch_fraction * stand

    def leg_forces(F: np.ndarray, M: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        per = F / n
        norm = float(np.linalg.norm(per))
        if norm > max_leg:
            per = per * (max_leg / norm)
        return [(per, h) for h in hips(M)]

    def flight_target(k: int, t: float, M: np.ndarray) -> np.ndarray:
        a, b, t0, span = flight["start"][k], flight["end"][k], flight["t0"], flight["span"]
        u = min(max((t - t0) / span, 0.0), 1.0)
        mid = 0.5 * (a + b) + np.array([0.0, c.flight_foot_lift, 0.0])
        p_b = (1 - u) ** 2 * a + 2 * u * (1 - u) * (2 * mid - 0.5 * (a + b)) + u * u * b
        return (M @ np.append(p_b, 1.0))[:3]

    for s in range(n_steps + 1):
        t = s * dt
        M = location()
        if s % per_frame == 0:  # a frame: legs by IK
            targets = []
            for k, leg in enumerate(legs):
                targets.append(footholds[k] if footholds[k] is not None else flight_target(k, t, M))
            fig.location = M
            ik_err.append(solver.solve(targets))
            kin = fig.kinematics()
            fk = kin.forward(fig.q, fig.location)
            feet_out.append([(fk.segments[kin.segment_index[l.foot[0]]] @ fig.segments[l.foot[0]].sites[l.foot[1]].location)[:3, 3]
                             for l in legs])
            postures.append(Posture.of(fig))
            phases.append(phase)
            contact.append([f is not None for f in footholds])
        if s == n_steps:
            break
        steps.append((t, phase, body.P.copy(), body.V.copy(), body.L.copy(), body.R.copy(), body.omega.copy()))
        # ----- forces of this step
        if phase in (LANDING, PUSHING):
            body.step(dt, leg_forces(force, M))
        elif phase == STANDING:
            # hold: cancel gravity and damp the remaining velocity on the stance legs
            F = mass * (-G - body.V / max(dt * 20, 1e-9))
            body.step(dt, leg_forces(F, M))
        else:
            body.step(dt)
        M = location()
        frame = (s + 1) // per_frame
        # ----- events
        if phase == PUSHING:
            reach_lost = any(np.linalg.norm(fh - h) > REACH_FRACTION * leg.full_length
                             for leg, fh, h in zip(legs, footholds, hips(M)))
            if body.V[1] >= flight["V1"][1] or reach_lost:
                phase = FLIGHT
                hops += 1
                support_time = max(t - support_start, 0.1)
                vy = max(body.V[1], 0.05)
                inv = np.linalg.inv(M)
                vxz = np.array([body.V[0], 0.0, body.V[2]])
                start, end = [], []
                for k, leg in enumerate(legs):
                    start.append((inv @ np.append(footholds[k], 1.0))[:3])
                    world_land = (M @ np.append(leg.neutral_body, 1.0))[:3] + vxz * (2 * vy / g + 0.5 * support_time)
                    p = (inv @ np.append(world_land, 1.0))[:3]
                    d = p - leg.hip_body
                    p = leg.hip_body + d / np.linalg.norm(d) * LANDING_EXTENSION * leg.full_length
                    end.append(p)
                    events.add(frame, "liftoff", leg.name, footholds[k], time=t + dt)
                    footholds[k] = None
                flight.update(start=start, end=end, t0=t + dt, span=2 * vy / g)
                events.add(frame, "takeoff", fig.name, body.P, time=t + dt)
        elif phase == FLIGHT:
            for k, leg in enumerate(legs):
                if footholds[k] is None:
                    p = flight_target(k, t + dt, M)
                    if p[1] <= terrain.height(p[0], p[2]):
                        footholds[k] = on_ground(p)
                        events.add(frame, "footstep", leg.name, footholds[k], time=t + dt)
                        if len(touchdowns) < hops:
                            touchdowns.append(abs(float(body.V[1])))
            if all(f is not None for f in footholds):
                phase = LANDING
                support_start = t + dt
                y0, v0 = body.P[1], body.V[1]
                ground = float(np.mean([f[1] for f in footholds]))
                hip_off = float(np.mean([h[1] for h in hips(M)])) - body.P[1]
                yc = ground + crouch - hip_off
                dy = min(yc - y0, -1e-3)
                span = 2 * dy / min(v0, -1e-6)
                force = mass * (np.array([0.0, -v0, 0.0]) / span - G)
                events.add(frame, "landing", fig.name, body.P, time=t + dt)
        elif phase == LANDING:
            if body.V[1] >= 0.0:
                phase, force = start_pushing(t + dt)
    return PronkResult(fig, legs, terrain, c, goal, fps, postures, phases, np.array(feet_out), np.array(contact), steps, touchdowns,
                       hops, events, np.array(ik_err), mass, I_b)
