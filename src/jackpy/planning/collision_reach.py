"""Collision-aware reach verdicts (issue 16): a target counts as reached only with a posture that
does not interpenetrate the workplace by more than the contact tolerance.

Two :class:`~jackpy.analysis.clearance.ClearanceChecker` on a private copy of the figure judge a
posture: the full-size one finds the objects a segment *touches*; one eroded by
:data:`CONTACT_TOLERANCE` finds the objects a segment *passes into* (deeper than the tolerance).
Self-collision is not judged here (the IK joint limits keep the arm off the body).

Arm reach (:func:`collision_free_arm_reach`): the IK from the current posture and from
``restarts`` random postures of the arm chain (fixed seed: the same answer every run) gives
candidate postures; a candidate that passes into an object is backed off along the straight
joint-space line from the start posture to its last free posture (1/16 steps, then bisection).
The nearest free candidate is the answer; among those at the target, one without any touch is
preferred, then one whose only touch is the hand on the target's own object (pressing a button is
meant to touch it).

Verdicts (:class:`Verdict`):

* ``reached``: a free posture puts the hand within the reach tolerance, touching nothing but the
  target's own object with the hand;
* ``touching``: reached, but only by touching another object (or the target's object with another
  segment) within the tolerance: "reached only by touching X";
* ``blocked``: not reached, and the collisions are why: either ignoring them the figure would get
  more than :data:`BLOCK_MARGIN` nearer (the object it would pass into is named), or the straight
  way from the hand's best free position to the target runs into an object (named);
* ``short``: not reached, nothing in the way: "short by N cm".
"""

from __future__ import annotations

import copy
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from jackpy import ik
from jackpy.analysis.clearance import ClearanceChecker
from jackpy.analysis.parts import figure_parts
from jackpy.peabody.model import Figure

#: a segment may press this far (metres) into a surface (skin, and the polygonal approximation of
#: both shapes); deeper is interpenetration
CONTACT_TOLERANCE = 0.01
#: collisions "block" a target when ignoring them the hand would get this much (m) nearer
BLOCK_MARGIN = 0.01
#: radius (m) of the hand-sized capsule swept from the hand to the target to find what is in the way
WAY_RADIUS = 0.02
#: the swept capsule stops this far (m) short of the target (the target lies on its object's surface)
WAY_END_GAP = 0.04


@dataclass
class Verdict:
    """``kind`` (``reached``/``touching``/``blocked``/``short``), the ``shortfall`` (m), the objects
    ``touching`` (within the tolerance) and the object the target is ``blocked_by``."""

    kind: str
    shortfall: float
    touching: list[str] = field(default_factory=list)
    blocked_by: str | None = None
    tolerance: float = CONTACT_TOLERANCE

    @property
    def reached(self) -> bool:
        return self.kind in ("reached", "touching")

    def describe(self) -> str:
        if self.kind == "reached":
            return f"reached ({self.shortfall * 1e3:.0f} mm)"
        if self.kind == "touching":
            return f"reached only by touching {', '.join(self.touching)}"
        if self.kind == "blocked":
            return f"blocked by {self.blocked_by} (short by ~{self.shortfall * 100:.0f} cm)"
        return f"short by ~{self.shortfall * 100:.0f} cm"

    def to_dict(self) -> dict:
        return {"verdict": self.kind, "touching": list(self.touching), "blocked_by": self.blocked_by,
                "contact_tolerance_m": self.tolerance}


class WorkplaceJudge:
    """Judges postures of ``figure`` (any posture taken from it or a copy) against ``obstacles``:
    which objects they pass into (deeper than ``tolerance``) and which they touch.

    ``allowed``: ``(segment, object)`` pairs that may overlap (:meth:`allow_hand_on`)."""

    def __init__(self, figure: Figure, obstacles: Sequence[Figure], tolerance: float = CONTACT_TOLERANCE) -> None:
        self.allowed: set[tuple[str, str]] = set()
        self.figure = copy.deepcopy(figure)
        self.root = tuple(self.figure.root)
        self.tolerance = tolerance
        self.touch = ClearanceChecker(self.figure, obstacles, self_collision=False)
        self.deep = ClearanceChecker(self.figure, obstacles, self_collision=False, erode=tolerance)

    def _pose(self, posture) -> None:
        posture.apply(self.figure, root=self.root)
        self.touch.update()
        self.deep.update()

    def allow_hand_on(self, hands: set[str], target_object: str | None) -> None:
        """Let the ``hands`` segments (the palm, which carries the grip point) meet the target's own
        object: the grip point lies inside the palm, so a palm on a button or a handle overlaps its
        object by up to half the palm's thickness. The fingers, the forearm and the rest of the
        body still may not pass into it."""
        if target_object is None:
            return
        bodies = [b for b in self.deep.body_names if b == target_object or b.startswith(target_object + ".")]
        self.allowed = {(s, b) for s in hands for b in bodies}

    def penetrations(self, posture) -> list[tuple[str, str]]:
        """``(segment, object)`` pairs passing into each other deeper than the tolerance (allowed
        pairs left out)."""
        self._pose(posture)
        return [p for p in self.deep.object_collisions() if p not in self.allowed]

    def free(self, posture) -> bool:
        return not self.penetrations(posture)

    def touches(self, posture) -> list[tuple[str, str]]:
        """``(segment, object)`` pairs in contact (full-size segments)."""
        self._pose(posture)
        return self.touch.object_collisions()

    def way_blocked_by(self, start: np.ndarray, target: np.ndarray) -> str | None:
        """The first object a hand-sized capsule from ``start`` towards ``target`` runs into
        (stopping :data:`WAY_END_GAP` short of the target), or None."""
        axis = np.asarray(target, float) - np.asarray(start, float)
        length = float(np.linalg.norm(axis))
        if length <= WAY_END_GAP:
            return None
        end = start + axis * (length - WAY_END_GAP) / length
        hits = self.touch.line_hits(start, end, WAY_RADIUS)
        return hits[0][1] if hits else None


