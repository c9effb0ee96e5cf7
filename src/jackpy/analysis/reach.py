"""Point reach: can this hand reach this point, and if not, how far short is it (IK, book §3.2;
issue 8: "feet planted (or allowed to step) ... uses the IK with balance").

Three modes:

* ``"arm"`` (default): a position goal on the hand's reference site is solved over the arm chain
  (from the clavicle: the torso, pelvis and feet stay where they are) or over a longer chain given
  by ``start_joint`` (e.g. the lowest spine joint to let the torso bend). The IK ends at the target
  or, when the target is out of reach, at the constrained minimum of the distance: the arm stretched
  towards it (book §3.4.1: a target outside the reach ends on the envelope). Balance is not checked.
* ``"body"``: whole-body reach with the feet planted, through the behaviors
  (:class:`jackpy.behaviors.BehaviorLoop` on a *copy* of the figure): the hand goal is moved from
  the hand to the target over ``ramp`` frames with *lean* on, so an out-of-reach goal bends the
  spine and hips and shifts the weight towards it (never past the edge of the feet), the torso and
  balance behaviors keeping the figure upright and balanced. Stepping is off.
* ``"step"``: as ``"body"`` with the Stepping behavior on: when the weight reaches the edge of the
  feet the figure steps towards the target, then leans again.

Both behavior modes run a bounded number of frames (``max_frames``; no wall time): they stop when
the hand is within the tolerance with no step under way, or when the distance has not improved by
``STALL_IMPROVEMENT`` over ``STALL_FRAMES`` frames (no step under way), or at ``max_frames``. The
answer is the best *balanced* frame (centre of mass inside the support polygon of the planted feet,
no step under way, joints within limits; the starting posture counts): a figure that can only get
nearer by falling over is reported short from where it still stands. From that frame the arm alone
(IK from the clavicle, body and feet fixed, position only) takes the last millimetres, kept when the
figure stays balanced: the behaviors keep the elbow 10° short of full extension (limit springs) and
weigh the hand against the lean, which leaves a few millimetres. The result carries that
posture (:class:`Posture`: root, root location, displacements, group angles) for the report's
picture and strength, the steps taken to get there, and the balance margin.

With ``obstacles`` (the workplace's objects) every mode is collision-aware (issue 16,
:mod:`jackpy.planning.collision_reach`): a posture counts only when no segment passes into an
object deeper than the contact tolerance; the arm mode searches several IK starts for such a
posture, the behavior modes keep the best *free* balanced frame. The result then carries a
:class:`~jackpy.planning.collision_reach.Verdict`: reached, reached only by touching X, blocked
by X, or short by N cm.
"""

from __future__ import annotations

import copy
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from jackpy import ik
from jackpy.analysis.parts import figure_parts
from jackpy.peabody.model import Figure

#: a hand within this distance of the target has reached it (metres)
REACH_TOLERANCE = 0.005
#: reach modes: arm chain only; whole body with the feet planted; whole body allowed to step
MODES = ("arm", "body", "step")
#: behavior modes stop when the distance has not improved by this much (m) ...
STALL_IMPROVEMENT = 0.002
#: ... over this many frames (with no step under way)
STALL_FRAMES = 15


@dataclass
class Posture:
    """A whole posture: the root ``segment.site``, its world ``location`` (4x4), the displacements
    ``q`` and each joint group's angles."""

    root: tuple[str, str]
    location: np.ndarray
    q: np.ndarray
    group_angles: dict[str, np.ndarray] = field(default_factory=dict)

    @classmethod
    def of(cls, figure: Figure) -> Posture:
        return cls(tuple(figure.root), np.array(figure.location, dtype=float), figure.q.copy(),
                   {n: np.array(g.angles, dtype=float) for n, g in figure.groups.items()})

    def apply(self, figure: Figure, root: tuple[str, str] | None = None) -> None:
        """Put ``figure`` (the figure this posture was taken from, or a copy of it) in this posture;
        with ``root`` re-root it there afterwards (world transforms kept)."""
        if tuple(figure.root) != tuple(self.root):  # re-rooting rebuilds the figure's kinematics
            figure.reroot(*self.root)
        figure.location = self.location.copy()
        figure.q = self.q.copy()
        for n, a in self.group_angles.items():
            if n in figure.groups:
                figure.groups[n].angles = a.copy()
        if root is not None and tuple(root) != tuple(self.root):
            figure.reroot(*root)


