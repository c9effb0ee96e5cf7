"""The scene document: the one headless owner of the user's work.

A :class:`Document` holds the environment (figures, objects), a behavior loop per standard human,
the user's goals (:class:`~jackpy.document.goals.GoalEntry`, each owning its IK goal's targets),
the settings, the undo/redo stack of document commands, the file path and a dirty flag, and the
motion timeline with its clock. It imports nothing from :mod:`jackpy.ui`: scripts, tests and the
window drive it alike.

One step (:meth:`Document.step`): timeline → goals → behaviors → IK → FK → live analyses. The
window's :class:`~jackpy.ui.app.App` adds input before it (the operator moves goals through
:meth:`Document.move_goal`) and the draw after it.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.behaviors import BehaviorLoop, FrameReport, manipulation
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.document.analyses import LiveAnalyses, figure_of_interest
from jackpy.document.effectors import FOOT_ROLES, HAND_ROLES, find_effectors, is_object
from jackpy.document.goals import EYES, FRAME_TYPES, GoalEntry, eyes_goal, new_goal
from jackpy.document.settings import Settings
from jackpy.document.undo import UndoStack
from jackpy.errors import JackpyError
from jackpy.ik.problem import Problem
from jackpy.ik.result import ITERATION_LIMIT, TIME_LIMIT
from jackpy.ik.solver import solve as ik_solve
from jackpy.peabody import Environment, Figure
from jackpy.peabody.transforms import rigid_inverse

if TYPE_CHECKING:
    from jackpy.behaviors.loop import UserGoal

SETTLED_DQ = 1e-6
"""A behavior frame that moves no DOF more than this (rad or m) ends the solve."""
CUT_FRAME_SHARE = 0.25
"""What a behavior frame cut short by the time box counts towards ``settings.settle_frames``."""
LOOK_DISTANCE = 1.0
"""A head drag fixates the point this far (m) ahead of the dragged view frame."""
ITERATIONS_PER_CALL = 15
"""Solver iterations between time-box checks."""


@dataclass
class DocumentState:
    """What undo puts back: every figure's displacements, placement and root, the goals, and the
    behaviors' switches and parameters; whole figure copies only for structural commands
    (rescale, import, new scene)."""

    postures: dict[str, tuple[np.ndarray, np.ndarray, tuple[str, str] | None]]
    goals: list[GoalEntry]
    figures: dict[str, Figure] | None = None
    behaviors: dict[str, dict[str, tuple[bool, object]]] = field(default_factory=dict)
    timeline: dict | None = None
    """The timeline's contents (:meth:`Timeline.to_dict`), so timeline edits undo too."""
    extras: dict[str, Any] = field(default_factory=dict)
    """A copy of :attr:`Document.extras` (the step editor's walk plans)."""


@dataclass
class SolveLimits:
    """How much one :meth:`Document.step` may solve (the frame loop's quality, see
    :mod:`jackpy.ui.frame_budget`): the time box ``box_s`` (s; None: ``settings.ik_time_budget_s``),
    and caps on every behavior pass's solver iterations and on the COM loop's passes (None: the
    loops' own settings)."""

    box_s: float | None = None
    iterations: int | None = None
    passes: int | None = None


@dataclass
class StepStats:
    """What one :meth:`Document.step` did: solve time (s), iterations or behavior frames, and the
    time box it had (s) and whether the box cut the solve short."""

    solve_s: float = 0.0
    iterations: int = 0
    solved: bool = False
    box_s: float = 0.0
    timed_out: bool = False
    behaviors_s: float = 0.0
    """Of ``solve_s``, the behaviors' own work (updates and finishes, outside the IK solves)."""


