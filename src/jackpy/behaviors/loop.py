"""The per-frame behavior loop ([SH4] §4.1, Fig. 4.1; [PB91] §4; behaviors.md §2.2).

One :meth:`BehaviorLoop.step` is one iteration of Jack's control loop with time frozen:

1. input has already written goals into :class:`~jackpy.behaviors.state.BehaviorState`
   (the manipulation commands of :mod:`jackpy.behaviors.manipulation`);
2. every enabled behavior's ``update`` runs in ``order``: automatic root (10), feet (20), pelvis
   (30), balance (40), stepping (50, active), torso (60), gaze (70), hands (80), limit springs (90);
   each reads the figure and adds goals to the frame's passes;
3. the solve, inside the centre-of-mass fixed-point loop ([PB91] §4.3): the **body pass** (legs and
   spine: feet, balance, pelvis, torso; arms, neck and hands frozen), then the **head pass** (neck
   and eyes), then one **arm pass** per hand with the body frozen ([SH4] §4.1.1); the COM is then
   recomputed and, if it has left the balance line by more than ``com_tolerance``, the passes
   repeat (at most ``max_passes``; the book seldom needs more than two);
4. every enabled behavior's ``finish`` runs (attached objects follow hands, steps advance).

**Time box** (:attr:`BehaviorLoop.time_box_s`, or ``step(deadline=...)``): the frame's passes end
by the deadline. Each solve gets the time left (the body pass half of it while limb goals wait; the solves
together at least half the box, however long the behaviors' updates took),
less a margin the loop learns from its own frames (how far a solve has run past the budget it was
given, and what the frame costs after the solve); once the deadline has passed no further COM pass
starts (the report says ``timed_out``). The first pass of each part always runs, so a drag always
moves something, and the limbs pass always gets at least ``LIMB_FLOOR_ITERATIONS`` (counted, not
timed) even when the body pass has spent the box; the solves warm-start, so work cut from one frame
goes on in the next.

**User goals** (:meth:`BehaviorLoop.add_user_goal`): constraints the user adds on any site (an
elbow kept out of a box, a head aim, a site on a plane) join the passes every frame, below the
planted feet: a goal whose chain reaches into an arm or the neck and eyes is solved by those
joints in the limbs pass (at its own level, beside the hands and the gaze); a goal moved only by
legs, pelvis and spine joints goes to the body pass at ``feet level + 1 + level`` (level 0 shares
the balance, pelvis and torso level and trades with them by weight). They are kept objects, so
their compiled problems are reused across frames; only adding, removing, enabling or disabling
one, or changing its level, recompiles.

The loop knows nothing of windows; it reports what it did in a :class:`FrameReport`.
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from jackpy.behaviors.anatomy import SIDES, Anatomy
from jackpy.behaviors.base import Behavior, BehaviorBase
from jackpy.behaviors.state import BehaviorState, FootState, HandState
from jackpy.behaviors.support import BalanceFrame, convex_hull, floor, yaw_of
from jackpy.ik import Problem, solve
from jackpy.ik.result import TIME_LIMIT
from jackpy.ik.goals import GOAL_TYPES, Aim, CentreOfMass, Goal
from jackpy.ik.goals.base import Context
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

#: foot points within this height (m) of the foot's lowest point touch the floor: the actual
#: contact patch (a 7 deg toe or heel lift raises the far corners 6-25 mm, out of contact)
CONTACT_HEIGHT = 0.004
#: distance (m) of the aim point of a direction goal
FAR = 1.0e3
#: a limbs or arm pass left less than this (s) of the frame's box runs this many iterations
#: instead, unboxed (the solver's evaluation cap bounds them: a few arm evaluations, ~1-3 ms): cut
#: frames otherwise starved the arm after a drag, the miss that stayed read as a reach beyond the
#: arm, the figure leaned and stepped, and the released hand ended 10-30 cm off its goal
LIMB_FLOOR_S, LIMB_FLOOR_ITERATIONS = 0.001, 1
#: how the passes solve their priority levels (``ik.solve``'s ``priorities``): the book's projected
#: BFGS with restoration. [decision] The bounded default meets the priority mix's cost targets, but
#: under the passes' 8-15 iteration caps its per-frame progress differs: its lightly damped step
#: turns a pivoting free foot further (a pivot step declined: 49.5 deg where the book step leaves
#: 42.1), and no goal holds that foot's yaw (one frame with the COM 1.2 cm outside the turned
#: contact region); causes traced in docs/ik.md
PRIORITIES = "book"

def reusable_attributes(cls: type) -> tuple[str, ...] | None:
    """The attributes that carry a frame's targets of a goal type whose compiled form the loop
    reuses across frames (copied from the fresh goal a behavior made into the cached one): the
    registered kind's ``targets``, ``params`` and weight (:data:`jackpy.ik.goals.GOAL_TYPES`).
    None for types that are not a registered leaf kind. Binding (site, chain) is part of the cache
    key, so nothing that ``bind`` resolves is ever copied."""
    kind = getattr(cls, "kind", "")
    if not kind or GOAL_TYPES.get(kind) is not cls or not cls.targets:
        return None
    return cls.targets + tuple(p for p in cls.params if p != "chain") + ("weight",)


def _goal_key(goal: Goal) -> tuple | None:
    """Identity of a goal across frames (None: not reusable): type, name, site and chain."""
    if reusable_attributes(type(goal)) is None:
        return None
    chain = getattr(goal, "chain", None)
    if chain is not None and not isinstance(chain, str):
        chain = tuple(chain)
    return type(goal), goal.name, getattr(goal, "site_name", None), chain


#: the parts a user goal can be solved in: the body pass, or the limbs pass's head or an arm
USER_PARTS = ("body", "head", *SIDES)

_KEEP = object()


@dataclass
class UserGoal:
    """A goal the user added (:meth:`BehaviorLoop.add_user_goal`): ``level`` is its priority among
    user goals (0 highest; always below the planted feet), ``part`` the pass that solves it
    (``"body"``, ``"head"``, ``"left"``, ``"right"``), ``key`` an optional name to find it by."""

    goal: Goal
    level: int = 0
    enabled: bool = True
    part: str = "body"
    key: str | None = None


@dataclass
class PassSettings:
    """Interactive budget of one kind of pass: at most ``iterations`` solver iterations per solve
    (the solve warm-starts from the last frame's posture, so an unfinished solve goes on next
    frame), goals achieved within ``tol_position`` m and ``tol_angle`` degrees."""

    iterations: int
    tol_position: float
    tol_angle: float


def default_pass_settings() -> dict[str, PassSettings]:
    """Budgets of the body pass (legs and spine; planted feet held to 0.2 mm), the head pass and
    each arm pass."""
    return {"body": PassSettings(15, 2e-4, 0.1), "head": PassSettings(8, 1e-3, 0.2),
            "arm": PassSettings(10, 5e-4, 0.5)}


@dataclass
class FrameReport:
    """What one frame did: passes of the COM loop, the COM's horizontal distance from the balance
    line after the last pass (m), the root, balance parameters of the COM, notes of behaviors
    (root switches, steps) and the residual error of each pass's goals (m and deg)."""

    passes: int
    com_error: float
    root: str
    balance: tuple[float, float]
    notes: list[str] = field(default_factory=list)
    errors: dict[str, tuple[float, float]] = field(default_factory=dict)
    timed_out: bool = False
    """The frame's deadline ended its COM loop or cut one of its solves."""
    solve_s: float = 0.0
    """Time (s) the COM loop's solves took; the rest of the frame is the behaviors' own work."""