@dataclass
class PointReach:
    """Outcome of one reach: ``shortfall`` metres between the hand and ``target`` after the solve,
    ``reached`` when that is within the tolerance, the hand's final world ``position`` and the
    posture ``q`` that got there (IK ``status``; for the behavior modes ``"behaviors"``).

    ``mode`` is the reach mode; ``steps`` the steps taken (``"step"`` mode); ``frames`` the
    behavior frames run; ``com_margin`` the signed distance (m, negative inside) of the centre of
    mass from the support polygon of the feet in the final posture (None in ``"arm"`` mode, where
    balance is not checked); ``posture`` the whole final posture (root, location, q)."""

    target: np.ndarray
    reached: bool
    shortfall: float
    position: np.ndarray
    q: np.ndarray
    status: str
    mode: str = "arm"
    steps: int = 0
    frames: int = 0
    com_margin: float | None = None
    posture: Posture | None = None
    #: collision-aware verdict (:class:`jackpy.planning.collision_reach.Verdict`; None without obstacles)
    verdict: Any = None
    #: with obstacles: ``(shortfall, Posture)`` reached when collisions are ignored (what "blocked" compares with)
    verdict_any: Any = None

    @property
    def stepped(self) -> bool:
        return self.steps > 0

    @property
    def balanced(self) -> bool | None:
        """Centre of mass inside the support polygon (None: not checked, ``"arm"`` mode)."""
        return None if self.com_margin is None else self.com_margin <= 0.0

    def describe(self) -> str:
        """One line for a report: ``reached (2 mm)`` or ``short by ~10 cm`` (``, 1 step`` added
        when the figure stepped); with obstacles the verdict's words (``blocked by partition ...``)."""
        if self.verdict is not None:
            text = self.verdict.describe()
            if self.steps:
                text += f", {self.steps} step" + ("s" if self.steps > 1 else "")
            return text
        text = (f"reached ({self.shortfall * 1e3:.0f} mm)" if self.reached
                else f"short by ~{self.shortfall * 100:.0f} cm")
        if self.steps:
            text += f", {self.steps} step" + ("s" if self.steps > 1 else "")
        return text


def point_reach(figure: Figure, target: np.ndarray, hand: str = "right", start_joint: str | None = None,
                tolerance: float = REACH_TOLERANCE, keep_posture: bool = False,
                max_iterations: int = 300, mode: str = "arm", max_frames: int = 150,
                ramp: int = 20, obstacles: Sequence[Figure] | None = None, target_object: str | None = None,
                contact_tolerance: float | None = None, restarts: int = 16) -> PointReach:
    """Reach for world point ``target`` (metres) with ``hand`` (``"right"``/``"left"``) from the
    figure's current posture, in ``mode`` ``"arm"``, ``"body"`` or ``"step"`` (module docstring).

    ``"arm"``: the chain starts at ``start_joint`` (default: the arm's clavicle), at most
    ``max_iterations`` IK iterations. ``"body"``/``"step"``: at most ``max_frames`` behavior frames,
    the goal moved onto the target over ``ramp`` frames, on a copy of the figure (``start_joint``
    and ``max_iterations`` are not used). The figure's posture is restored afterwards unless
    ``keep_posture`` (then it takes the final posture, root included).

    ``obstacles``: objects (CAD figures) the posture must not pass into deeper than
    ``contact_tolerance`` (default :data:`jackpy.planning.collision_reach.CONTACT_TOLERANCE`);
    ``target_object``: the target's own object, which the hand may touch; ``restarts``: extra
    random IK starts of the arm search."""
    if mode not in MODES:
        raise ValueError(f"reach mode must be one of {MODES}, not {mode!r}")
    target = np.asarray(target, dtype=float).reshape(3)
    if obstacles is not None:
        r = _collision_aware_reach(figure, target, hand, start_joint, tolerance, max_iterations, mode,
                                   max_frames, ramp, list(obstacles), target_object, contact_tolerance, restarts)
        if keep_posture and r.posture is not None:
            r.posture.apply(figure)
        return r
    if mode != "arm":
        r = _behavior_reach(figure, target, hand, mode, tolerance, max_frames, ramp)
        if keep_posture:
            r.posture.apply(figure)
        return r
    h = figure_parts(figure).hands[hand]
    before = Posture.of(figure)
    problem = ik.Problem(figure)
    problem.add(ik.Position(f"{h.segment}.{h.site}", target, chain=start_joint or h.start_joint))
    result = ik.solve(problem, max_iterations=max_iterations, tol_position=tolerance / 5)
    position = figure.site_world(h.segment, h.site)[:3, 3].copy()
    shortfall = float(np.linalg.norm(position - target))
    q = figure.q
    posture = Posture.of(figure)
    if not keep_posture:
        before.apply(figure)  # group angles too: the IK moves them with the displacements
    return PointReach(target, shortfall <= tolerance, shortfall, position, q, result.status, posture=posture)


