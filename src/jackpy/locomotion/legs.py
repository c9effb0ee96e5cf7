"""The legs of any N-legged Peabody figure, found from its graph, and leg IK (Sims Ch. 5-6).

A **leg** is the chain of joints from the root (body) segment to a leaf segment whose tip site lies
well below the body (by default: lower than the root by at least a quarter of the root's height
above the lowest tip), or a leaf named in ``names``. The **tip** (foot) is the leaf's site farthest
from the joint that carries the leaf. Body frame: the root site's frame, ``+z`` forward, ``+y`` up,
``+x`` the figure's left.

Leg IK uses :mod:`jackpy.ik` (a :class:`~jackpy.ik.Position` goal per foot on the leg's chain),
with Sims' full-extension method (6.3.1) as the fallback when a foot is asked for more than
``full_extension_fraction`` of the leg's full length or the solve misses: the distal joints
interpolate between their current and full-extension values, bisected on the hip-foot distance,
then the base (ball) joint alone aims the foot.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np

from jackpy import ik
from jackpy.errors import FigureError
from jackpy.peabody.model import Figure


@dataclass
class Leg:
    """One leg: its joints root to tip, its foot site and where things are in the body frame."""

    name: str
    joints: list[str]
    foot: tuple[str, str]
    #: hip (base-joint centre) in the body (root-site) frame, metres
    hip_body: np.ndarray
    #: foot in the body frame in the figure's file posture (the neutral stance offset)
    neutral_body: np.ndarray
    #: +1 left (body +x), -1 right
    side: int = 1
    #: index front (0) to back on its side
    order: int = 0
    #: hip-foot distance with every distal joint at its full-extension value (m)
    full_length: float = 0.0
    #: the distal joints' full-extension displacements (q slices of joints[1:], concatenated)
    full_extension: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def foot_name(self) -> str:
        return f"{self.foot[0]}.{self.foot[1]}"


def _tree(fig: Figure) -> tuple[dict[str, list[tuple[str, str]]], str]:
    """children[segment] = [(joint, child segment)] from the root segment."""
    root = fig.root_segment()
    adj: dict[str, list[tuple[str, str]]] = {s: [] for s in fig.segments}
    for j in fig.joints.values():
        adj[j.from_seg].append((j.name, j.to_seg))
        adj[j.to_seg].append((j.name, j.from_seg))
    children: dict[str, list[tuple[str, str]]] = {s: [] for s in fig.segments}
    seen, stack = {root}, [root]
    while stack:
        s = stack.pop()
        for jn, other in adj[s]:
            if other not in seen:
                seen.add(other)
                children[s].append((jn, other))
                stack.append(other)
    return children, root


def _site_of_joint_on(fig: Figure, joint: str, seg: str) -> str:
    j = fig.joints[joint]
    return j.to_site if j.to_seg == seg else j.from_site


def body_frame(fig: Figure) -> np.ndarray:
    """World 4x4 of the body frame (the root site)."""
    return fig.location


def find_legs(fig: Figure, names: Iterable[str] | None = None) -> list[Leg]:
    """The figure's legs, left then right, each side front to back (see the module docstring).

    ``names`` (leaf segment names) overrides the graph's choice. Raises :class:`FigureError` when
    the figure has no legs.
    """
    children, root = _tree(fig)
    leaves: list[tuple[list[str], str]] = []

    def walk(seg: str, path: list[str]) -> None:
        if not children[seg] and path:
            leaves.append((path, seg))
        for jn, child in children[seg]:
            walk(child, path + [jn])

    walk(root, [])
    kin = fig.kinematics()
    fk = kin.forward(fig.q, fig.location)
    inv_body = np.linalg.inv(body_frame(fig))
    tips = []
    for path, leaf in leaves:
        seg = fig.segments[leaf]
        attach = _site_of_joint_on(fig, path[-1], leaf)
        a = seg.sites[attach].location[:3, 3]
        far = max(seg.sites.values(), key=lambda s: float(np.linalg.norm(s.location[:3, 3] - a)))
        if far.name == attach:
            continue
        world = fk.segments[kin.segment_index[leaf]] @ far.location
        tips.append((path, leaf, far.name, (inv_body @ world)[:3, 3]))
    wanted = set(names) if names is not None else None
    if wanted is None and tips:
        lowest = min(t[3][1] for t in tips)
        tips = [t for t in tips if t[3][1] <= 0.75 * lowest]  # below the root by >= 1/4 of its height
    elif wanted is not None:
        missing = wanted - {t[1] for t in tips}
        if missing:
            raise FigureError(f"figure {fig.name!r}: no leg ends in segment {sorted(missing)[0]!r}")
        tips = [t for t in tips if t[1] in wanted]
    if not tips:
        raise FigureError(f"figure {fig.name!r} has no legs (no chain from the body to a tip below it)")
    legs = []
    for path, leaf, site, foot_b in tips:
        j0 = fig.joints[path[0]]
        hip_seg, hip_site = (j0.from_seg, j0.from_site) if j0.from_seg != leaf else (j0.to_seg, j0.to_site)
        hip_w = fk.segments[kin.segment_index[hip_seg]] @ fig.segments[hip_seg].sites[hip_site].location
        hip_b = (inv_body @ hip_w)[:3, 3]
        side = 1 if (hip_b[0] + foot_b[0]) >= 0 else -1
        legs.append(Leg(leaf, list(path), (leaf, site), hip_b, foot_b.copy(), side))
    legs.sort(key=lambda g: (-g.side, -g.hip_body[2]))
    for s in (1, -1):
        for k, g in enumerate([g for g in legs if g.side == s]):
            g.order = k
    for g in legs:
        g.full_extension, g.full_length = _full_extension(fig, g)
    return legs


def _foot_world(fig: Figure, leg: Leg, q: np.ndarray) -> np.ndarray:
    kin = fig.kinematics()
    fk = kin.forward(q, fig.location)
    return (fk.segments[kin.segment_index[leg.foot[0]]] @ fig.segments[leg.foot[0]].sites[leg.foot[1]].location)[:3, 3]


def _hip_world(fig: Figure, leg: Leg) -> np.ndarray:
    return (fig.location @ np.append(leg.hip_body, 1.0))[:3]


def _distal_slices(fig: Figure, leg: Leg) -> list[slice]:
    return [fig.joint_dof_slice(j) for j in leg.joints[1:]]


def _full_extension(fig: Figure, leg: Leg) -> tuple[np.ndarray, float]:
    """Distal joint values (within limits) maximising the hip-foot distance: coordinate ascent on a
    grid over each DOF's range, then refinement."""
    slices = _distal_slices(fig, leg)
    q = fig.q.copy()
    hip = _hip_world(fig, leg)
    idx = [i for s in slices for i in range(s.start, s.stop)]
    lo, hi = fig.lower, fig.upper

    def dist(qq: np.ndarray) -> float:
        return float(np.linalg.norm(_foot_world(fig, leg, qq) - hip))

    best = dist(q)
    for width in (None, 0.2, 0.05, 0.01):
        for _ in range(2):
            for i in idx:
                a, b = (lo[i], hi[i]) if width is None else (max(lo[i], q[i] - width), min(hi[i], q[i] + width))
                a, b = max(a, -np.pi), min(b, np.pi)
                for v in np.linspace(a, b, 25):
                    trial = q.copy()
                    trial[i] = v
                    d = dist(trial)
                    if d > best + 1e-12:
                        best, q = d, trial
    return q[idx].copy(), best


