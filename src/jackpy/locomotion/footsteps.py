"""Footstep sequences: straight walks and footsteps from a planar path (digest §2.7, §2.8.4).

A path (points on the floor, x and z in metres) becomes a centre line (a Catmull-Rom spline
through the points); it is sampled every step length, shortened on turns
(``sl = sl_nominal·(1 − k·|Δψ|/45°)``, at least 0.3·sl_nominal) so that no step turns more than
45°; the feet alternate at ± half the step width beside the centre line. The walk starts from
standing (feet side by side at the first point, facing along the path) and ends standing with
the feet together at the last point, facing ``facing`` (the path's end direction when None);
a turn at the end larger than 45° is done by turning steps on the spot.
"""

from __future__ import annotations

import numpy as np

from jackpy.locomotion.walk_gait import GaitParams
from jackpy.locomotion.walk_path import Footstep

#: the largest heading change between consecutive footsteps of one foot's step (rad)
MAX_TURN = np.radians(45.0)
#: step shortening per unit of |Δψ|/45° and the shortest step (fraction of the nominal step)
K_TURN = 0.5
MIN_STEP = 0.3


def _lat(psi: float) -> np.ndarray:
    """Unit vector to the left of heading ``psi`` (top view x, z)."""
    return np.array([np.cos(psi), -np.sin(psi)])


def _dir(psi: float) -> np.ndarray:
    return np.array([np.sin(psi), np.cos(psi)])


def standing(p: GaitParams, x: float, z: float, psi: float, first: str = "right") -> list[Footstep]:
    """The two standing feet at ``(x, z)`` facing ``psi``; the foot ``first`` to step comes first."""
    c = np.array([x, z])
    other = "left" if first == "right" else "right"
    return [_foot_at(c, psi, first, p.foot.width), _foot_at(c, psi, other, p.foot.width)]


def _foot_at(c: np.ndarray, psi: float, side: str, w: float) -> Footstep:
    q = c + (w if side == "left" else -w) * _lat(psi)
    return Footstep(float(q[0]), float(q[1]), float(psi), side)


def spline(points: np.ndarray, samples: int = 24) -> np.ndarray:
    """Dense centre line through ``points`` (N, 2): centripetal-free uniform Catmull-Rom."""
    P = np.asarray(points, dtype=float)
    if len(P) == 2:
        s = np.linspace(0.0, 1.0, samples + 1)
        return P[0] + s[:, None] * (P[1] - P[0])
    ext = np.vstack([2 * P[0] - P[1], P, 2 * P[-1] - P[-2]])
    out = [P[:1]]
    for i in range(1, len(ext) - 2):
        p0, p1, p2, p3 = ext[i - 1], ext[i], ext[i + 1], ext[i + 2]
        t = np.linspace(0.0, 1.0, samples + 1)[1:, None]
        out.append(0.5 * (2 * p1 + (-p0 + p2) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t**2
                          + (-p0 + 3 * p1 - 3 * p2 + p3) * t**3))
    return np.vstack(out)


def from_path(p: GaitParams, points, facing: float | None = None, first: str | None = None) -> list[Footstep]:
    """Footsteps along the path through ``points`` ((N, 2) x, z; m), standing at both ends."""
    P = np.asarray(points, dtype=float).reshape(-1, 2)
    keep = [P[0]]
    for q in P[1:]:
        if np.linalg.norm(q - keep[-1]) > 1e-6:
            keep.append(q)
    P = np.array(keep)
    if len(P) < 2:
        psi = 0.0 if facing is None else facing
        return turn_in_place(p, P[0], psi, psi)
    line = spline(P)
    seg = np.linalg.norm(np.diff(line, axis=0), axis=1)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    total = float(cum[-1])

    def at(s: float) -> tuple[np.ndarray, float]:
        s = min(max(s, 0.0), total)
        k = min(int(np.searchsorted(cum, s, side="right")) - 1, len(seg) - 1)
        f = (s - cum[k]) / max(seg[k], 1e-12)
        d = line[k + 1] - line[k]
        return line[k] + f * d, float(np.arctan2(d[0], d[1]))

    c0, psi0 = at(0.0)
    side = first or "right"
    steps = standing(p, *c0, psi0, side)
    s_now, psi_prev = 0.0, psi0
    sl = p.step_length
    w = p.step_half_width  # walking steps on the narrower base; standing and stopping at foot.width
    # the first step is half a step (from standing), then full steps, shortened on turns
    target = 0.5 * sl
    while True:
        s_next = s_now + target
        if s_next >= total - 0.25 * sl:
            break
        c, psi = at(s_next)
        turn = (psi - psi_prev + np.pi) % (2 * np.pi) - np.pi
        if abs(turn) > MAX_TURN:
            psi = psi_prev + np.sign(turn) * MAX_TURN
            turn = psi - psi_prev
        k = max(MIN_STEP, 1.0 - K_TURN * abs(turn) / MAX_TURN)
        if target > 0.5 * sl + 1e-9 and k < 1.0 and s_next - s_now > k * sl + 1e-9:
            s_next = s_now + k * sl
            c, psi2 = at(s_next)
            t2 = (psi2 - psi_prev + np.pi) % (2 * np.pi) - np.pi
            psi = psi_prev + float(np.clip(t2, -MAX_TURN, MAX_TURN))
        steps.append(_foot_at(c, psi, side, w))
        side = "left" if side == "right" else "right"
        s_now, psi_prev = s_next, psi
        target = sl
    c_end, psi_end = at(total)
    return steps + _stop(p, steps, c_end, psi_end if facing is None else facing, side)