def unintended_touches(touches: Sequence[tuple[str, str]], target_object: str | None,
                       hand_segments: set[str]) -> list[str]:
    """Objects touched other than the target's own object by the hand (its palm and fingers)."""
    out = []
    for seg, body in touches:
        own = target_object is not None and (body == target_object or body.startswith(target_object + "."))
        if own and seg in hand_segments:
            continue
        if body not in out:
            out.append(body)
    return out


def hand_segments(figure: Figure, hand: str) -> set[str]:
    """The hand's segment and everything distal to it (the fingers)."""
    palm = figure_parts(figure).hands[hand].segment
    kin = figure.kinematics()
    out = {palm}
    changed = True
    while changed:
        changed = False
        for j in figure.joints.values():
            for a, b in ((j.from_seg, j.to_seg), (j.to_seg, j.from_seg)):
                if a in out and b not in out and kin.segment_names.index(b) > kin.segment_names.index(a):
                    out.add(b)
                    changed = True
    return out


def judge(judge_: WorkplaceJudge, posture, shortfall: float, hand_pos: np.ndarray, target: np.ndarray,
          reach_tolerance: float, target_object: str | None, hands: set[str],
          unconstrained: tuple[float, object] | None) -> Verdict:
    """The verdict for the best free ``posture`` (hand at ``hand_pos``, ``shortfall`` m from
    ``target``); ``unconstrained``: the shortfall and posture reached when collisions are ignored."""
    if shortfall <= reach_tolerance:
        extra = unintended_touches(judge_.touches(posture), target_object, hands)
        return Verdict("touching" if extra else "reached", shortfall, extra, tolerance=judge_.tolerance)
    if unconstrained is not None and unconstrained[0] < shortfall - BLOCK_MARGIN:
        bodies = Counter(b for _, b in judge_.penetrations(unconstrained[1]))
        if bodies:
            return Verdict("blocked", shortfall, blocked_by=bodies.most_common(1)[0][0], tolerance=judge_.tolerance)
    way = judge_.way_blocked_by(hand_pos, target)
    if way is not None:
        return Verdict("blocked", shortfall, blocked_by=way, tolerance=judge_.tolerance)
    return Verdict("short", shortfall, tolerance=judge_.tolerance)


@dataclass
class ArmSearch:
    """Outcome of :func:`collision_free_arm_reach`: the best free posture's ``q`` (None when the
    start itself passes into an object and no candidate is free), its shortfall and hand position,
    and the best shortfall and ``q`` with collisions ignored."""

    q: np.ndarray | None
    shortfall: float
    position: np.ndarray
    status: str
    free_candidates: int
    any_shortfall: float
    any_q: np.ndarray