class Frame:
    """One frame's scratch space: the posture at the frame start and the goals of each pass."""

    def __init__(self, loop: "BehaviorLoop") -> None:
        self.loop = loop
        self.figure: Figure = loop.figure
        self.anatomy: Anatomy = loop.anatomy
        self.state: BehaviorState = loop.state
        self.body: list[tuple[Goal, int]] = []
        self.head: list[tuple[Goal, int]] = []
        self.arms: dict[str, list[tuple[Goal, int]]] = {s: [] for s in SIDES}
        self.com_goal: np.ndarray | None = None
        self.com_weight = 1.0
        self.com_level = 1
        self.spine_free = True
        self.notes: list[str] = []
        self._refresh()

    def _refresh(self) -> None:
        self.fk, self.com = self.loop.posture()
        self._balance: BalanceFrame | None = None

    @property
    def cut(self) -> bool:
        """Whether the time box has cut this frame's solves short (read in ``finish``): the posture
        is on its way to the goals, not where the solves would have settled."""
        return self.loop._timed_out

    # ----- reading the posture -----------------------------------------------------------------
    def site(self, seg: str, site: str) -> np.ndarray:
        """World 4x4 of ``seg.site`` at the frame start."""
        kin = self.figure.kinematics()
        return self.fk.segments[kin.segment_index[seg]] @ self.figure.site_location(seg, site)

    def segment(self, seg: str) -> np.ndarray:
        """World 4x4 of a segment's base frame at the frame start."""
        kin = self.figure.kinematics()
        return self.fk.segments[kin.segment_index[seg]]

    def balance_frame(self) -> BalanceFrame:
        """Balance line and support polygon from the feet's goals (where planted feet are)."""
        if self._balance is None:
            self._balance = self.loop.balance_frame_for({s: f.target for s, f in self.state.feet.items()})
        return self._balance

    def invalidate_balance(self) -> None:
        """Recompute the balance frame on next use (after feet goals changed)."""
        self._balance = None

    def balance_params(self) -> tuple[float, float]:
        """(x, z) of the current COM."""
        return self.balance_frame().params(floor(self.com))

    def feet_height(self) -> float:
        """Floor height under the feet (m): the lower of the two ball goals."""
        return min(f.target[1, 3] for f in self.state.feet.values())

    # ----- acting --------------------------------------------------------------------------------
    def set_root(self, root: str) -> None:
        """Re-root through ``"left"``/``"right"`` foot (ball site) or ``"pelvis"``; keeps the world still."""
        self.loop.set_root(root)
        self._refresh()

    def note(self, text: str) -> None:
        self.notes.append(text)

    def keep_direction(self, seg: str, site: str, axis: np.ndarray, direction: np.ndarray,
                       weight: float = 1.0, name: str | None = None) -> Aim:
        """A goal turning segment-local ``axis`` of ``seg`` to the world ``direction`` (an aim at a
        point :data:`FAR` away, so only the direction matters; rotation about it stays free)."""
        loc = self.figure.site_location(seg, site)
        origin = self.site(seg, site)[:3, 3]
        d = np.asarray(direction, dtype=float)
        return Aim(f"{seg}.{site}", origin + FAR * d / np.linalg.norm(d), axis=loc[:3, :3].T @ axis,
                   weight=weight, name=name)