def solve_goals(env: Environment, goals: list[GoalEntry], budget_s: float,
                deadline: float | None = None) -> tuple[int, bool]:
    """Solve each figure's enabled goals (priority = level, 0 first) from its current posture by
    plain IK, in slices of :data:`ITERATIONS_PER_CALL` iterations until the goals are achieved, the
    solver stops improving, or ``budget_s`` seconds have passed (or the ``time.perf_counter()``
    ``deadline``, whichever is first: the solver starts no evaluation after it). Returns
    (iterations, settled)."""
    start = time.perf_counter()
    end = start + budget_s if deadline is None else min(deadline, start + budget_s)
    iterations, settled = 0, True
    for fig in env.figures.values():
        mine = [g for g in goals if g.figure == fig.name and g.enabled and g.role != EYES]
        if not mine or is_object(fig):
            continue
        problem = Problem(fig)
        for g in mine:
            problem.add(g.goal, level=max(0, g.priority))
        while True:
            result = ik_solve(problem, max_iterations=ITERATIONS_PER_CALL,
                              time_budget_s=max(0.0, end - time.perf_counter()))
            iterations += result.iterations
            if result.status == TIME_LIMIT or (result.status == ITERATION_LIMIT and time.perf_counter() >= end):
                settled = False
                break
            if result.status != ITERATION_LIMIT:
                break
    return iterations, settled