def _anatomy(figure: Figure):
    from jackpy.behaviors.anatomy import human_anatomy, synthetic_anatomy

    return human_anatomy(figure) if "right_palm" in figure.segments else synthetic_anatomy(figure)


def _collision_aware_reach(figure: Figure, target: np.ndarray, hand: str, start_joint: str | None,
                           tolerance: float, max_iterations: int, mode: str, max_frames: int, ramp: int,
                           obstacles: list[Figure], target_object: str | None, contact_tolerance: float | None,
                           restarts: int) -> PointReach:
    from jackpy.planning import collision_reach as cr

    tol = cr.CONTACT_TOLERANCE if contact_tolerance is None else contact_tolerance
    judge = cr.WorkplaceJudge(figure, obstacles, tol)
    hands = cr.hand_segments(figure, hand)
    judge.allow_hand_on({figure_parts(figure).hands[hand].segment}, target_object)
    arm = _free_arm_reach(figure, target, hand, start_joint, tolerance, max_iterations, judge, hands,
                          target_object, restarts)
    if mode == "arm" or arm.reached:
        arm.mode = mode
        if mode != "arm" and arm.posture is not None:
            arm.com_margin = _com_margin(figure, arm.posture)
        return arm
    # the behaviors only when the arm alone does not reach; then the arm again from their best free
    # balanced posture (the behaviors hold the elbow short of full extension)
    r, unconstrained = _behavior_reach(figure, target, hand, mode, tolerance, max_frames, ramp, accept=judge.free)
    if r.posture is not None:
        fig = copy.deepcopy(figure)
        r.posture.apply(fig)
        polish = _free_arm_reach(fig, target, hand, None, tolerance, 100, judge, hands, target_object, min(restarts, 4))
        if polish.posture is not None and polish.shortfall < r.shortfall:
            r.shortfall, r.position, r.posture, r.q = polish.shortfall, polish.position, polish.posture, polish.q
    if arm.posture is not None and arm.shortfall < r.shortfall:
        r.shortfall, r.position, r.posture, r.q, r.steps = arm.shortfall, arm.position, arm.posture, arm.q, 0
    if r.posture is None:
        r.verdict = cr.Verdict("blocked", r.shortfall, blocked_by=_first_body(judge.penetrations(unconstrained[1])),
                               tolerance=tol)
    else:
        best_any = min((unconstrained[0], unconstrained[1]), (arm.verdict_any[0], arm.verdict_any[1]),
                       key=lambda t: t[0])
        r.verdict = cr.judge(judge, r.posture, r.shortfall, r.position, target, tolerance, target_object,
                             hands, best_any)
    r.reached = r.verdict.reached
    return r


def _free_arm_reach(figure: Figure, target: np.ndarray, hand: str, start_joint: str | None, tolerance: float,
                    max_iterations: int, judge, hands: set[str], target_object: str | None,
                    restarts: int) -> PointReach:
    """Collision-free arm reach from ``figure``'s posture (the arm search of
    :func:`jackpy.planning.collision_reach.collision_free_arm_reach`) with its verdict; the
    result's ``verdict_any`` holds the shortfall and posture reached ignoring collisions."""
    from jackpy.planning import collision_reach as cr

    tol = judge.tolerance
    root, location = tuple(figure.root), figure.location.copy()
    groups = {n: np.array(g.angles, dtype=float) for n, g in figure.groups.items()}

    def posture(q: np.ndarray) -> Posture:
        return Posture(root, location, q, groups)

    def prefer(q: np.ndarray) -> int:
        return len(cr.unintended_touches(judge.touches(posture(q)), target_object, hands))

    s = cr.collision_free_arm_reach(figure, target, hand, start_joint, lambda q: judge.free(posture(q)), prefer,
                                    tolerance, restarts, max_iterations)
    if s.q is None:  # the start posture itself passes into an object and no IK start is free
        v = cr.Verdict("blocked", s.any_shortfall, blocked_by=_first_body(judge.penetrations(posture(figure.q))),
                       tolerance=tol)
        r = PointReach(target, False, s.any_shortfall, s.position, figure.q.copy(), "blocked", verdict=v)
    else:
        p = posture(s.q)
        v = cr.judge(judge, p, s.shortfall, s.position, target, tolerance, target_object, hands,
                     (s.any_shortfall, posture(s.any_q)))
        r = PointReach(target, v.reached, s.shortfall, s.position, s.q.copy(), s.status, posture=p, verdict=v)
    r.verdict_any = (s.any_shortfall, posture(s.any_q))
    return r


