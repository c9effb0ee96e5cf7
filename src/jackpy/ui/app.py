"""The workbench application: state, input handlers and the frame step, apart from any window.

One frame (DESIGN.md): input → goals → behaviors → IK → FK → draw. The input handlers
(:meth:`App.on_cursor_pos`, :meth:`App.on_mouse_button`, :meth:`App.on_scroll`, :meth:`App.on_key`)
take the same arguments glfw passes to its callbacks (buttons, actions, modifier bits and key codes
as glfw numbers) and only change goals, the camera, or, for CONTROL-rotation of a joint, one joint
DOF within its limits. :meth:`App.step` then solves IK (time-boxed) when goals changed, and draws.
The window (:mod:`jackpy.ui.window`) calls exactly these; tests call them with synthetic events.

Mouse (default mapping, docs/workbench.md): a press on a pickable thing (hand, foot, head, pelvis,
a goal marker, any other segment of a figure, an object) starts the Jack operator on it; a press
on empty space navigates: left orbits, right pans, middle zooms, the wheel zooms.
"""

from __future__ import annotations

import copy
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors import BehaviorLoop, FrameReport, manipulation
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.errors import JackpyError
from jackpy.ik.goals import Aim, Goal, HalfSpace, Orientation, Plane, Position, PositionOrientation
from jackpy.ik.problem import Problem
from jackpy.ik.result import ITERATION_LIMIT
from jackpy.ik.solver import solve as ik_solve
from jackpy.peabody import Environment, Figure
from jackpy.peabody.transforms import rigid_inverse
from jackpy.ui.analysis_overlays import AnalysisState
from jackpy.ui.camera import NavAction, OrbitCamera, navigation_action
from jackpy.ui.manipulator import Manipulator
from jackpy.ui.scene_view import GoalPick, Overlay, SceneView, SegmentPick, is_object
from jackpy.ui.undo import UndoStack

if TYPE_CHECKING:
    from jackpy.ui.render import Renderer

# glfw's numbers, so that this module needs no glfw import (and no display).
MOUSE_LEFT, MOUSE_RIGHT, MOUSE_MIDDLE = 0, 1, 2
RELEASE, PRESS, REPEAT = 0, 1, 2
MOD_SHIFT, MOD_CONTROL, MOD_ALT = 1, 2, 4
KEY_ESCAPE, KEY_DELETE = 256, 261
KEY_LEFT_SHIFT, KEY_LEFT_CONTROL, KEY_RIGHT_SHIFT, KEY_RIGHT_CONTROL = 340, 341, 344, 345
_BUTTON_NAMES = {MOUSE_LEFT: "left", MOUSE_MIDDLE: "middle", MOUSE_RIGHT: "right"}

HAND_ROLES = ("right_hand", "left_hand")
FOOT_ROLES = ("right_foot", "left_foot")

EFFECTOR_SITES: dict[str, tuple[str, ...]] = {
    # role: candidate "segment.site" names, the standard human's (docs/body.md) first, then the
    # synthetic tree's (jackpy.peabody.synthetic.human_like_tree)
    "right_hand": ("right_palm.palm_centre", "palm_right.tip"),
    "left_hand": ("left_palm.palm_centre", "palm_left.tip"),
    "right_foot": ("right_foot.ball", "right_foot.heel", "foot_right.tip"),
    "left_foot": ("left_foot.ball", "left_foot.heel", "foot_left.tip"),
    "head": ("head.view", "head.tip"),
    "pelvis": ("pelvis.centre", "lower_torso.proximal"),
}
"""The end effectors the operator grabs, by role; the first existing site of each role is used."""

EYE_SEGMENTS = ("left_eye", "right_eye", "eye_left", "eye_right")
"""Segments whose press grabs the eyes target (the gaze's look-at point) on a behavior-driven human."""
FRAME_KINDS = ("position", "orientation", "position+orientation")
"""Goal kinds that bring a site onto a frame (the operator's effector goals are of these kinds)."""
GOAL_KINDS = FRAME_KINDS + ("aim", "plane", "half-space", "eyes")
"""Every goal kind: ``aim`` turns the site's local ``axis`` to the target point; ``plane`` keeps the
site on the plane through the target's origin with normal ``target @ axis``; ``half-space`` keeps
it on the side that normal points into; ``eyes`` is the gaze behavior's look-at point."""


@dataclass
class Settings:
    """User settings, saved with a session."""

    literal_grab: bool = False
    """Jack's literal operator: the grabbed origin jumps to the closest point at button-down."""
    skeleton: bool = False
    show_floor: bool = True
    ik_time_budget_s: float = 0.03
    """Time box of the per-frame IK solve (s)."""
    mouse_mapping: str = "default"
    autosave_s: float = 60.0
    gizmo_local: bool = False
    snap_translate_m: float = 0.05
    snap_rotate_deg: float = 15.0
    behaviors: bool = True
    """Drags of a human's hands, feet, pelvis and head go through the behaviors (balance, planted
    feet, stepping, as in Jack); off: plain IK on the workbench goals."""
    hand_lean: bool = True
    """A dragged hand beyond the arm's reach bends the body and shifts the weight (then steps)."""
    head_drag: str = "head"
    """What a head drag moves: ``"head"`` (neck fixates the point ahead) or ``"eyes"`` (eyes, then head)."""
    feet_hold: bool = True
    """Planted feet hold their full orientation (Jack's "hold"); off: they may pivot about the ball."""
    settle_frames: int = 60
    """Behavior frames after a release before the solve stops even if the posture still creeps."""


