"""Rigid polyhedra bouncing on terrain (Sims Ch. 12).

The body is a :class:`~jackpy.locomotion.rigid_body.RigidBody` (full inertia tensor). After each
free step every vertex below the terrain that moves into it gets the normal response of eq. 12.19
taken to an impulse (Sims applies ``f`` for one step ``dt``; with ``dt -> 0`` that is the impulse
``j = f dt``): the vertex's normal velocity becomes ``-b`` times what it was,
``j = -(1 + b) v_n / (1/m + N . ((I_w^-1 (r x N)) x r))`` with ``r`` the vertex from the COM
(the tensor form of ``|L x N|^2 / i``). Sims left friction out; to come to rest on a slope we add
Coulomb friction at the vertex: a tangential impulse stopping its sliding, at most ``mu j``. Both
impulses only remove kinetic energy (``b < 1``). A step with no vertex reaching the terrain is the
exact ballistic step (energy conserved exactly for a body of isotropic inertia, a cube); a step
with contacts is taken at the velocity level (gravity, impulses, then the move), which never gains
energy beyond round-off, so the total energy never rises. A vertex arriving slower
than two steps of gravity (``2 g dt``) is a resting contact: it does not bounce but leaves at the
speed the step's gravity cancels (never faster than it came), so the body neither chatters nor
sinks. The body **comes to
rest** when every vertex stays slower than ``2 g dt`` for ``rest_time``: it is then held still.

Every new contact is a ``bounce`` event (Ch. 13) at its vertex.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from jackpy.locomotion.events import EventLog
from jackpy.locomotion.rigid_body import RigidBody, point_mass_inertia
from jackpy.locomotion.terrain import Terrain


def cube(size: float = 0.2) -> np.ndarray:
    """The 8 vertices (m) of a cube of edge ``size`` centred on the origin."""
    h = size / 2
    return np.array([[x, y, z] for x in (-h, h) for y in (-h, h) for z in (-h, h)], dtype=float)


@dataclass
class BounceResult:
    times: np.ndarray
    energy: np.ndarray  # total energy (J) per step, zero potential at y = 0
    positions: np.ndarray  # COM per step
    rest_time: float | None  # when it came to rest, None if it did not
    events: EventLog
    bounces: int = 0
    vertices_world: list[np.ndarray] = field(default_factory=list)


def _resolve(body: RigidBody, world: np.ndarray, touching: np.ndarray, in_contact: np.ndarray,
             terrain: Terrain, bounciness: float, friction: float, dt: float, events: EventLog,
             t: float, fps: float) -> None:
    """Normal (eq. 12.19 as an impulse) and friction impulses at the touching vertices, a few
    sweeps so simultaneous contacts settle; a new contact is a ``bounce`` event."""
    mass = body.mass
    Iw_inv = body.R @ body.inertia_inv @ body.R.T
    rest_speed = 2.0 * 9.81 * dt
    for sweep in range(4):
        hit = False
        for k in np.flatnonzero(touching):
            p = world[k]
            N = terrain.normal(p[0], p[2])
            v = body.point_velocity(p)
            vn = float(v @ N)
            if vn >= 0.0:
                continue
            r = p - body.P
            k_n = 1.0 / mass + float(N @ np.cross(Iw_inv @ np.cross(r, N), r))
            if -vn > rest_speed:
                jn = -(1.0 + bounciness) * vn / k_n
                bounced = True
            else:  # resting contact: leave at the speed that the step's gravity cancels (no sinking)
                jn = max(0.0, (min(0.5 * 9.81 * N[1] * dt, -vn) - vn) / k_n)
                bounced = False
            body.apply_impulse(jn * N, p)
            v = body.point_velocity(p)
            vt = v - (v @ N) * N
            speed = float(np.linalg.norm(vt))
            if speed > 1e-12 and friction > 0:
                tdir = vt / speed
                k_t = 1.0 / mass + float(tdir @ np.cross(Iw_inv @ np.cross(r, tdir), r))
                body.apply_impulse(-min(speed / k_t, friction * jn) * tdir, p)
            hit = True
            if sweep == 0 and not in_contact[k] and bounced:
                events.add(int(t * fps), "bounce", "polyhedron", p, time=t)
        if not hit:
            break


def drop(vertices: np.ndarray, terrain: Terrain, start: Sequence[float], *, mass: float = 1.0,
         bounciness: float = 0.5, friction: float = 0.8, seconds: float = 4.0, dt: float = 1.0 / 240.0,
         R: np.ndarray | None = None, omega: Sequence[float] = (0.0, 0.0, 0.0), rest_time: float = 0.25,
         fps: float = 30.0) -> BounceResult:
    """Drop a polyhedron (``vertices`` about its centre, equal point masses at them) with its
    centre at ``start`` and simulate ``seconds`` at step ``dt``."""
    if not 0.0 <= bounciness <= 1.0:
        raise ValueError(f"bounciness must lie in [0, 1], not {bounciness}")
    v_b = np.asarray(vertices, float)
    v_b = v_b - v_b.mean(axis=0)
    inertia = point_mass_inertia(np.full(len(v_b), mass / len(v_b)), v_b)
    body = RigidBody(mass, inertia, start, R, omega=omega)
    events = EventLog(fps)
    n = int(round(seconds / dt))
    times, energy, pos = np.zeros(n + 1), np.zeros(n + 1), np.zeros((n + 1, 3))
    in_contact = np.zeros(len(v_b), dtype=bool)
    calm, rested = 0.0, None
    rest_speed = 2.0 * 9.81 * dt
    for s in range(n + 1):
        t = s * dt
        times[s], energy[s], pos[s] = t, body.energy(), body.P
        if s == n:
            break
        if rested is not None:
            continue
        P0, R0, V0, L0 = body.P.copy(), body.R.copy(), body.V.copy(), body.L.copy()
        body.step(dt)  # exact ballistic step, accepted when no vertex reaches the terrain
        world = (body.R @ v_b.T).T + body.P
        touching = world[:, 1] <= terrain.height(world[:, 0], world[:, 2])
        if touching.any():
            # a contact step: the impulses on the velocities at the start of the step (vertices at
            # or below the terrain at its start or its end), then the exact ballistic step
            body.P, body.R, body.V, body.L = P0, R0, V0, L0
            world0 = (R0 @ v_b.T).T + P0
            touching |= world0[:, 1] <= terrain.height(world0[:, 0], world0[:, 2])
            _resolve(body, world0, touching, in_contact, terrain, bounciness, friction, dt, events, t, fps)
            body.step(dt)
        in_contact = touching
        world = (body.R @ v_b.T).T + body.P
        fastest = max(float(np.linalg.norm(body.point_velocity(p))) for p in world)
        calm = calm + dt if (fastest < rest_speed and touching.any()) else 0.0
        if calm >= rest_time:
            body.V[:] = 0.0
            body.L[:] = 0.0
            rested = t + dt
    return BounceResult(times, energy, pos, rested, events, len(events.of("bounce")))
