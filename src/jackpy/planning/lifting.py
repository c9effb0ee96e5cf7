"""Strength-guided lifting (Philip Lee's strength-guided motion, book §5.3; spec C13, C14, §2.9).

Given a load (kg) held in one hand, a goal for it (world metres), a comfort level ``cl`` and a
perceived exertion ``pe``, :func:`strength_guided_lift` maps out the hand path and the joint
trajectories one short step at a time (§5.3.3): the condition monitor
(:mod:`.lifting_monitor`) reports the static torques and the torque ratios ``r_i = |tau_i| /
tau_max,i`` of the arm and trunk; it picks a strategy by comfort band; the path planning scheme
(:mod:`.lifting_strategies`) picks the hand direction and the joint step; a rate model gives the
time of the step. The strategies, in order of rising discomfort (§5.3.4, §5.3.5):

1. **available torque** (``R <= RM_ONSET·cl``): the hand heads along ``dx = J w`` (eq. 5.18), with
   the headroom weights ``w = a ⊙ J^+ u`` - the joint motion that would move the hand straight to
   the goal (``u``), scaled per joint by its torque availability ``a`` - projected into the
   perceived-exertion cone (half-angle ``pe·90°``, a [proposal] of the spec); the joint step moving
   the hand that way is the availability-weighted least-norm one, so joints with much torque
   available do most of the work. With a light load (``a`` nearly even) the path is nearly
   straight, the book's "minimum time path" (§5.3.6);
2. **reducing moment** (``RM_ONSET·cl < R <= cl``, or when the available-torque step would pass
   ``cl``): the direction inside the cone along which the discomfort grows least, found by a
   virtual displacement of each active joint, plus a null-space motion that lowers it;
   when even that passes ``cl`` the cone is widened (the Discomfort band: "a larger path deviation
   is allowed");
3. **pull back** (``R > cl``, until ``R <= PB_RELEASE·cl``): direct joint control, the goal is
   ignored and the active joints move down the discomfort gradient (the weakest joint reverses and
   the hand moves away from the goal);
4. **added joint**: when pull back is exhausted (it no longer lowers the discomfort) or the hand
   has stopped gaining on the goal, the waist (the spine group's flexion: the trunk leans, :data:`WAIST_ANGLES`) joins
   the hand-shoulder chain (§5.3.6, Fig 5.18). When that too is exhausted the lift stops and
   reports failure (§5.3.3: "the attempt to complete a task should cease").

Here ``cl`` is the largest torque ratio the lifter accepts (the effective maximum strength is
``cl × tau_max``, §5.3.4; eq. 5.19's ``dcl``); the reported comfort is ``1 - max_i r_i``. Static
torques only, as in the book's examples. Deterministic: no randomness anywhere.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from jackpy import ik
from jackpy.analysis.parts import figure_parts
from jackpy.peabody.groups import VariableMap
from jackpy.peabody.model import Figure
from jackpy.planning.lifting_monitor import ChainState, LiftingMonitor
from jackpy.planning.lifting_strategies import (availability, least_moment_direction, project_to_cone,
                                                weighted_pinv, weighted_step)

AVAILABLE_TORQUE, REDUCING_MOMENT, PULL_BACK, ADDED_JOINT = ("available torque", "reducing moment",
                                                             "pull back", "added joint")
#: reducing moment takes over when the discomfort passes this fraction of cl
RM_ONSET = 0.8
#: pull back ends when the discomfort is back below this fraction of cl
PB_RELEASE = 0.9
#: pull back is exhausted after this many steps without lowering the discomfort by PB_MIN_GAIN
PB_PATIENCE = 4
PB_MIN_GAIN = 1e-4
#: the hand has stalled when it has not come this much nearer the goal (m) in STALL_STEPS steps
STALL_GAIN = 0.002
STALL_STEPS = 40
#: a group limit row is touched when the posture is this near it (rad along the row's normal)
SLIDE_SLACK = 1e-3
#: largest change of any active variable in one step (rad)
MAX_JOINT_STEP = np.radians(2.0)
#: the added joint: the waist's forward/backward bend (the spine group's flexion, spread over the
#: vertebrae by Monheit's model), the sagittal lean of the book's Fig 5.18; bend and twist stay held
WAIST_ANGLES = ("flexion",)
#: the planner keeps the shoulder's elevation above this (rad; or above the start's when lower): at 0
#: the plane of elevation is singular and a step "through" the hanging arm would be clamped
MIN_ELEVATION = np.radians(10.0)
#: torque availability never drops below this (a joint at its limit still moves a little)
AVAILABILITY_FLOOR = 0.05
#: rate model [proposal]: the fastest joint moves at W_MAX·(1 - R) rad/s (R the discomfort, at most 1),
#: at least RATE_FLOOR of W_MAX: light loads move fast, heavy ones slowly (§5.3.6)
W_MAX = 3.0
RATE_FLOOR = 0.1


@dataclass
class LiftTask:
    """A lift: ``load_kg`` in ``hand`` ("right"/"left") to ``goal`` (world m) from ``start`` (world
    m; None: the figure's current grip position), comfort level ``comfort`` (largest accepted torque
    ratio, 0-1], perceived exertion ``exertion`` (cone half-angle = exertion × 90°), hand travel
    ``step`` (m) per iteration. ``allow_waist`` permits the added joint. ``fatigue_time`` (s, None:
    no fatigue) lowers the effective comfort limit as ``cl·exp(-t/T)`` (§5.3.8 [proposal])."""

    load_kg: float
    goal: np.ndarray
    start: np.ndarray | None = None
    comfort: float = 0.5
    exertion: float = 0.3
    hand: str = "right"
    allow_waist: bool = True
    step: float = 0.01
    tolerance: float = 0.01
    max_iterations: int = 800
    fatigue_time: float | None = None

    def __post_init__(self) -> None:
        self.goal = np.asarray(self.goal, dtype=float).reshape(3)
        if self.start is not None:
            self.start = np.asarray(self.start, dtype=float).reshape(3)
        if not np.all(np.isfinite(self.goal)) or (self.start is not None and not np.all(np.isfinite(self.start))):
            raise ValueError("goal and start must be finite points (m)")
        if not (self.load_kg >= 0.0 and np.isfinite(self.load_kg)):
            raise ValueError(f"load must be a finite mass >= 0 kg, not {self.load_kg}")
        if not 0.0 < self.comfort <= 1.0:
            raise ValueError(f"comfort level must lie in (0, 1], not {self.comfort}")
        if not 0.0 <= self.exertion <= 1.0:
            raise ValueError(f"perceived exertion must lie in [0, 1], not {self.exertion}")
        if self.hand not in ("left", "right"):
            raise ValueError(f"hand must be 'left' or 'right', not {self.hand!r}")
        if not self.step > 0.0 or not self.tolerance > 0.0:
            raise ValueError("step and tolerance must be > 0 m")


@dataclass
class LiftFrame:
    """One iteration: time (s), the figure's variables (:class:`VariableMap` order), grip and
    shoulder-joint positions (world m), joint displacements, torque ratios of the monitored DOFs,
    the effective limit, the strategy used, the active chain, the work ``sum tau_i dtheta_i`` of the step (J, eq. 5.20) and the energy so far (``sum |dW|``)."""

    t: float
    x: np.ndarray
    hand: np.ndarray
    shoulder: np.ndarray
    q: np.ndarray
    ratios: np.ndarray
    limit: float
    strategy: str
    chain: str
    work: float
    energy: float

    @property
    def discomfort(self) -> float:
        return float(self.ratios.max())


@dataclass
class LiftResult:
    """The lift's frames, whether the goal was reached, why it stopped, the strategy changes
    ``(frame, strategy)`` (the strategy of the step that made that frame on) and the frame after
    which the waist joined the chain (None: never)."""

    task: LiftTask
    frames: list[LiftFrame]
    reached: bool
    reason: str
    monitored: list[str]
    joint_groups: dict[str, list[int]]
    strategy_log: list[tuple[int, str]] = field(default_factory=list)
    waist_added_at: int | None = None
    figure_name: str = ""
    waist_variables: list[int] = field(default_factory=list)

    @property
    def hand_path(self) -> np.ndarray:
        """(N, 3) grip positions, world m."""
        return np.array([f.hand for f in self.frames])

    @property
    def times(self) -> np.ndarray:
        return np.array([f.t for f in self.frames])

    def horizontal_distance(self) -> np.ndarray:
        """(N,) horizontal (x-z) distance of the grip from the shoulder joint, m, per frame."""
        d = np.array([f.hand - f.shoulder for f in self.frames])
        return np.hypot(d[:, 0], d[:, 2])

    def joint_ratios(self) -> dict[str, np.ndarray]:
        """Per monitored joint group (shoulder, elbow, waist), its largest torque ratio per frame."""
        r = np.array([f.ratios for f in self.frames])
        return {name: r[:, idx].max(axis=1) for name, idx in self.joint_groups.items()}

    def waist_motion(self) -> float:
        """Largest change (rad) of a waist angle (the spine group's flexion, lateral bend or twist,
        each the sum over the vertebrae) from the start over the lift."""
        x = np.array([f.x for f in self.frames])[:, self.waist_variables]
        return float(np.abs(x - x[0]).max())

    def strategies_used(self) -> list[str]:
        """The distinct strategies in the order first used."""
        out: list[str] = []
        for _, s in self.strategy_log:
            if s not in out:
                out.append(s)
        return out

    def summary(self) -> dict[str, Any]:
        """A JSON-ready summary (SI units): task, outcome, strategy log and the per-frame series."""
        t = self.task
        dist = self.horizontal_distance()
        return {
            "figure": self.figure_name,
            "task": {"load_kg": t.load_kg, "goal_m": t.goal.tolist(),
                     "start_m": None if t.start is None else t.start.tolist(), "comfort": t.comfort,
                     "exertion": t.exertion, "hand": t.hand, "allow_waist": t.allow_waist, "step_m": t.step},
            "reached": self.reached, "reason": self.reason, "iterations": len(self.frames) - 1,
            "duration_s": float(self.frames[-1].t), "strategies": self.strategy_log,
            "waist_added_at": self.waist_added_at, "waist_motion_deg": float(np.degrees(self.waist_motion())),
            "peak_discomfort": float(max(f.discomfort for f in self.frames)),
            "mean_hand_shoulder_horizontal_m": float(dist.mean()),
            "final_distance_to_goal_m": float(np.linalg.norm(self.frames[-1].hand - t.goal)),
            "energy_J": float(self.frames[-1].energy),
            "series": {
                "t_s": self.times.tolist(), "hand_m": self.hand_path.tolist(),
                "hand_shoulder_horizontal_m": dist.tolist(),
                "comfort": [1.0 - f.discomfort for f in self.frames],
                "discomfort": [f.discomfort for f in self.frames], "limit": [f.limit for f in self.frames],
                "strategy": [f.strategy for f in self.frames], "chain": [f.chain for f in self.frames],
                "work_J": [f.work for f in self.frames], "energy_J": [f.energy for f in self.frames],
                "ratios": {k: v.tolist() for k, v in self.joint_ratios().items()}},
        }


def arm_variables(vmap: VariableMap, hand: str) -> list[int]:
    """Indices in ``vmap`` of the hand-shoulder chain: shoulder complex (elevation, plane, twist), elbow."""
    names = [f"{hand}_shoulder_complex.elevation", f"{hand}_shoulder_complex.abduction",
             f"{hand}_shoulder_complex.twist", f"{hand}_elbow[0]"]
    return [vmap.names.index(n) for n in names]


def waist_variables(vmap: VariableMap) -> list[int]:
    """Indices in ``vmap`` of the added joint (:data:`WAIST_ANGLES` of the spine group)."""
    return [vmap.names.index(f"spine.{a}") for a in WAIST_ANGLES]


#: the default lift (figure frame: x the figure's left, y up, z forward; metres from the shoulder
#: joint of the lifting hand): from in front of the chest to above the head, in front of the face
DEFAULT_START = np.array([0.0, -0.25, 0.30])
DEFAULT_GOAL = np.array([0.0, 0.45, 0.30])


def shoulder_position(figure: Figure, hand: str = "right") -> np.ndarray:
    """World position (m) of the ``hand`` side's shoulder joint centre in the figure's posture."""
    kin = figure.kinematics()
    fk = kin.forward(figure.q, figure.location)
    j = kin.joint_names.index(f"{hand}_shoulder")
    return (fk.segments[kin.joint_from_seg[j]] @ kin.L_from[j])[:3, 3].copy()


def figure_offset(figure: Figure, offset: np.ndarray, hand: str = "right") -> np.ndarray:
    """World point (m) at ``offset`` (figure frame, m; :data:`DEFAULT_START`) from the shoulder."""
    heading = figure.location[:3, :3]
    return shoulder_position(figure, hand) + heading @ np.asarray(offset, dtype=float)


def overhead_task(figure: Figure, load_kg: float, hand: str = "right", **options: Any) -> LiftTask:
    """The book's example task (§5.3.6): put ``load_kg`` above the head, from in front of the chest
    (:data:`DEFAULT_START`, :data:`DEFAULT_GOAL`); ``options`` are further :class:`LiftTask` fields."""
    return LiftTask(load_kg, figure_offset(figure, DEFAULT_GOAL, hand), figure_offset(figure, DEFAULT_START, hand),
                    hand=hand, **options)


#: the start posture's grip may miss ``task.start`` by this much (m)
START_TOLERANCE = 0.01


def place_start(figure: Figure, task: LiftTask) -> None:
    """Pose ``figure``'s arm by IK so the grip is at ``task.start`` (wrist and forearm held);
    ValueError when the arm cannot put it there."""
    if task.start is None:
        return
    h = figure_parts(figure).hands[task.hand]
    problem = ik.Problem(figure)
    problem.add(ik.Position(f"{h.segment}.{h.site}", task.start, chain=h.start_joint))
    problem.lock(f"{task.hand}_wrist", f"{task.hand}_forearm")
    ik.solve(problem, max_iterations=200, tol_position=1e-4)
    miss = float(np.linalg.norm(figure.site_world(h.segment, h.site)[:3, 3] - task.start))
    if miss > START_TOLERANCE:
        raise ValueError(f"the {task.hand} hand cannot hold the load at the start {task.start.round(3).tolist()} m "
                         f"(out of the arm's reach by {miss * 100:.1f} cm)")


class _Lifter:
    """The loop of :func:`strength_guided_lift` on a private copy of the figure."""

    def __init__(self, figure: Figure, task: LiftTask) -> None:
        self.task = task
        self.fig = figure
        h = figure_parts(figure).hands[task.hand]
        self.spine = list(figure.groups["spine"].joints)
        vm = VariableMap(figure)
        self.active = np.array(arm_variables(vm, task.hand), dtype=int)
        self.waist = np.array(waist_variables(vm), dtype=int)
        self.monitor = LiftingMonitor(figure, h.segment, h.site, task.load_kg,
                                      [f"{task.hand}_shoulder", f"{task.hand}_elbow"] + self.spine,
                                      [int(v) for v in np.concatenate([self.active, self.waist])])
        self.vmap = vm = self.monitor.vmap
        self.shoulder_joint = f"{task.hand}_shoulder"
        names = self.monitor.monitored_names
        self.groups = {"shoulder": [k for k, n in enumerate(names) if n.startswith(f"{task.hand}_shoulder[")],
                       "elbow": [k for k, n in enumerate(names) if n.startswith(f"{task.hand}_elbow[")],
                       "waist": [k for k, n in enumerate(names) if n.split("[")[0] in self.spine]}
        dq = vm.dq_dx(vm.x())
        mon = self.monitor.monitored
        self._drives = {int(v): np.flatnonzero(np.abs(dq[mon, v]) > 1e-12)
                        for v in np.concatenate([self.active, self.waist])}
        self.lower, self.upper = vm.lower.copy(), vm.upper.copy()
        elevation = vm.names.index(f"{task.hand}_shoulder_complex.elevation")
        self.lower[elevation] = min(max(self.lower[elevation], MIN_ELEVATION), vm.x()[elevation])

    # ----- helpers -------------------------------------------------------------------------------
    def limit(self, t: float) -> float:
        cl = self.task.comfort
        return cl if self.task.fatigue_time is None else cl * float(np.exp(-t / self.task.fatigue_time))

    def weights(self, s: ChainState, limit: float) -> np.ndarray:
        a = availability(s.ratios, limit, AVAILABILITY_FLOOR)
        return np.array([a[self._drives[int(v)]].min() if self._drives[int(v)].size else 1.0 for v in self.active])

    def feasible(self, x: np.ndarray) -> bool:
        if np.any(x < self.lower - 1e-9) or np.any(x > self.upper + 1e-9):
            return False
        active = set(int(v) for v in self.active)
        for g, _, sl in self.vmap.group_slices:
            if active.intersection(range(sl.start, sl.stop)) and not g.is_feasible(x[sl]):
                return False
        return True

    def apply_step(self, s: ChainState, dx: np.ndarray) -> np.ndarray | None:
        """``s.x`` moved by ``dx`` over the active variables: capped at MAX_JOINT_STEP, clamped at the
        boxes, halved until the group limits hold, and where no halving holds them, slid along the
        group limit rows the posture touches (:meth:`slide`); None when no feasible move is left."""
        big = float(np.abs(dx).max())
        if big < 1e-12:
            return None
        if big > MAX_JOINT_STEP:
            dx = dx * (MAX_JOINT_STEP / big)
        for attempt in (dx, self.slide(s.x, dx)):
            x = self.halved(s.x, attempt)
            if x is not None:
                return x
        return None

    def halved(self, x0: np.ndarray, dx: np.ndarray) -> np.ndarray | None:
        """``x0`` moved by ``dx`` (active variables) clamped at the boxes, halved until the group
        limits hold (8 tries); None when no try moves."""
        for _ in range(8):
            x = x0.copy()
            x[self.active] = np.clip(x[self.active] + dx, self.lower[self.active], self.upper[self.active])
            if self.feasible(x) and np.abs(x - x0).max() > 1e-12:
                return x
            dx = dx / 2.0
        return None

    def slide(self, x0: np.ndarray, dx: np.ndarray) -> np.ndarray:
        """``dx`` (active variables) less its components across the group limit rows that ``x0``
        already touches (within :data:`SLIDE_SLACK`): at a shoulder-complex limit the step slides
        along the limit instead of being halved to nothing."""
        full = np.zeros_like(x0)
        full[self.active] = dx
        for g, _, sl in self.vmap.group_slices:
            d, theta = full[sl], x0[sl]
            free = np.isin(np.arange(sl.start, sl.stop), self.active)
            if not d[free].any():
                continue
            a, b = g.rows_at(theta)
            near = b - a @ theta <= SLIDE_SLACK * np.linalg.norm(a, axis=1)
            for _ in range(3):
                tight = near & (a @ d > 1e-12)
                if not tight.any():
                    break
                rows = a[tight][:, free]
                d[free] -= rows.T @ np.linalg.lstsq(rows @ rows.T, rows @ d[free], rcond=None)[0]
            full[sl] = d
        return full[self.active]

    def shoulder_position(self, q: np.ndarray) -> np.ndarray:
        fk = self.monitor.kin.forward(q, self.fig.location)
        kin = self.monitor.kin
        j = kin.joint_names.index(self.shoulder_joint)
        return (fk.segments[kin.joint_from_seg[j]] @ kin.L_from[j])[:3, 3].copy()


    # ----- strategies ----------------------------------------------------------------------------
    def toward_goal(self, s: ChainState, limit: float) -> tuple[np.ndarray, float]:
        """Unit axis to the goal and this step's hand travel."""
        d = self.task.goal - s.hand
        dist = float(np.linalg.norm(d))
        return d / max(dist, 1e-12), min(self.task.step, dist)

    def bounded(self, s: ChainState, solve: Callable[[np.ndarray], np.ndarray]) -> np.ndarray | None:
        """The step ``solve(mask)`` (mask: 1 free, 0 held, per active variable) re-solved with every
        variable that sits at a bound and would be pushed past it held, then applied."""
        mask = np.ones(len(self.active))
        x, lo, hi = s.x[self.active], self.lower[self.active], self.upper[self.active]
        dx = solve(mask)
        for _ in range(3):
            out = ((x <= lo + 1e-9) & (dx < 0.0)) | ((x >= hi - 1e-9) & (dx > 0.0))
            if not out.any():
                break
            mask[out] = 0.0
            dx = solve(mask) * mask
        return self.apply_step(s, dx)

    def available_torque(self, s: ChainState, limit: float) -> np.ndarray | None:
        u, h = self.toward_goal(s, limit)
        w = self.weights(s, limit)

        def solve(mask: np.ndarray) -> np.ndarray:
            headroom = w * mask * (weighted_pinv(s.jacobian, mask) @ u)
            direction = project_to_cone(s.jacobian @ headroom, u, self.beta)
            return weighted_step(s.jacobian, w * mask, h * direction)
        return self.bounded(s, solve)

    def reducing_moment(self, s: ChainState, limit: float, beta: float) -> np.ndarray | None:
        u, h = self.toward_goal(s, limit)
        w = self.weights(s, limit)
        grad = self.monitor.ratio_gradient(s, self.active)

        def solve(mask: np.ndarray) -> np.ndarray:
            wm = w * mask
            direction = least_moment_direction(s.jacobian, wm, grad, u, beta)
            pinv = weighted_pinv(s.jacobian, wm)
            dx = pinv @ (h * direction)
            null = -(np.eye(len(self.active)) - pinv @ s.jacobian) @ (wm * grad)
            nn = float(np.abs(null).max())
            return dx + null * (0.5 * MAX_JOINT_STEP / nn) if nn > 1e-12 else dx
        return self.bounded(s, solve)

    def pull_back(self, s: ChainState) -> np.ndarray | None:
        grad = self.monitor.ratio_gradient(s, self.active)
        return self.bounded(s, lambda mask: -grad * mask)

    # ----- the loop ------------------------------------------------------------------------------
    def run(self) -> LiftResult:
        task = self.task
        self.beta = task.exertion * np.pi / 2.0
        wide = self.beta + 0.5 * (np.pi / 2.0 - self.beta)
        s = self.monitor.state(self.vmap.x(), self.active)
        frames = [self.frame(s, 0.0, AVAILABLE_TORQUE, 0.0, 0.0)]
        log: list[tuple[int, str]] = []
        waist_at = None
        pulling, stuck, best, heading = False, 0, float(np.linalg.norm(task.goal - s.hand)), 0
        pulled = False  # pull back used since the hand last gained on the goal
        reason = f"iteration limit ({task.max_iterations})"
        for it in range(1, task.max_iterations + 1):
            dist = float(np.linalg.norm(task.goal - s.hand))
            if dist <= task.tolerance:
                break
            t = frames[-1].t
            limit = self.limit(t)
            new, used = None, PULL_BACK
            if pulling and s.discomfort <= PB_RELEASE * limit:
                pulling = False
            if not pulling and s.discomfort <= limit:
                if s.discomfort <= RM_ONSET * limit:
                    new, used = self.within(self.available_torque(s, limit), limit), AVAILABLE_TORQUE
                if new is None:
                    new, used = self.within(self.reducing_moment(s, limit, self.beta), limit), REDUCING_MOMENT
                if new is None:  # the Discomfort band: a larger path deviation is allowed
                    new = self.within(self.reducing_moment(s, limit, wide), limit)
            pulling = pulling or new is None
            exhausted = False
            if pulling:
                used = PULL_BACK
                x = self.pull_back(s)
                new = None if x is None else self.monitor.state(x, self.active)
                stuck = 0 if new is not None and s.discomfort - new.discomfort > PB_MIN_GAIN else stuck + 1
                exhausted = stuck >= PB_PATIENCE
            if dist < best - STALL_GAIN:
                best, heading, pulled = dist, 0, False
            pulled = pulled or pulling
            heading += 0 if pulling else 1  # pull back ignores the goal: its steps do not count as a stall
            stalled = heading > STALL_STEPS
            if exhausted or stalled:
                if task.allow_waist and waist_at is None:
                    waist_at = len(frames) - 1
                    self.active = np.concatenate([self.active, self.waist])
                    log.append((waist_at, ADDED_JOINT))
                    pulling, stuck, heading = False, 0, 0
                    s = self.monitor.state(s.x, self.active)
                    continue
                why = ("pull back and reducing moment take turns at the comfort level" if pulled
                       else "beyond the chain's reach?")
                reason = (f"stopped: no strategy keeps the torque ratios within the comfort level "
                          f"(discomfort {s.discomfort:.2f}, limit {limit:.2f})" if exhausted else
                          f"stopped: the hand came no nearer the goal in {STALL_STEPS} steps ({why})")
                break
            if new is None:
                continue
            if not log or log[-1][1] != used:
                log.append((len(frames), used))
            frames.append(self.frame(new, t + self.duration(s, new), used, *self.work(s, new, frames[-1].energy)))
            s = new
        reached = float(np.linalg.norm(task.goal - s.hand)) <= task.tolerance
        return LiftResult(task, frames, reached, "goal reached" if reached else reason, self.monitor.monitored_names,
                          self.groups, log, waist_at, self.fig.name, [int(v) for v in self.waist])

    def within(self, x: np.ndarray | None, limit: float) -> ChainState | None:
        """The state at ``x`` when its discomfort stays within ``limit``, else None."""
        if x is None:
            return None
        state = self.monitor.state(x, self.active)
        return state if state.discomfort <= limit else None

    def work(self, a: ChainState, b: ChainState, energy: float) -> tuple[float, float]:
        dw = float(a.torques @ (b.q - a.q))
        return dw, energy + abs(dw)

    def duration(self, a: ChainState, b: ChainState) -> float:
        """Seconds of the step from ``a`` to ``b`` by the rate model (:data:`W_MAX`)."""
        rate = max(RATE_FLOOR, 1.0 - min(b.discomfort, 1.0))
        return float(np.abs(b.q - a.q).max()) / (W_MAX * rate)

    def frame(self, s: ChainState, t: float, strategy: str, work: float, energy: float) -> LiftFrame:
        chain = "hand-waist" if self.waist[0] in self.active else "hand-shoulder"
        return LiftFrame(t, s.x.copy(), s.hand.copy(), self.shoulder_position(s.q), s.q.copy(), s.ratios.copy(),
                         self.limit(t), strategy, chain, work, energy)


def strength_guided_lift(figure: Figure, task: LiftTask) -> LiftResult:
    """Lift ``task.load_kg`` to ``task.goal`` by strength-guided motion (module docstring).

    ``figure`` is a standard human (:func:`jackpy.body.human.make_human`), rooted at its pelvis,
    standing in its current posture; it is not changed (the lift runs on a copy)."""
    fig = copy.deepcopy(figure)
    place_start(fig, task)
    return _Lifter(fig, task).run()