@dataclass
class GoalEntry:
    """A goal as the workbench holds it: on ``figure``'s site ``"segment.site"``.

    ``kind`` is ``"position"``, ``"orientation"`` or ``"position+orientation"``; ``target`` the
    world 4x4 frame. ``manip`` and ``offset`` are the operator's manipulation transform ``M`` and
    orientation offset ``O`` (``R_target = R_M @ O``, spec §2.10).
    """

    key: str
    figure: str
    site: str
    kind: str
    target: np.ndarray
    enabled: bool = True
    weight: float = 1.0
    priority: int = 0
    chain: str | None = None
    manip: np.ndarray = field(default_factory=lambda: np.eye(4))
    offset: np.ndarray = field(default_factory=lambda: np.eye(3))
    axis: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))
    """``aim``: the site-local axis aimed at the target point; ``plane``/``half-space``: the normal in
    the target frame (world normal ``target[:3, :3] @ axis``)."""

    def marker_position(self) -> np.ndarray:
        """Where the goal marker is drawn (m)."""
        return self.target[:3, 3]


@dataclass
class Snapshot:
    """Undoable state: every figure's displacements and placement, and the goals.

    ``figures`` holds whole figure copies only for commands that change a figure's structure
    (rescale, import); otherwise ``None``.
    """

    postures: dict[str, tuple[np.ndarray, np.ndarray, tuple[str, str] | None]]
    goals: list[GoalEntry]
    figures: dict[str, Figure] | None = None
    behaviors: dict[str, dict[str, tuple[bool, object]]] = field(default_factory=dict)
    """Per behavior loop (figure name): each behavior's switch and a copy of its parameters."""


@dataclass
class FrameStats:
    """Timings of one frame (s)."""

    solve_s: float = 0.0
    draw_s: float = 0.0
    iterations: int = 0


# ---------------------------------------------------------------------- operator targets
class GoalTarget:
    """The operator drives a goal's manipulation transform; the goal follows (spec §2.10)."""

    def __init__(self, app: "App", goal: GoalEntry) -> None:
        self.app, self.goal = app, goal

    def transform(self) -> np.ndarray:
        return self.goal.manip

    def apply(self, M: np.ndarray) -> None:
        g = self.goal
        before = g.target.copy()
        g.manip = np.array(M, float)
        g.target = g.manip.copy()
        g.target[:3, :3] = g.manip[:3, :3] @ g.offset
        self.app.drive_behaviors(g, before)
        self.app.goals_changed()

    def end_primitive(self) -> None:
        """Ratchet: re-seat the goal orientation on the end effector's actual orientation."""
        g = self.goal
        if g.kind not in FRAME_KINDS:  # the target is a point or a plane, not the site's frame
            return
        actual = self.app.env.figure(g.figure).site_world(*g.site.split(".", 1))
        g.offset = g.manip[:3, :3].T @ actual[:3, :3]
        g.target[:3, :3] = actual[:3, :3]


class FigureTarget:
    """The operator moves a whole figure or object by its placement, its goals coming along."""

    def __init__(self, app: "App", figure: Figure) -> None:
        self.app, self.figure = app, figure

    def transform(self) -> np.ndarray:
        return self.figure.location

    def apply(self, M: np.ndarray) -> None:
        delta = np.array(M, float) @ rigid_inverse(self.figure.location)
        self.figure.location = np.array(M, float)
        for g in self.app.goals:
            if g.figure == self.figure.name:
                g.target = delta @ g.target
                g.manip = delta @ g.manip
        self.app.sync_behaviors(self.figure.name)
        self.app.goals_changed()

    def end_primitive(self) -> None:
        """Nothing to re-seat: a placement has no goal orientation."""