def collision_free_arm_reach(figure: Figure, target: np.ndarray, hand: str, chain: str | None,
                             free: Callable[[np.ndarray], bool], prefer: Callable[[np.ndarray], int],
                             tolerance: float, restarts: int = 16, max_iterations: int = 300,
                             seed: int = 0) -> ArmSearch:
    """Search the arm chain (from ``chain``, default the clavicle) for the nearest posture ``q``
    that ``free(q)`` accepts (module docstring); ``prefer(q)`` ranks postures at the target (lower
    is better). The figure's posture is left unchanged."""
    h = figure_parts(figure).hands[hand]
    site = f"{h.segment}.{h.site}"
    q0 = figure.q.copy()
    groups = {n: np.array(g.angles, dtype=float) for n, g in figure.groups.items()}
    problem = ik.Problem(figure)
    goal = problem.add(ik.Position(site, target, chain=chain or h.start_joint))
    problem.compile()
    mask = goal.chain_mask()
    lo, hi = figure.lower, figure.upper
    rng = np.random.default_rng(seed)

    def hand_at(q: np.ndarray) -> np.ndarray:
        figure.q = q
        return figure.site_world(h.segment, h.site)[:3, 3].copy()

    def dist(q: np.ndarray) -> float:
        return float(np.linalg.norm(hand_at(q) - target))

    start_free = free(q0)
    best: tuple | None = (dist(q0), 0, q0.copy()) if start_free else None
    any_best = (dist(q0), q0.copy())
    status, n_free = "start", int(start_free)
    for k in range(restarts + 1):
        q = q0.copy()
        if k:
            u = rng.uniform(size=int(mask.sum()))
            lo_m, hi_m = np.maximum(lo[mask], -np.pi), np.minimum(hi[mask], np.pi)
            q[mask] = lo_m + u * (hi_m - lo_m)
            figure.q = q  # group angles stay as the last solve left them: part of the random start
        else:
            _seed(figure, q, groups)
        result = ik.solve(problem, max_iterations=max_iterations, tol_position=tolerance / 5)
        qs = figure.q.copy()
        d = dist(qs)
        if d < any_best[0]:
            any_best = (d, qs.copy())
        if not free(qs):
            if not start_free:
                continue
            qs = _back_off(q0, qs, free)
            d = dist(qs)
        else:
            n_free += 1
        rank = prefer(qs) if d <= tolerance else 0
        key = (d > tolerance, rank, d)
        if best is None or key < (best[0] > tolerance, best[1], best[0]):
            best, status = (d, rank, qs.copy()), result.status
        if best[0] <= tolerance and best[1] == 0:
            break
    if best is not None and best[0] > tolerance:
        best = _approach(figure, h, chain or h.start_joint, target, free, best, q0, groups, tolerance,
                         max_iterations)
    figure.q = q0
    for n, a in groups.items():
        figure.groups[n].angles = a
    if best is None:
        return ArmSearch(None, float("inf"), hand_at(q0), "blocked", 0, any_best[0], any_best[1])
    pos = hand_at(best[2])
    figure.q = q0
    return ArmSearch(best[2], best[0], pos, status, n_free, any_best[0], any_best[1])


def _seed(figure: Figure, q: np.ndarray, groups: dict[str, np.ndarray]) -> None:
    """Start an IK at displacements ``q`` with the start posture's group angles (the IK starts a
    joint group, e.g. the shoulder complex, from its group angles, not from the displacements)."""
    figure.q = q.copy()
    for n, a in groups.items():
        figure.groups[n].angles = a.copy()


def _approach(figure: Figure, h, chain: str, target: np.ndarray, free, best: tuple, q0: np.ndarray,
              groups: dict[str, np.ndarray], tolerance: float, max_iterations: int, levels: int = 4) -> tuple:
    """Nearest free hand position on the line from the target back to the shoulder (the chain's
    first joint): bisection on the fraction of the way back, IK from the start posture and from the
    best free posture so far; returns the better of that and ``best`` as ``(distance, rank, q)``."""
    base = figure.joint(chain)
    figure.q = q0
    shoulder = figure.site_world(base.from_seg, base.from_site)[:3, 3].copy()
    lo_s, hi_s = 0.0, 1.0  # fraction of the way from the target back to the shoulder: hi_s is free
    seeds = [q0, best[2]]
    for _ in range(levels):
        mid = (lo_s + hi_s) / 2
        aim = target + mid * (shoulder - target)
        problem = ik.Problem(figure)
        problem.add(ik.Position(f"{h.segment}.{h.site}", aim, chain=chain))
        ok = False
        for seed in seeds:
            _seed(figure, seed, groups)
            ik.solve(problem, max_iterations=max_iterations, tol_position=tolerance / 5)
            qs = figure.q.copy()
            at = figure.site_world(h.segment, h.site)[:3, 3]
            if np.linalg.norm(at - aim) <= 2 * tolerance and free(qs):
                d = float(np.linalg.norm(at - target))
                if d < best[0]:
                    best = (d, 0, qs)
                ok = True
                break
        if ok:
            hi_s = mid
        else:
            lo_s = mid
    return best


def _back_off(q_from: np.ndarray, q_to: np.ndarray, free: Callable[[np.ndarray], bool]) -> np.ndarray:
    """The last free posture on the straight joint-space line from free ``q_from`` to ``q_to``."""
    ok = 0.0
    for s in np.linspace(1 / 16, 1.0, 16):
        if not free(q_from + s * (q_to - q_from)):
            bad = s
            break
        ok = s
    else:
        return q_to.copy()
    for _ in range(5):
        mid = (ok + bad) / 2
        if free(q_from + mid * (q_to - q_from)):
            ok = mid
        else:
            bad = mid
    return q_from + ok * (q_to - q_from)