class LegSolver:
    """Places every foot on its target each frame: one :func:`jackpy.ik.solve` over all legs, then
    Sims' full-extension fallback for any leg that missed or is in the full-extension region."""

    def __init__(self, fig: Figure, legs: Sequence[Leg], tolerance: float = 1e-4,
                 full_extension_fraction: float = 0.97, max_iterations: int = 60) -> None:
        self.fig, self.legs, self.tolerance = fig, list(legs), float(tolerance)
        self.fraction, self.max_iterations = float(full_extension_fraction), int(max_iterations)
        self.problem = ik.Problem(fig)
        self.goals = [self.problem.add(ik.Position(g.foot_name, _foot_world(fig, g, fig.q), chain=list(g.joints)))
                      for g in self.legs]
        #: how many leg solves used the full-extension fallback (for reports and tests)
        self.fallbacks = 0
        #: the file posture, the seed of a retry when a leg misses from the previous frame's posture
        self.neutral_q = fig.q.copy()
        self._single = {}
        for leg in self.legs:
            p = ik.Problem(fig)
            self._single[leg.name] = (p, p.add(ik.Position(leg.foot_name, np.zeros(3), chain=list(leg.joints))))

    def solve(self, targets: Sequence[np.ndarray]) -> np.ndarray:
        """Move the feet to ``targets`` (world, m) with the body where ``fig.location`` puts it;
        returns each foot's remaining error (m)."""
        for goal, t in zip(self.goals, targets):
            goal.target = np.asarray(t, dtype=float)
        ik.solve(self.problem, max_iterations=self.max_iterations, tol_position=self.tolerance * 0.5)
        errors = np.zeros(len(self.legs))
        q = self.fig.q
        kin = self.fig.kinematics()
        fk = kin.forward(q, self.fig.location)
        for k, (leg, t) in enumerate(zip(self.legs, targets)):
            seg = leg.foot[0]
            foot = (fk.segments[kin.segment_index[seg]] @ self.fig.segments[seg].sites[leg.foot[1]].location)[:3, 3]
            err = float(np.linalg.norm(foot - t))
            reach = float(np.linalg.norm(np.asarray(t) - _hip_world(self.fig, leg)))
            if err > self.tolerance:  # retry this leg alone from its neutral posture
                q, err = self._retry(leg, np.asarray(t), q, err)
            if err > self.tolerance and reach > self.fraction * leg.full_length:
                q2 = full_extension_solve(self.fig, leg, np.asarray(t), q)
                err2 = float(np.linalg.norm(_foot_world(self.fig, leg, q2) - t))
                if err2 < err:
                    q, err = q2, err2
                    self.fallbacks += 1
            errors[k] = err
        self.fig.q = q
        return errors


    def _retry(self, leg: Leg, target: np.ndarray, q: np.ndarray, err: float) -> tuple[np.ndarray, float]:
        problem, goal = self._single[leg.name]
        goal.target = target
        seed = q.copy()
        for jn in leg.joints:
            sl = self.fig.joint_dof_slice(jn)
            seed[sl] = self.neutral_q[sl]
        saved = self.fig.q
        self.fig.q = seed
        ik.solve(problem, max_iterations=2 * self.max_iterations, tol_position=self.tolerance * 0.5)
        q2 = self.fig.q
        self.fig.q = saved
        err2 = float(np.linalg.norm(_foot_world(self.fig, leg, q2) - target))
        return (q2, err2) if err2 < err else (q, err)