def _com_margin(figure: Figure, posture: Posture) -> float:
    """Signed distance (m, negative inside) of the centre of mass of ``figure`` in ``posture`` from
    the support polygon of its feet where they stand."""
    from jackpy.behaviors import BehaviorLoop
    from jackpy.behaviors.support import floor

    fig = copy.deepcopy(figure)
    posture.apply(fig)
    loop = BehaviorLoop(fig, _anatomy(fig))
    feet = {s: f.target.copy() for s, f in loop.state.feet.items()}
    return float(loop.balance_frame_for(feet).margin(floor(fig.centre_of_mass())))


def _first_body(pairs: list[tuple[str, str]]) -> str | None:
    return pairs[0][1] if pairs else None


def _behavior_reach(figure: Figure, target: np.ndarray, hand: str, mode: str, tolerance: float,
                    max_frames: int, ramp: int, accept=None):
    from jackpy.behaviors import BehaviorLoop
    from jackpy.behaviors import manipulation as m
    from jackpy.behaviors.support import floor

    h = figure_parts(figure).hands[hand]
    fig = copy.deepcopy(figure)  # the behaviors re-root and move the figure: never the caller's
    loop = BehaviorLoop(fig, _anatomy(fig))
    loop.behavior("stepping").enabled = mode == "step"
    stepping = loop.behavior("stepping")
    palm = loop.anatomy.hands[hand].palm
    lo, hi = fig.lower - 1e-9, fig.upper + 1e-9

    def site() -> np.ndarray:
        return fig.site_world(h.segment, h.site)[:3, 3].copy()

    def margin(feet: dict[str, np.ndarray]) -> float:
        bf = loop.balance_frame_for(feet)
        return float(bf.margin(floor(fig.centre_of_mass())))

    def feet_now() -> dict[str, np.ndarray]:
        return {s: f.target.copy() for s, f in loop.state.feet.items()}

    start = site()
    best_d, best_feet = float(np.linalg.norm(start - target)), feet_now()
    best_m, best_p, best_pos, best_steps = margin(best_feet), Posture.of(fig), start, 0
    ref_d, improved_at, frames = best_d, 0, 0
    any_d, any_p = best_d, best_p
    if accept is not None and not accept(best_p):
        best_d, best_p = float("inf"), None
    for frames in range(1, max_frames + 1):
        u = min(1.0, frames / max(ramp, 1))
        want = (1.0 - u) * start + u * target
        # the behaviors drive the palm site; aim it so that the reach's reference site lands on ``want``
        offset = fig.site_world(*palm)[:3, 3] - site()
        m.move_hand(loop, hand, position=want + offset, lean=True)
        loop.step()
        pos = site()
        d = float(np.linalg.norm(pos - target))
        idle = stepping.step is None
        if idle and d < max(best_d, any_d):
            q, feet = fig.q, feet_now()
            mg = margin(feet)
            if mg <= 0.0 and np.all(q >= lo) and np.all(q <= hi):
                p = Posture.of(fig)
                if d < any_d:
                    any_d, any_p = d, p
                if d < best_d and (accept is None or accept(p)):
                    best_d, best_m, best_p, best_pos, best_feet = d, mg, p, pos, feet
                    best_steps = loop.state.steps_taken
        if min(best_d, any_d) < ref_d - STALL_IMPROVEMENT:
            ref_d, improved_at = min(best_d, any_d), frames
        if u < 1.0 or not idle:
            continue
        if best_d <= tolerance or frames - improved_at >= STALL_FRAMES:
            break
    # polish: the behaviors hold the elbow short of full extension (limit springs) and weigh the hand
    # against the lean; the arm alone (body, feet fixed) takes the last millimetres when that keeps
    # the balance
    if best_p is None:  # with ``accept``: no free balanced frame, not even the start
        r = PointReach(target, False, any_d, start, fig.q.copy(), "behaviors", mode, 0, frames, None, None)
        return r, (any_d, any_p)
    best_p.apply(fig)
    problem = ik.Problem(fig)
    problem.add(ik.Position(f"{h.segment}.{h.site}", target, chain=h.start_joint))
    ik.solve(problem, max_iterations=100, tol_position=tolerance / 5)
    pos, q = site(), fig.q
    d, mg = float(np.linalg.norm(pos - target)), margin(best_feet)
    if d < best_d and mg <= 0.0 and np.all(q >= lo) and np.all(q <= hi):
        p = Posture.of(fig)
        if d < any_d:
            any_d, any_p = d, p
        if accept is None or accept(p):
            best_d, best_m, best_p, best_pos = d, mg, p, pos
    r = PointReach(target, best_d <= tolerance, best_d, best_pos, best_p.q.copy(), "behaviors", mode,
                   best_steps, frames, best_m, best_p)
    return r if accept is None else (r, (any_d, any_p))