class BehaviorLoop:
    """Runs behaviors and the IK once per frame for one figure.

    ``behaviors`` defaults to :func:`jackpy.behaviors.default_behaviors`; the initial state takes the
    feet where they stand, the balance point under the current COM and the root at the loaded foot.
    """

    def __init__(self, figure: Figure, anatomy: Anatomy, behaviors: Iterable[Behavior] | None = None,
                 max_passes: int = 3, com_tolerance: float = 0.002, max_iterations: int = 30,
                 tol_position: float = 2e-4, passes: dict[str, PassSettings] | None = None,
                 combine_limbs: bool = True) -> None:
        from jackpy.behaviors import default_behaviors

        self.figure = figure
        self.anatomy = anatomy
        self.behaviors: list[Behavior] = list(default_behaviors() if behaviors is None else behaviors)
        self.max_passes = max_passes
        self.com_tolerance = com_tolerance
        self.max_iterations = max_iterations
        self.tol_position = tol_position
        #: per kind of pass ("body", "head", "arm"): iteration cap and tolerances; ``max_iterations``
        #: caps every pass and ``tol_position`` is the body pass's (planted feet) tolerance
        self.passes = default_pass_settings() if passes is None else dict(passes)
        #: solve the head and both arms together (one forward pass per evaluation for all three)
        self.combine_limbs = combine_limbs
        #: time box of one :meth:`step` (s from its start; None: unbounded), see the module docstring
        self.time_box_s: float | None = None
        #: learned margins (s): a solve's run past its budget, and the frame's cost after its solve
        self._overrun_s = 0.0
        self._after_s = 0.0
        self._deadline: float | None = None
        self._box_s = 0.0
        self._timed_out = False
        self.state = BehaviorState()
        #: per pass: goals kept across frames (by :func:`_goal_key`) and the last problem with the
        #: identities of its entries, so an unchanged set of goals is solved without recompiling
        self._goal_cache: dict[str, dict[tuple, Goal]] = {}
        self._problems: dict[str, tuple[list[tuple[int, int]], Problem]] = {}
        self._arm_lengths: dict[str, float] = {}
        self._posture: tuple | None = None
        self._balance_cache: tuple | None = None
        self._footprints = self._footprint_locals()
        self._locked = self._pass_locks()
        #: goals the user added, solved with the behaviors' (see :meth:`add_user_goal`)
        self.user_goals: list[UserGoal] = []
        self.reset_state()

    # ----- set-up ---------------------------------------------------------------------------------
    def _footprint_locals(self) -> dict[str, np.ndarray]:
        """Footprint corners and the reference point (rows) in each foot's ball-site frame."""
        out = {}
        self._heel_local: dict[str, np.ndarray] = {}
        for side, spec in self.anatomy.feet.items():
            ball = self.figure.site_world(*spec.ball)
            inv = np.linalg.inv(ball)
            pts = []
            lateral = np.cross(spec.up, spec.forward)
            seg_w = self.figure.world_transforms()[spec.segment]
            for seg, site in (spec.heel, spec.ball, spec.toe):
                w = self.figure.site_world(seg, site)[:3, 3]
                for s in (-1.0, 1.0):
                    p = w + s * spec.half_width * (seg_w[:3, :3] @ lateral)
                    pts.append(inv[:3, :3] @ p + inv[:3, 3])
            heel = self.figure.site_world(*spec.heel)[:3, 3]
            self._heel_local[side] = inv[:3, :3] @ heel + inv[:3, 3]
            ref = 0.5 * (heel + ball[:3, 3])
            pts.append(inv[:3, :3] @ ref + inv[:3, 3])
            out[side] = np.array(pts)
        return out

    def _pass_locks(self) -> dict[str, list[str]]:
        """Joints each pass locks: all but its own (body: legs and spine; legs; head: neck and
        eyes; each arm)."""
        a = self.anatomy
        legs = [j for f in a.feet.values() for j in f.joints]
        own = {"body": legs + list(a.spine_joints), "legs": legs,
               "head": list(a.neck_joints) + list(a.eye_joints.values())}
        for side, h in a.hands.items():
            own[side] = list(h.arm_joints)
        own["limbs"] = own["head"] + [j for s in a.hands for j in own[s]]
        return {k: [j for j in self.figure.joints if j not in set(v)] for k, v in own.items()}

    def reset_state(self) -> None:
        """State from the current posture: feet planted where they are, balance point under the COM."""
        st = self.state
        st.feet = {s: FootState(self.figure.site_world(*f.ball)) for s, f in self.anatomy.feet.items()}
        st.hands = {s: HandState() for s in self.anatomy.hands}
        bf = self.balance_frame_for({s: f.target for s, f in st.feet.items()})
        x, z = bf.params(floor(self.figure.centre_of_mass()))
        st.balance = (x, z)
        st.balance_point = bf.point(x, z)
        st.pelvis_goal = None
        self.set_root("right" if x >= 0.5 else "left")

    def posture(self) -> tuple[FKResult, np.ndarray]:
        """Forward kinematics and centre of mass of the figure's current posture; computed once
        while the displacements, the root location and the rooting stay the same."""
        kin = self.figure.kinematics()
        q = self.figure.q
        loc = self.figure.location
        c = self._posture
        if c is None or c[0] is not kin or not np.array_equal(c[1], q) or not np.array_equal(c[2], loc):
            fk = kin.forward(q, loc)
            c = self._posture = (kin, q, np.array(loc, dtype=float), fk, kin.centre_of_mass(fk))
        return c[3], c[4]

    def balance_frame_for(self, targets: dict[str, np.ndarray]) -> BalanceFrame:
        """Balance frame of the feet at ball-site poses ``targets`` (contact: below CONTACT_HEIGHT);
        the last one is reused while the targets are unchanged."""
        key = tuple((s, t.tobytes()) for s, t in sorted(targets.items()))
        if self._balance_cache is not None and self._balance_cache[0] == key:
            return self._balance_cache[1]
        bf = self._balance_frame_for(targets)
        self._balance_cache = (key, bf)
        return bf

    def _balance_frame_for(self, targets: dict[str, np.ndarray]) -> BalanceFrame:
        refs, fwd, contact = {}, np.zeros(2), []
        for side, t in targets.items():
            pts = self._footprints[side] @ t[:3, :3].T + t[:3, 3]
            refs[side] = floor(pts[-1])
            corners = pts[:-1]
            low = corners[corners[:, 1] < corners[:, 1].min() + CONTACT_HEIGHT]
            contact.append(floor(low))
            spec = self.anatomy.feet[side]
            fwd += floor(t[:3, :3] @ (self.figure.site_location(*spec.ball)[:3, :3].T @ spec.forward))
        return BalanceFrame(refs["left"], refs["right"], fwd, convex_hull(np.vstack(contact)))

    def foot_reference(self, side: str, target: np.ndarray) -> np.ndarray:
        """Floor reference point (mid-arch) of foot ``side`` with its ball site at pose ``target``."""
        return floor(target[:3, :3] @ self._footprints[side][-1] + target[:3, 3])

    def foot_yaw(self, side: str, target: np.ndarray) -> float:
        """Yaw (rad) of foot ``side``'s forward with its ball site at pose ``target``."""
        spec = self.anatomy.feet[side]
        loc = self.figure.site_location(*spec.ball)
        return yaw_of(target[:3, :3] @ (loc[:3, :3].T @ spec.forward))

    def arm_length(self, side: str) -> float:
        """Shoulder-to-palm-site length (m) of arm ``side`` when straight."""
        if side not in self._arm_lengths:
            h = self.anatomy.hands[side]
            pts = [self.figure.site_world(*h.shoulder)[:3, 3]]
            for jn in h.arm_joints[2:]:
                j = self.figure.joint(jn)
                pts.append(self.figure.site_world(j.to_seg, j.to_site)[:3, 3])
            pts.append(self.figure.site_world(*h.palm)[:3, 3])
            self._arm_lengths[side] = float(sum(np.linalg.norm(b - a) for a, b in zip(pts, pts[1:])))
        return self._arm_lengths[side]

    def heel_point(self, side: str, target: np.ndarray) -> np.ndarray:
        """World heel point of foot ``side`` when its ball site is at pose ``target``."""
        return target[:3, :3] @ self._heel_local[side] + target[:3, 3]

    def set_root(self, root: str) -> None:
        """Root through a foot's ball site or the pelvis, keeping every global transform."""
        if root == "pelvis":
            self.figure.reroot(self.anatomy.pelvis, self.anatomy.pelvis_site)
        else:
            self.figure.reroot(*self.anatomy.feet[root].ball)
        self.state.root = root

    def behavior(self, name: str) -> Behavior:
        """The behavior called ``name``."""
        for b in self.behaviors:
            if b.name == name:
                return b
        raise KeyError(f"no behavior named {name!r}")

    # ----- user goals ---------------------------------------------------------------------------------
    def add_user_goal(self, goal: Goal, level: int = 0, chain: object = _KEEP, *, enabled: bool = True,
                      key: str | None = None, part: str | None = None) -> UserGoal:
        """Solve ``goal`` with the behaviors every frame, below the planted feet.

        ``level``: priority among user goals (0 highest). ``chain`` (when given) replaces the goal's
        chain (None: from the root, a joint name, or a list of joints). ``part`` forces the pass
        (``"body"``, ``"head"``, ``"left"``, ``"right"``); by default a chain that reaches an arm or
        the neck/eyes is solved by that limb, anything else in the body pass. Raises
        :class:`~jackpy.errors.FigureError` for a site or chain the figure lacks.
        """
        if chain is not _KEEP:
            goal.chain = chain  # type: ignore[attr-defined]
        if part is None:
            part = self._part_of(goal)
        elif part not in USER_PARTS:
            raise ValueError(f"part must be one of {USER_PARTS}, not {part!r}")
        if int(level) < 0:
            raise ValueError(f"level must be >= 0, not {level}")
        entry = UserGoal(goal, int(level), bool(enabled), part, key)
        self.user_goals.append(entry)
        return entry

    def user_goal(self, which: "UserGoal | Goal | str") -> UserGoal:
        """The user goal given by itself, its goal or its key (KeyError if none)."""
        for u in self.user_goals:
            if u is which or u.goal is which or (isinstance(which, str) and u.key == which):
                return u
        raise KeyError(f"no user goal {which!r}")

    def remove_user_goal(self, which: "UserGoal | Goal | str") -> None:
        """Stop solving a user goal (given by itself, its goal or its key)."""
        self.user_goals.remove(self.user_goal(which))

    def set_user_goal(self, which: "UserGoal | Goal | str", *, enabled: bool | None = None,
                      weight: float | None = None, level: int | None = None) -> UserGoal:
        """Enable or disable a user goal, or change its weight (no recompile) or level."""
        u = self.user_goal(which)
        if enabled is not None:
            u.enabled = bool(enabled)
        if weight is not None:
            if not weight >= 0.0:
                raise ValueError(f"weight must be >= 0, not {weight}")
            u.goal.weight = float(weight)
        if level is not None:
            if int(level) < 0:
                raise ValueError(f"level must be >= 0, not {level}")
            u.level = int(level)
        return u

    def _part_of(self, goal: Goal) -> str:
        """The pass a goal belongs in by the joints its chain moves: the neck and eyes → ``"head"``,
        an arm → that side, otherwise (legs, pelvis, spine only) ``"body"``."""
        goal.bind(self.figure)
        kin = self.figure.kinematics()
        mask = goal.chain_mask()
        joints = {kin.joint_names[j] for j in np.unique(kin.dof_joint[mask])} if mask.size else set()
        a = self.anatomy
        spine = set(a.spine_joints)
        if joints & ((set(a.neck_joints) | set(a.eye_joints.values())) - spine):
            return "head"
        for side, h in a.hands.items():
            if joints & set(h.arm_joints):
                return side
        return "body"

    def _user_entries(self, part: str) -> list[tuple[Goal, int]]:
        """(goal, level) of the enabled user goals of ``part`` (body levels below the feet)."""
        base = 0
        if part == "body":
            feet = next((b for b in self.behaviors if b.name == "feet"), None)
            base = int(getattr(getattr(feet, "params", None), "level", 0)) + 1
        return [(u.goal, base + u.level) for u in self.user_goals if u.enabled and u.part == part]

    # ----- one frame -------------------------------------------------------------------------------
    def step(self, deadline: float | None = None) -> FrameReport:
        """Run one frame: behaviors, then the passes inside the COM loop, then the finishes.

        ``deadline`` (a ``time.perf_counter()`` time) or else :attr:`time_box_s` bounds the frame's
        solves (module docstring)."""
        start = time.perf_counter()
        if deadline is None and self.time_box_s is not None:
            deadline = start + max(0.0, float(self.time_box_s))
        self._deadline, self._timed_out = deadline, False
        self._box_s = 0.0 if deadline is None else max(0.0, deadline - start)
        frame = Frame(self)
        active = sorted((b for b in self.behaviors if b.enabled), key=lambda b: b.order)
        for b in active:
            b.update(frame)
        begun = time.perf_counter()
        if deadline is not None:  # the solves keep half the box whatever the behaviors took
            self._deadline = max(deadline, begun + 0.5 * self._box_s)
        try:
            passes, com_err, errors = self._solve(frame)
        finally:
            self._deadline = None
        solved = time.perf_counter()
        frame._refresh()
        for b in active:
            b.finish(frame)
        report = FrameReport(passes, com_err, self.state.root, frame.balance_params(), frame.notes, errors,
                             self._timed_out, solved - begun)
        if deadline is not None:
            self._after_s = _learn(self._after_s, time.perf_counter() - solved)
        return report

    def _margin(self, estimate: float) -> float:
        """A learned margin (s), at most a tenth of the frame's box: one slow frame (a first
        compile, a busy machine) must not starve the next frames' solves."""
        return min(estimate, 0.1 * self._box_s)

    def _budget(self, share: float = 1.0) -> float | None:
        """Seconds the next solve may take: ``share`` of what is left before the deadline, less the
        learned margins (None: no deadline). Never negative."""
        if self._deadline is None:
            return None
        left = self._deadline - time.perf_counter() - self._margin(self._after_s)
        return max(0.0, share * left - self._margin(self._overrun_s))

    def _expired(self) -> bool:
        return self._deadline is not None and time.perf_counter() >= self._deadline - self._margin(self._after_s)

    def _solve(self, frame: Frame) -> tuple[int, float, dict[str, tuple[float, float]]]:
        errors: dict[str, tuple[float, float]] = {}
        com_err = 0.0
        body = list(frame.body)
        if frame.com_goal is not None:
            body.append((CentreOfMass(frame.com_goal, weight=frame.com_weight, name="balance"), frame.com_level))
        user = {p: self._user_entries(p) for p in USER_PARTS} if self.user_goals else {}
        n_body = len(body)
        body += user.get("body", [])
        body_pass = "body" if frame.spine_free else "legs"
        limb_goals = {"head": frame.head + user.get("head", []),
                      **{s: frame.arms[s] + user.get(s, []) for s in SIDES}}
        n_own = {"head": len(frame.head), **{s: len(frame.arms[s]) for s in SIDES}}
        if self.combine_limbs:
            # head and arms move disjoint joints after the body: one solve, one forward pass per
            # evaluation for all three (their goals do not interact)
            limbs = [(g, lv) for goals in limb_goals.values() for g, lv in goals]
            owner = [k if i < n_own[k] else "user" for k, goals in limb_goals.items() for i in range(len(goals))]
        passes = 0
        limbs_wait = any(limb_goals.values())
        for passes in range(1, self.max_passes + 1):
            if passes > 1 and self._expired():
                self._timed_out = True  # the time box ends the COM loop: the next frame goes on
                passes -= 1
                break
            per_body = self._solve_pass(body, body_pass, share=0.5 if limbs_wait else 1.0)
            errors["body"] = _worst(per_body[:n_body])
            user_errs = per_body[n_body:]
            if self.combine_limbs:
                per_goal = self._solve_pass(limbs, "limbs")
                for k in limb_goals:
                    errors[k] = _worst([e for e, o in zip(per_goal, owner) if o == k])
                user_errs += [e for e, o in zip(per_goal, owner) if o == "user"]
            else:
                for k in limb_goals:
                    per = self._solve_pass(limb_goals[k], k)
                    errors[k] = _worst(per[:n_own[k]])
                    user_errs += per[n_own[k]:]
            if user.get("body") or any(user.get(k) for k in limb_goals):
                errors["user"] = _worst(user_errs)
            if frame.com_goal is None:
                break
            c = self.posture()[1]
            prev, com_err = com_err, float(np.hypot(c[0] - frame.com_goal[0], c[2] - frame.com_goal[2]))
            if com_err <= self.com_tolerance:
                break
            if passes > 1 and com_err > 0.5 * prev:
                break  # the body's goals hold the COM off (a lean, a limit): another pass won't help
        return passes, com_err, errors

    def _reuse(self, which: str, goal: Goal) -> Goal:
        """The cached goal of pass ``which`` with ``goal``'s identity, its targets updated from
        ``goal``; or ``goal`` itself (cached for next frame) when there is none. User goals are
        kept objects already and are never cached (a name they share with a behavior's goal must
        not swap targets)."""
        key = _goal_key(goal)
        if key is None or any(u.goal is goal for u in self.user_goals):
            return goal
        cache = self._goal_cache.setdefault(which, {})
        old = cache.get(key)
        if old is None or old is goal:
            cache[key] = goal
            return goal
        for attr in reusable_attributes(type(goal)) or ():
            setattr(old, attr, getattr(goal, attr))
        return old

    def problem_for(self, goals: list[tuple[Goal, int]], which: str) -> Problem:
        """The IK problem of pass ``which`` for ``goals``: last frame's when the same goals (by
        identity, see :meth:`_reuse`) sit at the same levels, so it keeps its compiled form (it
        recompiles by itself when the figure is re-rooted); otherwise a new one."""
        entries = []
        seen: set[int] = set()
        for g, level in goals:
            g = self._reuse(which, g)
            if id(g) in seen:  # two goals with one identity: keep both, as distinct objects
                g = goals[len(entries)][0]
            seen.add(id(g))
            entries.append((g, level))
        key = [(id(g), lv) for g, lv in entries]
        cached = self._problems.get(which)
        if cached is not None and cached[0] == key:
            return cached[1]
        problem = Problem(self.figure)
        for g, level in entries:
            problem.add(g, level)
        problem.lock(*self._locked[which])
        self._problems[which] = (key, problem)
        return problem

    def _solve_pass(self, goals: list[tuple[Goal, int]], which: str,
                    share: float = 1.0) -> list[tuple[float, float]]:
        """Solve ``goals`` (goal, priority level) moving only the joints of pass ``which`` within its
        budget (:class:`PassSettings`) and ``share`` of the time left in the frame's box; returns
        each goal's residual (m, deg)."""
        if not goals:
            return []
        problem = self.problem_for(goals, which)
        kind = "body" if which in ("body", "legs") else "head" if which == "head" else "arm"
        ps = self.passes[kind]
        tol = min(ps.tol_position, self.tol_position) if kind == "body" else ps.tol_position
        tol_angle = min(ps.tol_angle, self.passes["head"].tol_angle) if which == "limbs" else ps.tol_angle
        held = self._held(problem, tol, tol_angle)
        if held is not None:
            return held
        budget = self._budget(share)
        iterations = min(ps.iterations, self.max_iterations)
        if budget is not None and kind != "body" and budget < LIMB_FLOOR_S:
            # [decision] the limbs (the hand being dragged) always move: with the box spent by the
            # body pass they get LIMB_FLOOR_ITERATIONS counted iterations, not a box of nothing
            budget, iterations = None, min(iterations, LIMB_FLOOR_ITERATIONS)
        t0 = time.perf_counter()
        result = solve(problem, max_iterations=iterations, tol_position=tol,
                       tol_angle=tol_angle, time_budget_s=budget, priorities=PRIORITIES)
        if budget is not None:
            self._overrun_s = _learn(self._overrun_s, time.perf_counter() - t0 - budget)
            self._timed_out |= result.status == TIME_LIMIT
        return [(g.metres, g.degrees) for g in result.goals]

    def _held(self, problem: Problem, tol: float, tol_angle: float) -> list[tuple[float, float]] | None:
        """Each goal's residual at the current posture if every goal is already met, else None.

        Checked on the cached forward pass without Jacobian columns (no joint-group derivatives),
        so a pass whose goals still hold costs almost nothing. The balance goal counts as met within
        half the COM loop's tolerance; the solve, when it runs, still drives it to ``tol``, which
        leaves slack for the next frames' small arm motions.
        """
        comp = problem.compile()
        fk, _ = self.posture()
        ctx = Context(comp.kin, fk, np.zeros(0, dtype=int))
        out = []
        for g, _ in comp.entries:
            e = g.evaluate(ctx)
            limit = 0.5 * self.com_tolerance if isinstance(g, CentreOfMass) else tol
            if e.metres > limit or e.degrees > tol_angle:
                return None
            out.append((e.metres, e.degrees))
        return out


def _learn(estimate: float, sample: float) -> float:
    """A cost estimate (s, >= 0): half way to a higher sample, a fifth of the way to a lower one."""
    w = 0.5 if sample > estimate else 0.2
    return max(0.0, estimate + w * (sample - estimate))


def _worst(errs: list[tuple[float, float]]) -> tuple[float, float]:
    """The largest residual (m, deg) of a list of goal residuals; (0, 0) for none."""
    return max((e[0] for e in errs), default=0.0), max((e[1] for e in errs), default=0.0)


__all__ = ["BehaviorBase", "BehaviorLoop", "Frame", "FrameReport", "PassSettings", "USER_PARTS", "UserGoal",
           "default_pass_settings"]