class JointRotation:
    """CONTROL-drag target: one joint's rotational DOFs, clamped to their limits."""

    def __init__(self, app: "App", figure: Figure, joint: str) -> None:
        self.app, self.figure, self.joint = app, figure, figure.joint(joint)
        self._dofs = [k for k, d in enumerate(self.joint.dofs) if d.kind == "R"]
        self._slice = figure.joint_dof_slice(joint)

    def dof_count(self) -> int:
        return len(self._dofs)

    def dof_axis(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        kin = self.figure.kinematics()
        fk = kin.forward(self.figure.q, self.figure.location)
        i = self._slice.start + self._dofs[k]
        return fk.dof_axes[i] * kin.dof_sign[i], fk.dof_origins[i]

    def dof_value(self, k: int) -> float:
        return float(self.joint.displacement[self._dofs[k]])

    def dof_limits(self, k: int) -> tuple[float, float]:
        d = self.joint.dofs[self._dofs[k]]
        return d.lower, d.upper

    def set_dof_value(self, k: int, value: float) -> None:
        lo, hi = self.dof_limits(k)
        disp = self.joint.displacement.copy()
        disp[self._dofs[k]] = float(np.clip(value, lo, hi))
        self.joint.displacement = disp
        self.app.posture_changed(self.figure)


# ---------------------------------------------------------------------- IK
SETTLED_DQ = 1e-6
"""A behavior frame that moves no DOF more than this (rad or m) ends the solve."""
LOOK_DISTANCE = 1.0
"""A head drag fixates the point this far (m) ahead of the dragged view frame."""
ITERATIONS_PER_CALL = 15
"""Solver iterations between time-box checks."""


def ik_goal(entry: GoalEntry) -> Goal | None:
    """The :mod:`jackpy.ik` goal of a workbench goal (None for ``eyes``: the gaze behavior's)."""
    chain = entry.chain or None
    if entry.kind == "eyes":
        return None
    if entry.kind == "aim":
        return Aim(entry.site, entry.target[:3, 3], entry.axis, chain, entry.weight, name=entry.key)
    if entry.kind in ("plane", "half-space"):
        cls = Plane if entry.kind == "plane" else HalfSpace
        return cls(entry.site, entry.target[:3, 3], entry.target[:3, :3] @ entry.axis, chain, entry.weight,
                   name=entry.key)
    if entry.kind == "position":
        return Position(entry.site, entry.target[:3, 3], chain, entry.weight, entry.key)
    if entry.kind == "orientation":
        return Orientation(entry.site, entry.target[:3, :3], chain, entry.weight, name=entry.key)
    return PositionOrientation(entry.site, entry.target, chain, entry.weight, name=entry.key)


def _signature(entry: GoalEntry) -> tuple:
    """What a goal's compiled form depends on: its kind, site and chain."""
    return entry.kind, entry.site, entry.chain or None


def solve_goals(env: Environment, goals: list[GoalEntry], budget_s: float) -> tuple[int, bool]:
    """Solve each figure's enabled goals (priority = level, 0 first) from its current posture.

    Runs :func:`jackpy.ik.solver.solve` in slices of :data:`ITERATIONS_PER_CALL` iterations until the
    goals are achieved, the solver stops improving, or ``budget_s`` seconds have passed. Returns
    (iterations, settled); not settled means the time box cut the solve short.
    """
    start = time.perf_counter()
    iterations, settled = 0, True
    for fig in env.figures.values():
        mine = [g for g in goals if g.figure == fig.name and g.enabled]
        if not mine or is_object(fig):
            continue
        problem = Problem(fig)
        for g in mine:
            goal = ik_goal(g)
            if goal is not None:
                problem.add(goal, level=max(0, g.priority))
        if not problem._entries:
            continue
        while True:
            result = ik_solve(problem, max_iterations=ITERATIONS_PER_CALL)
            iterations += result.iterations
            if result.status != ITERATION_LIMIT:
                break
            if time.perf_counter() - start >= budget_s:
                settled = False
                break
    return iterations, settled


# ---------------------------------------------------------------------- effectors
def find_effectors(figure: Figure) -> dict[str, str]:
    """``role -> "segment.site"`` of the end effectors this figure has (see :data:`EFFECTOR_SITES`)."""
    out = {}
    for role, candidates in EFFECTOR_SITES.items():
        for c in candidates:
            seg, site = c.split(".", 1)
            if seg in figure.segments and site in figure.segments[seg].sites:
                out[role] = c
                break
    return out


def effector_segments(figure: Figure, effectors: dict[str, str]) -> dict[str, str]:
    """``segment -> role``: each effector's own segment, and for hands, feet and head everything
    beyond it away from the pelvis (fingers, toes, jaw and eyes grab their hand, foot, head)."""
    adj: dict[str, list[str]] = {s: [] for s in figure.segments}
    for j in figure.joints.values():
        adj[j.from_seg].append(j.to_seg)
        adj[j.to_seg].append(j.from_seg)
    centre = effectors.get("pelvis", f"{figure.root_segment()}.x").split(".")[0]
    out: dict[str, str] = {}
    for role, site in effectors.items():
        seg = site.split(".")[0]
        out[seg] = role
        if role == "pelvis":
            continue
        toward = _next_toward(adj, seg, centre)
        stack, seen = [seg], {seg, toward}
        while stack:
            s = stack.pop()
            for n in adj[s]:
                if n not in seen:
                    seen.add(n)
                    out.setdefault(n, role)
                    stack.append(n)
    if "head" in effectors:
        for seg in EYE_SEGMENTS:
            if out.get(seg) == "head":
                out[seg] = "eyes"
    return out


def _next_toward(adj: dict[str, list[str]], start: str, goal: str) -> str | None:
    """The neighbour of ``start`` on the tree path to ``goal`` (None if ``start`` is ``goal``)."""
    prev = {start: start}
    queue = [start]
    while queue:
        s = queue.pop(0)
        if s == goal:
            break
        for n in adj[s]:
            if n not in prev:
                prev[n] = s
                queue.append(n)
    if goal not in prev or goal == start:
        return None
    s = goal
    while prev[s] != start:
        s = prev[s]
    return s


# ---------------------------------------------------------------------- the application
class App:
    """The workbench state and its frame step; ``renderer`` is optional (headless logic tests)."""

    def __init__(self, env: Environment, renderer: "Renderer | None" = None,
                 size: tuple[int, int] = (1280, 800), settings: Settings | None = None) -> None:
        self.settings = settings or Settings()
        self.renderer = renderer
        self.size = size
        self.camera = OrbitCamera()
        self.view = SceneView()
        self.manipulator = Manipulator(self.settings.literal_grab)
        self.undo_stack: UndoStack[Snapshot] = UndoStack()
        self.log: list[str] = []
        self.env = env
        self.goals: list[GoalEntry] = []
        self.selection: SegmentPick | GoalPick | None = None
        self.manipulation_mode = False
        """Explicit operator mode: drags anywhere move the selection (ESCAPE leaves it)."""
        self.session_path: Path | None = None
        self.scene_dir: Path | None = None
        """Directory the scene's included Peabody files are relative to."""
        self.dirty = False
        self.needs_solve = False
        self.stats = FrameStats()
        self.analysis = AnalysisState()
        """Analysis panel choices and results, live strength/clearance, overlays (analysis_overlays)."""
        self.on_log: Callable[[str], None] | None = None
        self._cursor = (0.0, 0.0)
        self._buttons: set[int] = set()
        self._mods = 0
        self._nav: NavAction | None = None
        self._drag_snapshot: Snapshot | None = None
        self._edit_snapshot: Snapshot | None = None
        self._drag_changed = False
        self.loops: dict[str, BehaviorLoop] = {}
        """The behavior loop of each standard human in the scene, by figure name."""
        self._user_goals: dict[str, dict[str, tuple]] = {}
        """Per figure: goal key -> (loop, signature, user goal or None) of the goals handed to its loop."""
        self._settle = 0
        self.last_report: FrameReport | None = None
        self.sensor_drive: object | None = None
        """A :class:`~jackpy.behaviors.sensor_drive.SensorDrive` (Devices panel), if connected."""
        self.driving = False
        """While True every frame runs one sensor-drive frame (the sensors move the figure)."""
        self.set_environment(env)

    # ------------------------------------------------------------------ scene
    def set_environment(self, env: Environment, goals: list[GoalEntry] | None = None) -> None:
        """Show ``env``; plant the feet of every articulated figure unless ``goals`` are given."""
        self.env = env
        self.view = SceneView()
        self.manipulator.attach(None)
        self.selection = None
        self.undo_stack.clear()
        if goals is None:
            goals = []
            for fig in env.figures.values():
                eff = find_effectors(fig)
                for role in FOOT_ROLES:
                    if role in eff:
                        goals.append(self._new_goal(fig, eff[role], "position+orientation"))
        self.goals = goals
        self.needs_solve = False
        self.make_loops()
        self.frame_all()

    def frame_all(self) -> None:
        """Aim the camera at everything in the scene."""
        lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
        for fig in self.env.figures.values():
            for w in fig.world_transforms().values():
                lo, hi = np.minimum(lo, w[:3, 3]), np.maximum(hi, w[:3, 3])
        if np.all(np.isfinite(lo)):
            self.camera.frame(lo - 0.15, hi + 0.15, self.size[0] / self.size[1])

    def figure_of_interest(self) -> Figure | None:
        """The first articulated figure (the human)."""
        return next((f for f in self.env.figures.values() if not is_object(f)), None)

    def _new_goal(self, fig: Figure, site: str, kind: str) -> GoalEntry:
        """A goal of ``kind`` that holds at the current posture: frame kinds at the site's frame;
        ``aim`` at the point :data:`LOOK_DISTANCE` along the site's z; ``plane`` and ``half-space``
        through the site with a world-up normal."""
        if kind not in GOAL_KINDS:
            raise ValueError(f"goal kind must be one of {GOAL_KINDS}, not {kind!r}")
        w = fig.site_world(*site.split(".", 1))
        manip = np.eye(4)
        manip[:3, 3] = w[:3, 3]
        if kind == "aim":
            manip[:3, 3] = w[:3, 3] + LOOK_DISTANCE * w[:3, 2]
            target = manip.copy()
            target[:3, :3] = w[:3, :3]
            return GoalEntry(f"{fig.name}:{site}", fig.name, site, kind, target, manip=manip,
                             offset=w[:3, :3].copy())
        if kind in ("plane", "half-space"):
            return GoalEntry(f"{fig.name}:{site}", fig.name, site, kind, manip.copy(), manip=manip.copy(),
                             axis=np.array([0.0, 1.0, 0.0]))
        return GoalEntry(f"{fig.name}:{site}", fig.name, site, kind, w.copy(), manip=manip,
                         offset=w[:3, :3].copy())

    def ensure_eyes_goal(self, fig: Figure) -> GoalEntry:
        """The eyes target of human ``fig`` (the gaze's look-at point, key ``FIGURE:eyes``), made at
        the gaze's current target or :data:`LOOK_DISTANCE` ahead of the view site."""
        key = f"{fig.name}:eyes"
        g = self.goal(key)
        if g is not None:
            return g
        view = find_effectors(fig).get("head", "head.view")
        loop = self.loops.get(fig.name)
        point = loop.state.eyes_target if loop is not None else None
        if point is None:
            w = fig.site_world(*view.split(".", 1))
            point = w[:3, 3] + LOOK_DISTANCE * w[:3, 2]
        manip = np.eye(4)
        manip[:3, 3] = point
        g = GoalEntry(key, fig.name, view, "eyes", manip.copy(), manip=manip)
        self.goals.append(g)
        return g

    def goal(self, key: str) -> GoalEntry | None:
        return next((g for g in self.goals if g.key == key), None)

    def ensure_goal(self, fig: Figure, site: str, kind: str = "position") -> GoalEntry:
        """The goal on ``fig``'s ``site``, created at the site's current frame if missing."""
        g = self.goal(f"{fig.name}:{site}")
        if g is None:
            g = self._new_goal(fig, site, kind)
            self.goals.append(g)
        return g

    def add_goal(self, fig: Figure, site: str, kind: str) -> GoalEntry:
        """A new goal at the site's current frame (replacing one on the same site)."""
        old = self.goal(f"{fig.name}:{site}")
        if old is not None:
            self.goals.remove(old)
        g = self._new_goal(fig, site, kind)
        self.goals.append(g)
        self.goals_changed()
        return g

    def remove_goal(self, key: str) -> None:
        """Delete a goal (one undo step)."""
        self.command(f"remove goal {key}", lambda: self.goals.remove(self.goal(key)))

    # ------------------------------------------------------------------ notifications
    def goals_changed(self) -> None:
        self._settle = 0
        self.needs_solve = True
        self.dirty = True
        self._drag_changed = True

    def posture_changed(self, figure: Figure) -> None:
        """A DOF was set directly: goals keep their targets but the figure is not re-solved."""
        self.dirty = True
        self._drag_changed = True

    def info(self, text: str) -> None:
        """Append to the log panel."""
        self.log.append(text)
        del self.log[:-500]
        if self.on_log is not None:
            self.on_log(text)

    # ------------------------------------------------------------------ undo
    def capture(self, structural: bool = False) -> Snapshot:
        """The current undoable state (whole figures too when ``structural``)."""
        postures = {n: (f.q.copy(), f.location.copy(), f.root) for n, f in self.env.figures.items()}
        figures = {n: copy.deepcopy(f) for n, f in self.env.figures.items()} if structural else None
        behaviors = {n: {b.name: (bool(b.enabled), copy.deepcopy(b.params)) for b in loop.behaviors}
                     for n, loop in self.loops.items()}
        return Snapshot(postures, copy.deepcopy(self.goals), figures, behaviors)

    def restore(self, snap: Snapshot) -> None:
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
        self.manipulator.attach(None)
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
        """Run ``action`` as one undoable step."""
        before = self.capture(structural)
        action()
        self.undo_stack.push(label, before)
        self.dirty = True
        self.info(label)

    def begin_edit(self) -> None:
        """A continuous edit (a slider drag) starts: remember the state for one undo step."""
        self._edit_snapshot = self.capture()

    def end_edit(self, label: str) -> None:
        """The continuous edit ended: push it as one undo step."""
        if self._edit_snapshot is not None:
            self.undo_stack.push(label, self._edit_snapshot)
            self._edit_snapshot = None
            self.info(label)

    def undo(self) -> None:
        if self.manipulator.active:
            return
        top = self.undo_stack.peek_undo()
        snap = self.undo_stack.undo(self.capture(top is not None and top.figures is not None))
        if snap is not None:
            self.restore(snap)
            self.info("undo")

    def redo(self) -> None:
        if self.manipulator.active:
            return
        top = self.undo_stack.peek_redo()
        snap = self.undo_stack.redo(self.capture(top is not None and top.figures is not None))
        if snap is not None:
            self.restore(snap)
            self.info("redo")

    # ------------------------------------------------------------------ picking
    def pick(self, x: float, y: float) -> SegmentPick | GoalPick | None:
        """What is drawn at framebuffer pixel (x, y) in the last frame."""
        if self.renderer is None:
            return None
        return self.view.pick_target(self.renderer.pick(int(x), int(y)))

    def ray(self, x: float, y: float) -> tuple[np.ndarray, np.ndarray]:
        """World mouse ray through framebuffer pixel (x, y)."""
        return self.camera.ray_from_pixel(x, y, *self.size)

    def world_to_pixel(self, p: np.ndarray) -> np.ndarray:
        """Framebuffer pixel (x, y) of world point ``p`` (m)."""
        clip = self.camera.projection_matrix(self.size[0] / self.size[1]) @ self.camera.view_matrix() @ np.append(p, 1.0)
        ndc = clip[:3] / clip[3]
        return np.array([(ndc[0] + 1.0) * 0.5 * self.size[0], (1.0 - ndc[1]) * 0.5 * self.size[1]])

    def select(self, target: SegmentPick | GoalPick | None) -> None:
        """Select a thing and attach the operator to it (for the next drag)."""
        self.selection = target
        self.manipulator.attach(None)

    def _attach_for_drag(self, target: SegmentPick | GoalPick, control: bool) -> bool:
        """Attach the operator to what a press hit; False when it is not manipulable."""
        if isinstance(target, GoalPick):
            g = self.goal(target.key)
            if g is None:
                return False
            self.manipulator.attach(GoalTarget(self, g))
            return True
        fig = self.env.figures.get(target.figure)
        if fig is None:
            return False
        if is_object(fig):
            self.manipulator.attach(FigureTarget(self, fig))
            return True
        roles = effector_segments(fig, find_effectors(fig))
        role = roles.get(target.segment)
        if role == "eyes":
            if fig.name in self.behavior_figures():
                self.manipulator.attach(GoalTarget(self, self.ensure_eyes_goal(fig)))
                return True
            role = "head"  # plain IK: the eyes have no target of their own; the head is grabbed
        if role is not None:
            g = self.ensure_goal(fig, find_effectors(fig)[role], "position")
            self.manipulator.attach(GoalTarget(self, g))
            return True
        if control:
            kin = fig.kinematics()
            s = kin.segment_index[target.segment]
            if kin.parent_joint[s] < 0:
                return False
            self.manipulator.attach(joint=JointRotation(self, fig, kin.joint_names[kin.parent_joint[s]]))
            return True
        self.manipulator.attach(FigureTarget(self, fig))
        return True

    @property
    def dragging(self) -> bool:
        """Whether a mouse button is held on the viewport (operator or camera)."""
        return bool(self._buttons)

    # ------------------------------------------------------------------ input handlers (glfw's)
    def resize(self, width: int, height: int) -> None:
        """Framebuffer resized (pixels)."""
        if width > 0 and height > 0:
            self.size = (width, height)
            if self.renderer is not None:
                self.renderer.resize(width, height)

    def on_cursor_pos(self, x: float, y: float) -> None:
        """Cursor moved to framebuffer pixel (x, y)."""
        dx, dy = x - self._cursor[0], y - self._cursor[1]
        self._cursor = (x, y)
        if self.manipulator.active:
            self.manipulator.move(self.ray(x, y))
        elif self._nav is NavAction.ORBIT:
            self.camera.orbit_pixels(dx, dy)
        elif self._nav is NavAction.PAN:
            self.camera.pan(dx, dy, self.size[1])
        elif self._nav is NavAction.ZOOM:
            self.camera.zoom(-dy / 40.0)

    def on_mouse_button(self, button: int, action: int, mods: int) -> None:
        """A mouse button went down (``action`` = 1) or up (0) with glfw modifier bits ``mods``."""
        if button not in _BUTTON_NAMES:
            return
        self._mods = mods
        was_idle = not self._buttons
        if action == PRESS:
            self._buttons.add(button)
        elif action == RELEASE:
            self._buttons.discard(button)
        else:
            return
        if was_idle and action == PRESS:
            self._begin_press(button)
        elif self.manipulator.target is not None or self.manipulator.joint is not None:
            self._update_operator()
        if not self._buttons:
            self._end_press()

    def _begin_press(self, button: int) -> None:
        x, y = self._cursor
        control = bool(self._mods & MOD_CONTROL)
        hit = self.pick(x, y)
        target = hit if hit is not None else (self.selection if self.manipulation_mode else None)
        before = self.capture()
        if target is not None and self._attach_for_drag(target, control):
            self.selection = target
            grabbed = self.manipulator.target
            if isinstance(grabbed, GoalTarget) and grabbed.goal.kind == "eyes":
                self.selection = GoalPick(grabbed.goal.key)  # an eye selects the eyes target
            self._drag_snapshot = before
            self._drag_changed = False
            self._update_operator()
            return
        mods = {"shift"} if self._mods & MOD_SHIFT else set()
        if self._mods & MOD_CONTROL:
            mods.add("ctrl")
        self._nav = navigation_action(self.settings.mouse_mapping, _BUTTON_NAMES[button], mods)

    def _update_operator(self) -> None:
        names = frozenset(_BUTTON_NAMES[b] for b in self._buttons)
        self.manipulator.literal = self.settings.literal_grab
        self.manipulator.set_buttons(names, bool(self._mods & MOD_SHIFT), bool(self._mods & MOD_CONTROL),
                                     self.ray(*self._cursor))

    def _end_press(self) -> None:
        self._nav = None
        if self._drag_snapshot is not None:
            self.manipulator.finish()
            if self._drag_changed:
                self.end_behavior_drag()
                self.needs_solve = True
            if self._drag_changed:
                self.undo_stack.push("drag", self._drag_snapshot)
            self._drag_snapshot = None

    def on_scroll(self, dx: float, dy: float) -> None:
        """Mouse wheel: zoom."""
        self.camera.zoom(dy)

    def on_key(self, key: int, scancode: int, action: int, mods: int) -> None:
        """Keyboard: modifiers re-select the operator's primitive mid-drag; shortcuts otherwise."""
        if key in (KEY_LEFT_SHIFT, KEY_RIGHT_SHIFT, KEY_LEFT_CONTROL, KEY_RIGHT_CONTROL):
            bit = MOD_SHIFT if key in (KEY_LEFT_SHIFT, KEY_RIGHT_SHIFT) else MOD_CONTROL
            self._mods = (self._mods | bit) if action != RELEASE else (self._mods & ~bit)
            if self._drag_snapshot is not None:
                self._update_operator()
            return
        if action != PRESS:
            return
        ctrl = bool(mods & MOD_CONTROL)
        if key == KEY_ESCAPE:
            self._end_press()
            self._buttons.clear()
            self.manipulation_mode = False
            self.select(None)
        elif ctrl and key == ord("Z"):
            self.redo() if mods & MOD_SHIFT else self.undo()
        elif ctrl and key == ord("Y"):
            self.redo()
        elif key == KEY_DELETE and isinstance(self.selection, GoalPick):
            self.remove_goal(self.selection.key)
            self.selection = None
        elif not ctrl and key == ord("M"):
            self.manipulation_mode = not self.manipulation_mode
        elif not ctrl and key == ord("K"):
            self.settings.skeleton = not self.settings.skeleton
        elif not ctrl and key == ord("F"):
            self.frame_all()
        elif not ctrl and key in (ord("1"), ord("3"), ord("7"), ord("9")):
            self.camera.set_preset({ord("1"): "front", ord("3"): "side", ord("7"): "top",
                                    ord("9"): "iso"}[key])

    # ------------------------------------------------------------------ frame
    def solve(self) -> tuple[int, bool]:
        """Solve for every figure with enabled goals, within the time box.

        Humans with a behavior loop (when ``settings.behaviors``) run :meth:`BehaviorLoop.step`
        frames; every other figure is solved by plain IK on its goals. Returns (iterations or
        behavior frames, settled): settled when the goals are met or the solve stalls.
        """
        start = time.perf_counter()
        budget = self.settings.ik_time_budget_s
        count, settled = 0, True
        driven = self.behavior_figures()
        for name in driven:
            loop, fig = self.loops[name], self.env.figures[name]
            self.sync_user_goals(name)
            while True:
                q0 = fig.q.copy()
                self.last_report = loop.step()
                count += 1
                self._settle += 1
                moved = float(np.max(np.abs(fig.q - q0), initial=0.0))
                if moved < SETTLED_DQ or self._settle >= self.settings.settle_frames:
                    break
                if time.perf_counter() - start >= budget:
                    settled = False
                    break
        rest = [g for g in self.goals if g.figure not in driven]
        if rest:
            it, ok = solve_goals(self.env, rest, max(0.0, budget - (time.perf_counter() - start)))
            count, settled = count + it, settled and ok
        return count, settled

    # ------------------------------------------------------------------ behaviors
    def make_loops(self) -> None:
        """A behavior loop for every standard human in the scene (feet planted where they stand)."""
        self.loops = {}
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
        if goal.kind == "eyes":
            return False
        return goal.kind not in FRAME_KINDS or self.role_of(goal) is None

    def sync_user_goals(self, name: str) -> None:
        """Hand figure ``name``'s user goals to its behavior loop: new ones are added, removed ones
        removed (a changed kind, site or chain is both); targets, weights, levels and switches are
        updated in place, so the loop keeps its compiled problems."""
        loop = self.loops.get(name)
        if loop is None:
            return
        mine = {g.key: g for g in self.goals if g.figure == name and self.is_user_goal(g)}
        have = self._user_goals.setdefault(name, {})
        for key in list(have):
            lp, sig, ug = have[key]
            e = mine.get(key)
            if lp is not loop or e is None or sig != _signature(e):
                if lp is loop and ug is not None:
                    loop.remove_user_goal(ug)
                del have[key]
        for key, e in mine.items():
            if key not in have:
                goal = ik_goal(e)
                try:
                    ug = loop.add_user_goal(goal, level=max(0, e.priority), enabled=e.enabled, key=key)
                except (JackpyError, KeyError, ValueError) as exc:
                    self.info(f"error: goal {key}: {exc}")
                    ug = None
                have[key] = (loop, _signature(e), ug)
                continue
            ug = have[key][2]
            if ug is None:
                continue
            fresh = ik_goal(e)
            for attr in ("target", "point", "normal", "axis"):
                if hasattr(fresh, attr):
                    setattr(ug.goal, attr, getattr(fresh, attr))
            loop.set_user_goal(ug, enabled=e.enabled, weight=max(0.0, e.weight), level=max(0, e.priority))

    def user_goal_part(self, key: str) -> str | None:
        """The pass (``body``, ``head``, ``left``, ``right``) that solves user goal ``key`` while the
        behaviors are on; None when the behaviors do not solve it."""
        for have in self._user_goals.values():
            entry = have.get(key)
            if entry is not None and entry[2] is not None:
                return entry[2].part
        return None

    def role_of(self, goal: GoalEntry) -> str | None:
        """The end-effector role (``right_hand`` ...) of a goal's site, if it is one."""
        fig = self.env.figures.get(goal.figure)
        if fig is None:
            return None
        return next((r for r, s in find_effectors(fig).items() if s == goal.site), None)

    def sync_behaviors(self, name: str) -> None:
        """Restart figure ``name``'s behavior state from its posture and its hand goals (after
        undo, a figure move, a rescale, opening a scene)."""
        loop = self.loops.get(name)
        if loop is None:
            return
        loop.reset_state()
        for side in loop.state.feet:
            manipulation.set_foot_behavior(loop, side, mode="hold" if self.settings.feet_hold else "pivot")
        manipulation.move_eyes(loop, None)  # the eyes target lives in the goals (undo may drop it)
        for g in self.goals:
            if g.figure == name and g.kind == "eyes" and g.enabled:
                manipulation.move_eyes(loop, g.target[:3, 3])
                continue
            role = self.role_of(g) if g.figure == name and g.kind in FRAME_KINDS else None
            if role in HAND_ROLES and g.enabled:
                side = role.split("_")[0]
                manipulation.move_hand(loop, side, position=g.target[:3, 3], rotation=g.target[:3, :3],
                                       lean=self.settings.hand_lean)
        self._settle = 0

    def drive_behaviors(self, goal: GoalEntry, before: np.ndarray) -> None:
        """A dragged effector goal moved from ``before`` to ``goal.target``: tell the behaviors
        through Jack's manipulation commands (move_hand, move_foot, move_pelvis, move_head/eyes)."""
        loop = self.loops.get(goal.figure) if goal.figure in self.behavior_figures() else None
        if loop is not None and goal.kind == "eyes":
            manipulation.move_eyes(loop, goal.target[:3, 3])
            self._settle = 0
            return
        role = self.role_of(goal) if loop is not None and goal.kind in FRAME_KINDS else None
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

    def set_behaviors_enabled(self, on: bool) -> None:
        """Switch between the behaviors and plain IK for the humans' goals."""
        if on == self.settings.behaviors:
            return
        self.settings.behaviors = on
        for name in self.loops:
            self.sync_behaviors(name)
        self.goals_changed()
        self.info("behaviors on" if on else "behaviors off: plain IK")

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
                g.target, g.offset = w.copy(), w[:3, :3].copy()
                g.manip = np.eye(4)
                g.manip[:3, 3] = w[:3, 3]
        self.make_loops()  # new sites and footprints; feet re-planted where they now stand
        self.goals_changed()
        self.info(f"rescaled {name} to {sex} P{percentile:g} ({population})")

    def import_cad(self, path: str | Path, units: str = "m", up: str = "y") -> bool:
        """Add a CAD file (one undo step); an error goes to the log and leaves the scene untouched."""
        from jackpy.ui import session

        before = self.capture(structural=True)
        try:
            obj = session.import_cad_file(self, path, units, up)
        except (JackpyError, OSError, ValueError) as exc:
            self.info(f"error: import {Path(path).name}: {exc}")
            return False
        self.undo_stack.push(f"import {obj.name}", before)
        self.dirty = True
        return True

    def end_behavior_drag(self) -> None:
        """Mouse release: :func:`~jackpy.behaviors.manipulation.end_drag` on every loop."""
        for loop in self.loops.values():
            manipulation.end_drag(loop)
        self._settle = 0

    def step(self) -> FrameStats:
        """One frame after the input handlers ran: solve if goals changed, then draw."""
        stats = FrameStats()
        if self.driving and self.sensor_drive is not None:
            t0 = time.perf_counter()
            try:
                report = self.sensor_drive.step()  # type: ignore[attr-defined]
                self.last_report = report.loop or self.last_report
            except JackpyError as exc:
                self.driving = False
                self.info(f"error: sensor drive stopped: {exc}")
            stats.solve_s = time.perf_counter() - t0
            self.dirty = True
        elif self.needs_solve:
            t0 = time.perf_counter()
            stats.iterations, settled = self.solve()
            stats.solve_s = time.perf_counter() - t0
            self.needs_solve = self.manipulator.active or not settled
        if self.renderer is not None:
            t0 = time.perf_counter()
            self.draw()
            stats.draw_s = time.perf_counter() - t0
        self.stats = stats
        return stats

    def draw(self) -> None:
        """Render the scene into the renderer's framebuffer."""
        assert self.renderer is not None
        triads, lines = self.manipulator.overlay()
        self.view.upload(self.renderer, self.env)
        scene = self.view.build(self.env, self.goals, self.settings.skeleton, self.selection,
                                Overlay(triads, lines), self.settings.show_floor)
        self.analysis.decorate(self, scene)
        self.renderer.render(scene, self.camera.view_matrix(), self.camera.projection_matrix(self.renderer.aspect))
        self.analysis.after_draw(self)