def full_extension_solve(fig: Figure, leg: Leg, target: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Sims 6.3.1: distance first (bisection of the distal joints on the straight joint-space path
    towards full extension or back towards the current bend), direction second (the base joint
    alone, by :func:`jackpy.ik.solve`). Returns the new ``q`` (the figure is left as given)."""
    hip = _hip_world(fig, leg)
    want = min(float(np.linalg.norm(target - hip)), leg.full_length)
    slices = _distal_slices(fig, leg)
    idx = np.array([i for s in slices for i in range(s.start, s.stop)], dtype=int)
    cur = q[idx].copy()

    def at(s: float) -> np.ndarray:
        qq = q.copy()
        qq[idx] = (1 - s) * cur + s * leg.full_extension
        return qq

    def dist(s: float) -> float:
        return float(np.linalg.norm(_foot_world(fig, leg, at(s)) - hip))

    lo_s, hi_s = 0.0, 1.0
    if dist(0.0) < want:
        for _ in range(40):
            mid = 0.5 * (lo_s + hi_s)
            if dist(mid) < want:
                lo_s = mid
            else:
                hi_s = mid
        q_new = at(hi_s if abs(dist(hi_s) - want) < abs(dist(lo_s) - want) else lo_s)
    else:
        q_new = q.copy()
    saved = fig.q
    fig.q = q_new
    problem = ik.Problem(fig)
    problem.add(ik.Position(leg.foot_name, target, chain=[leg.joints[0]]))
    ik.solve(problem, max_iterations=40)
    out = fig.q
    fig.q = saved
    return out