class Document:
    """The user's work, headless (module docstring). ``env`` is shown as it is; unless ``goals``
    are given, the feet of every articulated figure are planted where they stand."""

    def __init__(self, env: Environment | None = None, settings: Settings | None = None,
                 goals: list[GoalEntry] | None = None) -> None:
        self.settings = settings or Settings()
        self.undo_stack: UndoStack[DocumentState] = UndoStack()
        self.log: list[str] = []
        self.on_log: Callable[[str], None] | None = None
        self.path: Path | None = None
        """The file the document was opened from or last saved to."""
        self.scene_dir: Path | None = None
        """Directory the scene's included Peabody files are relative to."""
        self.dirty = False
        self.needs_solve = False
        self.analyses: LiveAnalyses = LiveAnalyses()
        self.loops: dict[str, BehaviorLoop] = {}
        """The behavior loop of each standard human in the scene, by figure name."""
        self.last_report: FrameReport | None = None
        self.timeline: Any = None
        """A :class:`jackpy.motion.timeline.Timeline` (or None): applied at :attr:`time` each step."""
        self.time = 0.0
        """The timeline's clock (s)."""
        self.playing = False
        self.view_state: dict[str, Any] = {}
        """What a window keeps with the document in its file (camera), opaque here."""
        self.extras: dict[str, Any] = {}
        """Plain JSON-ready data that tools keep with the document, undone and saved with it
        (``"walk_plans"``: the step editor's footsteps by figure), opaque here."""
        self.changed = False
        """Set by every change of goals or posture since the last :meth:`take_changed` (a drag's
        "did anything happen")."""
        self._handed: dict[str, dict[str, tuple[BehaviorLoop, GoalEntry, tuple, UserGoal | None]]] = {}
        self._settle = 0
        self._timed_out = False
        self._behaviors_s = 0.0
        self._frame_s = 0.0  # the last behavior frame's cost: a frame starts only if it fits the box
        self._edit_state: DocumentState | None = None
        self.set_environment(env if env is not None else Environment(), goals)

    # ------------------------------------------------------------------ files
    @classmethod
    def open(cls, path: str | Path) -> Document:
        """The document saved at ``path`` (a ``.env`` session; see :mod:`jackpy.document.session`)."""
        from jackpy.document import session

        doc = cls()
        session.open_into(doc, Path(path))
        return doc

    def save(self, path: str | Path | None = None) -> Path:
        """Save to ``path`` (default: :attr:`path`) atomically; the document remembers the path and
        is clean afterwards. Returns the path written."""
        from jackpy.document import session

        target = Path(path) if path is not None else self.path
        if target is None:
            raise ValueError("the document has no file yet: give a path")
        written = session.save(self, target)
        # scene_dir stays: the names of included and surface files in memory are relative to it
        self.path, self.dirty = written, False
        self.info(f"saved {written}")
        return written

    @property
    def title(self) -> str:
        """``name`` (``*name`` when modified) for a window title."""
        name = self.path.name if self.path is not None else "untitled"
        return ("*" if self.dirty else "") + name

    # ------------------------------------------------------------------ scene
    def set_environment(self, env: Environment, goals: list[GoalEntry] | None = None) -> None:
        """Show ``env``; plant the feet of every articulated figure unless ``goals`` are given."""
        self.env = env
        self.undo_stack.clear()
        if goals is None:
            goals = []
            for fig in env.figures.values():
                eff = find_effectors(fig)
                for role in FOOT_ROLES:
                    if role in eff:
                        goals.append(new_goal(fig, eff[role], "position+orientation"))
        self.goals = goals
        self.needs_solve = False
        self._handed = {}
        self.make_loops()

    def figure_of_interest(self) -> Figure | None:
        """The first articulated figure (the human)."""
        return figure_of_interest(self.env)

    def goal(self, key: str) -> GoalEntry | None:
        return next((g for g in self.goals if g.key == key), None)

    def ensure_goal(self, fig: Figure, site: str, kind: str = "position") -> GoalEntry:
        """The goal on ``fig``'s ``site``, created at the site's current frame if missing."""
        g = self.goal(f"{fig.name}:{site}")
        if g is None:
            g = new_goal(fig, site, kind)
            self.goals.append(g)
        return g

    def ensure_eyes_goal(self, fig: Figure) -> GoalEntry:
        """The eyes target of human ``fig`` (key ``FIGURE:eyes``), made at the gaze's current target
        or :data:`LOOK_DISTANCE` ahead of the view site."""
        g = self.goal(f"{fig.name}:{EYES}")
        if g is not None:
            return g
        view = find_effectors(fig).get("head", "head.view")
        loop = self.loops.get(fig.name)
        point = loop.state.eyes_target if loop is not None else None
        if point is None:
            w = fig.site_world(*view.split(".", 1))
            point = w[:3, 3] + LOOK_DISTANCE * w[:3, 2]
        g = eyes_goal(fig, view, point)
        self.goals.append(g)
        return g

    def add_goal(self, goal: GoalEntry | Figure, site: str | None = None, kind: str | None = None,
                 **params: Any) -> GoalEntry:
        """Add a goal: a ready :class:`GoalEntry`, or (``figure, site, kind``) a new goal of that
        registered kind holding at the site's current frame. It replaces a goal with the same key."""
        entry = goal if isinstance(goal, GoalEntry) else new_goal(goal, site, kind, **params)  # type: ignore[arg-type]
        old = self.goal(entry.key)
        if old is not None:
            self.goals.remove(old)
        self.goals.append(entry)
        self.goals_changed()
        return entry

    def remove_goal(self, key: str) -> None:
        """Delete a goal (one undo step)."""
        g = self.goal(key)
        if g is None:
            return
        self.command(f"remove {g.kind} goal {key}", lambda: self.goals.remove(g))

    def move_goal(self, goal: GoalEntry | str, manip: np.ndarray) -> None:
        """The operator moved ``goal``'s manipulation frame to ``manip``: the targets follow, and a
        human's behaviors hear of it through Jack's manipulation commands."""
        g = self.goal(goal) if isinstance(goal, str) else goal
        if g is None:
            raise KeyError(f"no goal {goal!r}")
        before = g.target
        g.move(manip)
        self.drive_behaviors(g, before)
        self.goals_changed()

    def reseat_goal(self, g: GoalEntry) -> None:
        """Ratchet (end of an operator primitive): a frame goal's orientation is re-seated on the
        end effector's actual orientation."""
        if not isinstance(g.goal, FRAME_TYPES) or g.role == EYES:
            return
        actual = self.env.figure(g.figure).site_world(*g.site.split(".", 1))
        target = g.target
        target[:3, :3] = actual[:3, :3]
        g.target = target

    def move_figure(self, fig: Figure, location: np.ndarray) -> None:
        """Place a whole figure or object at ``location``; its goals come along."""
        delta = np.array(location, float) @ rigid_inverse(fig.location)
        fig.location = np.array(location, float)
        for g in self.goals:
            if g.figure == fig.name:
                g.move(delta @ g.manip)
        self.sync_behaviors(fig.name)
        self.goals_changed()

    def set_dof(self, fig: Figure, joint: str, k: int, value: float) -> float:
        """Set DOF ``k`` of ``joint`` through the figure (clamped to its limits); goals keep their
        targets and the figure is not re-solved. Returns the value set."""
        v = fig.joint(joint).set_dof(k, value)
        self.posture_changed(fig)
        return v

    # ------------------------------------------------------------------ notifications
    def goals_changed(self) -> None:
        self._settle = 0
        self.needs_solve = True
        self.dirty = True
        self.changed = True

    def posture_changed(self, figure: Figure) -> None:
        """A DOF was set directly."""
        self.dirty = True
        self.changed = True

    def take_changed(self) -> bool:
        """Whether anything changed since the last call (and reset)."""
        out, self.changed = self.changed, False
        return out

    def info(self, text: str) -> None:
        """Append to the log."""
        self.log.append(text)
        del self.log[:-500]
        if self.on_log is not None:
            self.on_log(text)

    # ------------------------------------------------------------------ undo
    def capture(self, structural: bool = False) -> DocumentState:
        """The current undoable state (whole figures too when ``structural``)."""
        postures = {n: (f.q.copy(), f.location.copy(), f.root) for n, f in self.env.figures.items()}
        figures = {n: copy.deepcopy(f) for n, f in self.env.figures.items()} if structural else None
        behaviors = {n: {b.name: (bool(b.enabled), copy.deepcopy(b.params)) for b in loop.behaviors}
                     for n, loop in self.loops.items()}
        timeline = self.timeline.to_dict() if self.timeline is not None else None
        return DocumentState(postures, copy.deepcopy(self.goals), figures, behaviors, timeline,
                             copy.deepcopy(self.extras))

    def restore(self, snap: DocumentState) -> None:
        """Put back a captured state exactly (no solve follows)."""
        if snap.figures is not None:  # the scene's figures exactly (an import undone drops its object)
            self.env.figures.clear()
            for name, fig in snap.figures.items():
                self.env.figures[name] = copy.deepcopy(fig)
        for name, (q, loc, root) in snap.postures.items():
            fig = self.env.figures.get(name)
            if fig is not None:
                if fig.root != root:
                    fig.root = root
                    fig.topology_changed()
                fig.q = q.copy()
                fig.location = loc.copy()
        self.goals = copy.deepcopy(snap.goals)
        self.extras = copy.deepcopy(snap.extras)
        if snap.timeline is not None and self.timeline is not None:
            self.timeline.load_dict(snap.timeline)  # in place: views of the timeline keep it
        self.needs_solve = False
        self.dirty = True
        if snap.figures is not None:
            self.make_loops()
        for name, saved in snap.behaviors.items():
            loop = self.loops.get(name)
            for b in loop.behaviors if loop is not None else ():
                if b.name in saved:
                    b.enabled = saved[b.name][0]
                    b.params = copy.deepcopy(saved[b.name][1])
        if snap.figures is None:
            for name in list(self.loops):
                self.sync_behaviors(name)

    def command(self, label: str, action: Callable[[], object], structural: bool = False) -> None:
        """Run ``action`` as one undoable command."""
        before = self.capture(structural)
        action()
        self.undo_stack.push(label, before)
        self.dirty = True
        self.info(label)

    def push(self, label: str, before: DocumentState) -> None:
        """Record a command already done (a drag) whose state before was ``before``."""
        self.undo_stack.push(label, before)
        self.dirty = True

    def begin_edit(self) -> None:
        """A continuous edit (a slider drag) starts: remember the state for one undo step."""
        self._edit_state = self.capture()

    def end_edit(self, label: str) -> None:
        """The continuous edit ended: push it as one undo step."""
        if self._edit_state is not None:
            self.undo_stack.push(label, self._edit_state)
            self._edit_state = None
            self.info(label)

    def undo(self) -> bool:
        top = self.undo_stack.peek_undo()
        snap = self.undo_stack.undo(self.capture(top is not None and top.figures is not None))
        if snap is None:
            return False
        self.restore(snap)
        self.info("undo")
        return True

    def redo(self) -> bool:
        top = self.undo_stack.peek_redo()
        snap = self.undo_stack.redo(self.capture(top is not None and top.figures is not None))
        if snap is None:
            return False
        self.restore(snap)
        self.info("redo")
        return True

    # ------------------------------------------------------------------ the step
    def step(self, dt: float = 0.0, limits: SolveLimits | None = None) -> StepStats:
        """One step: the timeline (when set and playing, ``time`` advances by ``dt`` s), then, when
        goals changed, goals → behaviors → IK → FK within the time box, then the live analyses.

        Without ``limits`` (scripts, tests) the settings' box counts whole behavior frames: each
        runs to its end, another starts while the box lasts (so the result does not depend on the
        machine's speed within a frame). ``limits`` (the frame loop's) make the box strict: every
        solve ends by its deadline (:meth:`solve`), and cap the loops' iterations and passes."""
        stats = StepStats()
        strict = limits is not None
        limits = limits or SolveLimits()
        stats.box_s = self.settings.ik_time_budget_s if limits.box_s is None else max(0.0, limits.box_s)
        if self.timeline is not None and self.playing:
            self.time += float(dt)
            self.timeline.apply(self.time, self.loops, self.env)
            self.needs_solve = True
            self._settle = 0
        if self.needs_solve:
            t0 = time.perf_counter()
            saved = {n: (lp.max_iterations, lp.max_passes) for n, lp in self.loops.items()}
            try:
                for lp in self.loops.values():
                    if limits.iterations is not None:
                        lp.max_iterations = max(1, min(lp.max_iterations, int(limits.iterations)))
                    if limits.passes is not None:
                        lp.max_passes = max(1, min(lp.max_passes, int(limits.passes)))
                stats.iterations, settled = self.solve(stats.box_s, strict)
            finally:
                for n, (it, ps) in saved.items():
                    self.loops[n].max_iterations, self.loops[n].max_passes = it, ps
            stats.solve_s = time.perf_counter() - t0
            stats.solved = True
            stats.timed_out = self._timed_out
            stats.behaviors_s = self._behaviors_s
            self.needs_solve = not settled
        self.analyses.refresh(self.env)
        return stats

    def solve(self, box_s: float | None = None, strict: bool = False) -> tuple[int, bool]:
        """Solve for every figure with enabled goals, within the time box ``box_s`` (s; default
        ``settings.ik_time_budget_s``).

        Humans with a behavior loop (when ``settings.behaviors``) run :meth:`BehaviorLoop.step`
        frames while the box lasts; every other figure is solved by plain IK on its goals in the
        rest of the box. ``strict``: each behavior frame's solves end by the box's deadline, and
        another frame starts only while the last one's cost still fits in what is left. Returns
        (iterations or behavior frames, settled): settled when the goals are met or the solve
        stalls.
        """
        start = time.perf_counter()
        budget = self.settings.ik_time_budget_s if box_s is None else box_s
        deadline = start + budget
        count, settled = 0, True
        self._timed_out, self._behaviors_s = False, 0.0
        driven = self.behavior_figures()
        for name in driven:
            loop, fig = self.loops[name], self.env.figures[name]
            self.hand_user_goals(name)
            while True:
                q0 = fig.q.copy()
                f0 = time.perf_counter()
                self.last_report = loop.step(deadline=deadline if strict else None)
                self._frame_s = time.perf_counter() - f0
                self._timed_out |= self.last_report.timed_out
                self._behaviors_s += self._frame_s - self.last_report.solve_s
                count += 1
                # a frame the time box cut did a fraction of a frame's work: the posture is still on
                # its way (the lean waits for the body), so it counts CUT_FRAME_SHARE of a frame
                self._settle += CUT_FRAME_SHARE if self.last_report.timed_out else 1.0
                moved = float(np.max(np.abs(fig.q - q0), initial=0.0))
                if self._settle >= self.settings.settle_frames:
                    break
                if self.last_report.timed_out:  # cut short: not settled, whatever it moved
                    settled = False
                    break
                if moved < SETTLED_DQ:
                    break
                if time.perf_counter() + (self._frame_s if strict else 0.0) >= deadline:
                    settled = False
                    break
        rest = [g for g in self.goals if g.figure not in driven]
        if rest:
            it, ok = solve_goals(self.env, rest, max(0.0, deadline - time.perf_counter()),
                                 deadline if strict else None)
            count, settled = count + it, settled and ok
            self._timed_out |= not ok
        return count, settled

    # ------------------------------------------------------------------ behaviors
    def make_loops(self) -> None:
        """A behavior loop for every standard human in the scene (feet planted where they stand)."""
        self.loops = {}
        self._handed = {}
        for fig in self.env.figures.values():
            if is_object(fig):
                continue
            try:
                anatomy = human_anatomy(fig)
            except (JackpyError, KeyError, ValueError, IndexError):  # not the standard human: plain IK only
                continue
            q, loc, root = fig.q.copy(), fig.location.copy(), fig.root
            try:
                self.loops[fig.name] = BehaviorLoop(fig, anatomy)
            except Exception as exc:
                fig.root, fig.q, fig.location = root, q, loc
                fig.topology_changed()
                self.info(f"{fig.name}: no behaviors ({exc})")
                continue
            self.sync_behaviors(fig.name)

    def behavior_figures(self) -> set[str]:
        """Names of the figures whose goals the behaviors solve now."""
        return set(self.loops) if self.settings.behaviors else set()

    def is_user_goal(self, goal: GoalEntry) -> bool:
        """Whether the behaviors solve ``goal`` as a user goal (:meth:`BehaviorLoop.add_user_goal`):
        every goal but the effector goals the manipulation commands drive (hands, feet, pelvis, head
        as frames) and the eyes target."""
        if goal.role == EYES:
            return False
        return not isinstance(goal.goal, FRAME_TYPES) or self.role_of(goal) is None

    def hand_user_goals(self, name: str) -> None:
        """Give figure ``name``'s loop its user goals: the entries' own goal objects (the loop reads
        their targets, nothing is copied). New entries are added, removed ones removed (so is one
        whose goal object or chain changed); switches and levels are passed on."""
        loop = self.loops.get(name)
        if loop is None:
            return
        mine = {g.key: g for g in self.goals if g.figure == name and self.is_user_goal(g)}
        have = self._handed.setdefault(name, {})
        for key in list(have):
            lp, entry, sig, ug = have[key]
            e = mine.get(key)
            if lp is not loop or e is not entry or sig != _signature(e):
                if lp is loop and ug is not None:
                    loop.remove_user_goal(ug)
                del have[key]
        for key, e in mine.items():
            if key not in have:
                try:
                    ug = loop.add_user_goal(e.goal, level=max(0, e.priority), enabled=e.enabled, key=key)
                except (JackpyError, KeyError, ValueError) as exc:
                    self.info(f"error: goal {key}: {exc}")
                    ug = None
                have[key] = (loop, e, _signature(e), ug)
                continue
            ug = have[key][3]
            if ug is not None:
                loop.set_user_goal(ug, enabled=e.enabled, level=max(0, e.priority))

    def user_goal_part(self, key: str) -> str | None:
        """The pass (``body``, ``head``, ``left``, ``right``) that solves user goal ``key`` while the
        behaviors are on; None when the behaviors do not solve it."""
        for have in self._handed.values():
            entry = have.get(key)
            if entry is not None and entry[3] is not None:
                return entry[3].part
        return None

    def role_of(self, goal: GoalEntry) -> str | None:
        """The end-effector role (``right_hand`` ...) of a goal's site, if it is one."""
        fig = self.env.figures.get(goal.figure)
        if fig is None:
            return None
        return next((r for r, s in find_effectors(fig).items() if s == goal.site), None)

    def sync_behaviors(self, name: str) -> None:
        """Restart figure ``name``'s behavior state from its posture and its hand and eyes goals
        (after undo, a figure move, a rescale, opening a scene)."""
        loop = self.loops.get(name)
        if loop is None:
            return
        loop.reset_state()
        for side in loop.state.feet:
            manipulation.set_foot_behavior(loop, side, mode="hold" if self.settings.feet_hold else "pivot")
        manipulation.move_eyes(loop, None)  # the eyes target lives in the goals (undo may drop it)
        for g in self.goals:
            if g.figure == name and g.role == EYES and g.enabled:
                manipulation.move_eyes(loop, g.target[:3, 3])
                continue
            role = self.role_of(g) if g.figure == name and isinstance(g.goal, FRAME_TYPES) else None
            if role in HAND_ROLES and g.enabled:
                side = role.split("_")[0]
                t = g.target
                manipulation.move_hand(loop, side, position=t[:3, 3], rotation=t[:3, :3],
                                       lean=self.settings.hand_lean)
        self._settle = 0

    def drive_behaviors(self, goal: GoalEntry, before: np.ndarray) -> None:
        """A dragged effector goal moved from ``before`` to ``goal.target``: tell the behaviors
        through Jack's manipulation commands (move_hand, move_foot, move_pelvis, move_head/eyes)."""
        loop = self.loops.get(goal.figure) if goal.figure in self.behavior_figures() else None
        if loop is not None and goal.role == EYES:
            manipulation.move_eyes(loop, goal.target[:3, 3])
            self._settle = 0
            return
        role = self.role_of(goal) if loop is not None and isinstance(goal.goal, FRAME_TYPES) else None
        if role is None:
            return
        t = goal.target
        rotating = not np.allclose(before[:3, :3], t[:3, :3], atol=1e-12)
        side = role.split("_")[0]
        if role in HAND_ROLES:
            manipulation.move_hand(loop, side, position=t[:3, 3], rotation=t[:3, :3] if rotating else None,
                                   lean=self.settings.hand_lean)
        elif role in FOOT_ROLES:
            manipulation.move_foot(loop, side, position=t[:3, 3], rotation=t[:3, :3] if rotating else None)
        elif role == "pelvis":
            manipulation.move_pelvis(loop, rotation=t[:3, :3] if rotating else None,
                                     translation=None if rotating else t[:3, 3] - before[:3, 3])
        elif role == "head":
            point = t[:3, 3] + LOOK_DISTANCE * t[:3, 2]
            if self.settings.head_drag == "eyes":
                manipulation.move_eyes(loop, point)
            else:
                manipulation.move_head(loop, point)
        self._settle = 0

    def end_behavior_drag(self) -> None:
        """Mouse release: :func:`~jackpy.behaviors.manipulation.end_drag` on every loop."""
        for loop in self.loops.values():
            manipulation.end_drag(loop)
        self._settle = 0

    def set_behaviors_enabled(self, on: bool) -> None:
        """Switch between the behaviors and plain IK for the humans' goals."""
        if on == self.settings.behaviors:
            return
        self.settings.behaviors = on
        for name in self.loops:
            self.sync_behaviors(name)
        self.goals_changed()
        self.info("behaviors on" if on else "behaviors off: plain IK")

    # ------------------------------------------------------------------ structural commands
    def rescale_figure(self, name: str, sex: str, percentile: float, population: str = "ansur2") -> None:
        """Give human ``name`` another body in place (:func:`~jackpy.body.human.rescale_in_place`),
        keeping its posture, then re-solve its goals. One undo step; errors go to the log and leave
        the figure as it was."""
        from jackpy.body.human import rescale_in_place

        fig = self.env.figure(name)
        before = self.capture(structural=True)
        try:
            rescale_in_place(fig, sex, percentile, population)
        except (JackpyError, ValueError, KeyError) as exc:
            self.restore(before)
            self.info(f"error: rescale {name}: {exc}")
            return
        self.undo_stack.push(f"rescale {name} to {sex} P{percentile:g}", before)
        eff = find_effectors(fig)
        for g in self.goals:  # planted feet stay planted where the new feet stand
            if g.figure == name and g.site in (eff.get("left_foot"), eff.get("right_foot")):
                w = fig.site_world(*g.site.split(".", 1))
                g.manip = np.eye(4)
                g.manip[:3, 3] = w[:3, 3]
                g.offset = w[:3, :3].copy()
                g.goal.set_frame(g.target)
        self.make_loops()  # new sites and footprints; feet re-planted where they now stand
        self.goals_changed()
        self.info(f"rescaled {name} to {sex} P{percentile:g} ({population})")

    def import_cad(self, path: str | Path, units: str = "m", up: str = "y") -> Figure | None:
        """Add a CAD file (one undo step); an error goes to the log and leaves the scene untouched."""
        from jackpy.scene.cad import add_cad

        before = self.capture(structural=True)
        try:
            obj = add_cad(self.env, path, units, up)
        except (JackpyError, OSError, ValueError) as exc:
            self.info(f"error: import {Path(path).name}: {exc}")
            return None
        self.undo_stack.push(f"import {obj.name}", before)
        self.dirty = True
        self.info(f"imported {Path(path).name}: {obj.triangle_count} triangles")
        return obj


def _signature(entry: GoalEntry) -> tuple:
    """What a user goal's place in the loop depends on: its goal object, site and chain."""
    chain = entry.goal.chain
    return id(entry.goal), entry.site, chain if chain is None or isinstance(chain, str) else tuple(chain)