def _stop(p: GaitParams, steps: list[Footstep], c: np.ndarray, psi: float, side: str) -> list[Footstep]:
    """Steps to stand at ``c`` facing ``psi`` with the feet together, turning ≤ 45° per step
    (extra steps on the spot for larger turns)."""
    out: list[Footstep] = []
    last = steps[-1].psi
    while True:
        turn = (psi - last + np.pi) % (2 * np.pi) - np.pi
        last = last + float(np.clip(turn, -MAX_TURN, MAX_TURN))
        out.append(_foot_at(c, last, side, p.foot.width))
        side = "left" if side == "right" else "right"
        if len(out) >= 2 and _same(out[-2].psi, psi) and _same(out[-1].psi, psi):
            return out
        if abs(turn) <= MAX_TURN and len(out) >= 2 and _same(out[-1].psi, psi):
            out.append(_foot_at(c, last, side, p.foot.width))
            return out


def _same(a: float, b: float) -> bool:
    """Whether headings ``a`` and ``b`` (rad) are one direction (any multiple of 2π apart)."""
    return abs((a - b + np.pi) % (2 * np.pi) - np.pi) < 1e-12


def turn_in_place(p: GaitParams, c, psi0: float, psi1: float) -> list[Footstep]:
    """Standing at ``c`` facing ``psi0``, turn to ``psi1`` by steps on the spot."""
    c = np.asarray(c, dtype=float)
    turn = (psi1 - psi0 + np.pi) % (2 * np.pi) - np.pi
    side = "left" if turn > 0 else "right"
    steps = standing(p, *c, psi0, side)
    return steps + _stop(p, steps, c, psi0 + turn, side)


def straight(p: GaitParams, distance: float, x: float = 0.0, z: float = 0.0, psi: float = 0.0) -> list[Footstep]:
    """Footsteps walking ``distance`` (m) straight ahead from standing at ``(x, z)`` facing ``psi``."""
    d = _dir(psi)
    start = np.array([x, z])
    return from_path(p, [start, start + distance * d])


#: the most a foot moves per step when stepping sideways or backwards (fraction of the gait's step
#: length), and the longest such move (m; farther: walk there)
SHUFFLE_STEP = 0.4
SHUFFLE_LIMIT = 1.5


def shuffle(p: GaitParams, x: float, z: float, psi: float, right: float = 0.0, forward: float = 0.0) -> list[Footstep]:
    """Short steps keeping the heading ``psi``: from standing at ``(x, z)`` to standing ``right``
    (m, + to the figure's right) and ``forward`` (m, − backwards) from there, feet together at
    both ends. Sideways: the foot on that side leads and the other closes up to the standing width
    each step; backwards (or diagonally): the feet alternate, each passing the other. Each step
    moves a foot at most ``SHUFFLE_STEP`` of a step length; ``SHUFFLE_LIMIT`` at most."""
    d_local = np.array([float(right), float(forward)])
    dist = float(np.linalg.norm(d_local))
    if dist > SHUFFLE_LIMIT:
        raise ValueError(f"steps sideways or backwards go at most {SHUFFLE_LIMIT} m, not {dist:.2f} m: walk there")
    c0 = np.array([float(x), float(z)])
    d = -d_local[0] * _lat(psi) + d_local[1] * _dir(psi)  # world (x, z)
    w = p.foot.width
    if dist < 1e-6:
        return standing(p, x, z, psi)
    sideways = abs(d_local[0]) > 2.0 * abs(d_local[1])
    lead = ("right" if d_local[0] > 0 else "left") if sideways else "right"
    # each move of the centre line by d/n moves a sideways foot by d/n, an alternating one by 2d/n
    n = max(1, int(np.ceil((1.0 if sideways else 2.0) * dist / (SHUFFLE_STEP * p.step_length))))
    steps = standing(p, x, z, psi, lead)
    if sideways:  # lead out, close up: two footsteps per move
        for k in range(1, n + 1):
            c = c0 + d * (k / n)
            steps.append(_foot_at(c, psi, lead, w))
            steps.append(_foot_at(c, psi, "left" if lead == "right" else "right", w))
        return steps
    side = lead
    for k in range(1, n + 1):  # alternate: each foot to the next centre-line point
        steps.append(_foot_at(c0 + d * (k / n), psi, side, w))
        side = "left" if side == "right" else "right"
    steps.append(_foot_at(c0 + d, psi, side, w))  # the other foot closes up
    return steps
