"""The workbench application: input handlers, camera, selection, operator and drawing around a
:class:`~jackpy.document.Document`, apart from any window.

One frame (docs/architecture.md): input → document → goals → behaviors → IK → FK → analyses → draw.
The input handlers (:meth:`App.on_cursor_pos`, :meth:`App.on_mouse_button`, :meth:`App.on_scroll`,
:meth:`App.on_key`) take the same arguments glfw passes to its callbacks (buttons, actions, modifier
bits and key codes as glfw numbers) and change the document only through its methods (the
operator's :meth:`Document.move_goal`, :meth:`Document.move_figure`, :meth:`Document.set_dof`) or
the camera. :meth:`App.step` then runs :meth:`Document.step` and draws. The window
(:mod:`jackpy.ui.window`) calls exactly these; tests call them with synthetic events.

Mouse (default mapping, docs/workbench.md): a press on a pickable thing (hand, foot, head, pelvis,
a goal marker, any other segment of a figure, an object) starts the Jack operator on it; a press
on empty space navigates: left orbits, right pans, middle zooms, the wheel zooms.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors import BehaviorLoop, FrameReport
from jackpy.document import Document, DocumentState, GoalEntry, Settings
from jackpy.document.effectors import (  # noqa: F401  (re-exported for the panels and tests)
    EFFECTOR_SITES,
    EYE_SEGMENTS,
    FOOT_ROLES,
    HAND_ROLES,
    effector_segments,
    find_effectors,
)
from jackpy.document.goals import EYES
from jackpy.peabody import Environment, Figure
from jackpy.ui.analysis_overlays import AnalysisState
from jackpy.ui.camera import NavAction, OrbitCamera, navigation_action
from jackpy.ui.frame_budget import FrameBudget
from jackpy.ui.manipulator import Manipulator
from jackpy.ui.preferences import Preferences
from jackpy.ui.scene_view import GoalPick, Overlay, SceneView, SegmentPick, is_object

if TYPE_CHECKING:
    from jackpy.render import Renderer

# glfw's numbers, so that this module needs no glfw import (and no display).
MOUSE_LEFT, MOUSE_RIGHT, MOUSE_MIDDLE = 0, 1, 2
RELEASE, PRESS, REPEAT = 0, 1, 2
MOD_SHIFT, MOD_CONTROL, MOD_ALT = 1, 2, 4
KEY_ESCAPE, KEY_DELETE = 256, 261
KEY_LEFT_SHIFT, KEY_LEFT_CONTROL, KEY_RIGHT_SHIFT, KEY_RIGHT_CONTROL = 340, 341, 344, 345
_BUTTON_NAMES = {MOUSE_LEFT: "left", MOUSE_MIDDLE: "middle", MOUSE_RIGHT: "right"}


@dataclass
class FrameStats:
    """Timings of one frame (s), the solve's time box (s) and whether it solved, and the frame
    budget's rung (:mod:`jackpy.ui.frame_budget`; on the last rung every other frame of a drag
    draws without solving). ``idle_s``: a split sensor drive's idle step after the draw
    (:meth:`App.step`), also counted in ``solve_s``."""

    solve_s: float = 0.0
    draw_s: float = 0.0
    iterations: int = 0
    box_s: float = 0.0
    solved: bool = False
    timed_out: bool = False
    level: int = 0
    drawn: bool = False
    behaviors_s: float = 0.0
    idle_s: float = 0.0


# ---------------------------------------------------------------------- operator targets
class GoalTarget:
    """The operator drives a goal's manipulation transform; the goal follows (spec §2.10)."""

    def __init__(self, app: App, goal: GoalEntry) -> None:
        self.app, self.goal = app, goal

    def transform(self) -> np.ndarray:
        return self.goal.manip

    def apply(self, M: np.ndarray) -> None:
        self.app.doc.move_goal(self.goal, M)

    def end_primitive(self) -> None:
        """Ratchet: re-seat the goal orientation on the end effector's actual orientation."""
        self.app.doc.reseat_goal(self.goal)


class FigureTarget:
    """The operator moves a whole figure or object by its placement, its goals coming along."""

    def __init__(self, app: App, figure: Figure) -> None:
        self.app, self.figure = app, figure

    def transform(self) -> np.ndarray:
        return self.figure.location

    def apply(self, M: np.ndarray) -> None:
        self.app.doc.move_figure(self.figure, M)

    def end_primitive(self) -> None:
        """Nothing to re-seat: a placement has no goal orientation."""


class JointRotation:
    """CONTROL-drag target: one joint's rotational DOFs, written through the figure (clamped)."""

    def __init__(self, app: App, figure: Figure, joint: str) -> None:
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
        self.app.doc.set_dof(self.figure, self.joint.name, self._dofs[k], value)


def _doc_property(name: str, doc: str) -> property:
    """An App attribute that is the document's (read and written through ``app.doc``)."""
    return property(lambda self: getattr(self.doc, name), lambda self, v: setattr(self.doc, name, v), doc=doc)


# ---------------------------------------------------------------------- the application
class App:
    """The workbench around a :class:`Document`; ``renderer`` is optional (headless logic tests).

    ``env`` starts a new document on it; ``doc`` uses a given one.
    """

    env = _doc_property("env", "The document's environment.")
    goals = _doc_property("goals", "The document's goals.")
    settings = _doc_property("settings", "The document's settings.")
    loops = _doc_property("loops", "The document's behavior loops, by figure name.")
    undo_stack = _doc_property("undo_stack", "The document's undo/redo stack.")
    session_path = _doc_property("path", "The document's file.")
    scene_dir = _doc_property("scene_dir", "Directory the scene's included files are relative to.")
    dirty = _doc_property("dirty", "Whether the document changed since it was saved.")
    needs_solve = _doc_property("needs_solve", "Whether the document's goals changed since the last solve.")
    log = _doc_property("log", "The document's log.")
    last_report = _doc_property("last_report", "The last behavior frame's report.")

    def __init__(self, env: Environment | None = None, renderer: Renderer | None = None,
                 size: tuple[int, int] = (1280, 800), settings: Settings | None = None,
                 doc: Document | None = None) -> None:
        self.renderer = renderer
        self.size = size
        self.camera = OrbitCamera()
        self.view = SceneView()
        self.manipulator = Manipulator(False)
        self.selection: SegmentPick | GoalPick | None = None
        self.manipulation_mode = False
        """Explicit operator mode: drags anywhere move the selection (ESCAPE leaves it)."""
        self.stats = FrameStats()
        self.analysis = AnalysisState()
        """Analysis panel choices and results; the document's live analyses are this object."""
        self.on_log: Callable[[str], None] | None = None
        self._cursor = (0.0, 0.0)
        self._buttons: set[int] = set()
        self._mods = 0
        self._nav: NavAction | None = None
        self._drag_snapshot: DocumentState | None = None
        self.sensor_drive: object | None = None
        """A :class:`~jackpy.behaviors.sensor_drive.SensorDrive` (Devices panel), if connected."""
        self.driving = False
        """While True every frame runs one sensor-drive frame (the sensors move the figure)."""
        self._last_step = time.perf_counter()
        self.frame_budget = FrameBudget()
        """Adaptive quality: each frame's solve box, iteration caps and draw scale (status bar)."""
        self.preferences = Preferences.load()
        """The user's preferences ($JACKPY_HOME/preferences.json): mouse preset, dialogs, recent files."""
        self.set_document(doc if doc is not None else Document(env, settings))
        if self.preferences.problem:
            self.info(self.preferences.problem)

    # ------------------------------------------------------------------ document
    def set_document(self, doc: Document) -> None:
        """Show ``doc`` (new, opened): the view, selection and operator start afresh; the camera
        comes from the document's saved view, else frames everything."""
        self.doc = doc
        doc.analyses = self.analysis
        doc.on_log = self._forward_log
        self.view = SceneView()
        self.manipulator.attach(None)
        self.manipulator.literal = doc.settings.literal_grab
        doc.settings.mouse_mapping = self.preferences.mouse_preset  # the user's, whatever the file said
        self.selection = None
        cam = doc.view_state.get("camera")
        if cam is not None:
            self.camera.target = np.asarray(cam["target"], float).reshape(3)
            self.camera.distance, self.camera.yaw, self.camera.pitch = (float(cam["distance"]), float(cam["yaw"]),
                                                                       float(cam["pitch"]))
            self.camera.orthographic = bool(cam.get("orthographic", False))
        else:
            self.frame_all()

    def set_environment(self, env: Environment, goals: list[GoalEntry] | None = None) -> None:
        """Show ``env`` in the document (its undo history starts afresh; the camera frames it)."""
        self.doc.set_environment(env, goals)
        self.doc.view_state.pop("camera", None)
        self.set_document(self.doc)

    def store_view(self) -> None:
        """Put the camera into the document's view state (before a save)."""
        c = self.camera
        self.doc.view_state["camera"] = {"target": [float(x) for x in c.target], "distance": float(c.distance),
                                         "yaw": float(c.yaw), "pitch": float(c.pitch),
                                         "orthographic": bool(c.orthographic)}

    def _forward_log(self, text: str) -> None:
        if self.on_log is not None:
            self.on_log(text)

    def frame_all(self) -> None:
        """Aim the camera at everything in the scene."""
        lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
        for fig in self.env.figures.values():
            for w in fig.world_transforms().values():
                lo, hi = np.minimum(lo, w[:3, 3]), np.maximum(hi, w[:3, 3])
        if np.all(np.isfinite(lo)):
            self.camera.frame(lo - 0.15, hi + 0.15, self.size[0] / self.size[1])

    # the document's operations, as the panels call them
    def figure_of_interest(self) -> Figure | None:
        return self.doc.figure_of_interest()

    def goal(self, key: str) -> GoalEntry | None:
        return self.doc.goal(key)

    def ensure_goal(self, fig: Figure, site: str, kind: str = "position") -> GoalEntry:
        return self.doc.ensure_goal(fig, site, kind)

    def ensure_eyes_goal(self, fig: Figure) -> GoalEntry:
        return self.doc.ensure_eyes_goal(fig)

    def add_goal(self, fig: Figure, site: str, kind: str, **params: object) -> GoalEntry:
        return self.doc.add_goal(fig, site, kind, **params)

    def remove_goal(self, key: str) -> None:
        if isinstance(self.selection, GoalPick) and self.selection.key == key:
            self.selection = None
        self.manipulator.attach(None)
        self.doc.remove_goal(key)

    def goals_changed(self) -> None:
        self.doc.goals_changed()

    def posture_changed(self, figure: Figure) -> None:
        self.doc.posture_changed(figure)

    def info(self, text: str) -> None:
        """Append to the log panel."""
        self.doc.info(text)

    def capture(self, structural: bool = False) -> DocumentState:
        return self.doc.capture(structural)

    def restore(self, snap: DocumentState) -> None:
        self.doc.restore(snap)
        self.manipulator.attach(None)

    def command(self, label: str, action: Callable[[], object], structural: bool = False) -> None:
        """Run ``action`` as one undoable command on the document."""
        self.doc.command(label, action, structural)

    def begin_edit(self) -> None:
        self.doc.begin_edit()

    def end_edit(self, label: str) -> None:
        self.doc.end_edit(label)

    def undo(self) -> None:
        if not self.manipulator.active and self.doc.undo():
            self.manipulator.attach(None)

    def redo(self) -> None:
        if not self.manipulator.active and self.doc.redo():
            self.manipulator.attach(None)

    def behavior_figures(self) -> set[str]:
        return self.doc.behavior_figures()

    def is_user_goal(self, goal: GoalEntry) -> bool:
        return self.doc.is_user_goal(goal)

    def user_goal_part(self, key: str) -> str | None:
        return self.doc.user_goal_part(key)

    def role_of(self, goal: GoalEntry) -> str | None:
        return self.doc.role_of(goal)

    def sync_behaviors(self, name: str) -> None:
        self.doc.sync_behaviors(name)

    def drive_behaviors(self, goal: GoalEntry, before: np.ndarray) -> None:
        self.doc.drive_behaviors(goal, before)

    def end_behavior_drag(self) -> None:
        self.doc.end_behavior_drag()

    def set_behaviors_enabled(self, on: bool) -> None:
        self.doc.set_behaviors_enabled(on)

    def rescale_figure(self, name: str, sex: str, percentile: float, population: str = "ansur2") -> None:
        self.doc.rescale_figure(name, sex, percentile, population)

    def import_cad(self, path: str | Path, units: str = "m", up: str = "y") -> bool:
        """Add a CAD file (one undo step); an error goes to the log and leaves the scene untouched."""
        return self.doc.import_cad(path, units, up) is not None

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
        mods = {"shift"} if self._mods & MOD_SHIFT else set()
        if self._mods & MOD_CONTROL:
            mods.add("ctrl")
        if self._mods & MOD_ALT:
            mods.add("alt")
        nav = navigation_action(self.settings.mouse_mapping, _BUTTON_NAMES[button], mods)
        if nav is not None and "alt" in mods:  # Maya's Alt-drags navigate, also over a figure
            self._nav = nav
            return
        hit = self.pick(x, y)
        target = hit if hit is not None else (self.selection if self.manipulation_mode else None)
        before = self.capture()
        if target is not None and self._attach_for_drag(target, control):
            self.selection = target
            grabbed = self.manipulator.target
            if isinstance(grabbed, GoalTarget) and grabbed.goal.role == EYES:
                self.selection = GoalPick(grabbed.goal.key)  # an eye selects the eyes target
            self._drag_snapshot = before
            self._drag_label = self._label_of(self.manipulator)
            self.doc.take_changed()
            self._update_operator()
            return
        self._nav = nav

    @staticmethod
    def _label_of(manipulator: Manipulator) -> str:
        """The undo label of a drag: what it moves (a goal by its kind, a joint, a figure)."""
        t = manipulator.target
        if isinstance(t, GoalTarget):
            return f"drag {t.goal.kind} goal {t.goal.key}"
        if isinstance(t, FigureTarget):
            return f"move {t.figure.name}"
        if manipulator.joint is not None:
            return f"rotate {manipulator.joint.joint.name}"
        return "drag"

    def _update_operator(self) -> None:
        names = frozenset(_BUTTON_NAMES[b] for b in self._buttons)
        self.manipulator.literal = self.settings.literal_grab
        self.manipulator.set_buttons(names, bool(self._mods & MOD_SHIFT), bool(self._mods & MOD_CONTROL),
                                     self.ray(*self._cursor))

    def _end_press(self) -> None:
        self._nav = None
        if self._drag_snapshot is not None:
            self.manipulator.finish()
            if self.doc.take_changed():
                self.end_behavior_drag()
                self.doc.needs_solve = True
                self.doc.push(self._drag_label, self._drag_snapshot)
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
    def restart_frame_clock(self) -> None:
        """The time since the last :meth:`step` was not this App's frame (another App's frames ran,
        or a blocking dialog): the next step's period counts from now, so the frame budget does
        not read the gap as a slow frame."""
        self._last_step = time.perf_counter()

    def step(self) -> FrameStats:
        """One frame after the input handlers ran: a sensor-drive frame or the document's step
        (solve when goals changed, then the live analyses), then the draw. The frame budget plans
        the frame (the solve's box and caps, the draw's scale) from the frames before it.

        A sensor drive with split frames (``config.split``: the sample's step solved the spine and
        arms only) then runs :meth:`~jackpy.behaviors.sensor_drive.SensorDrive.idle` after the
        draw (the pelvis servo and the loop's full step, when owed), until the next frame is due
        (this frame's start + the budget's target period) but within the frame's solve box (the
        sensor step and the idle step together; the idle time counts in ``solve_s`` and in
        ``idle_s``)."""
        stats = FrameStats()
        now = time.perf_counter()
        dt, self._last_step = now - self._last_step, now
        prev = self.stats
        self.frame_budget.record(dt, prev.solve_s, prev.box_s, prev.solved, prev.drawn, prev.behaviors_s)
        plan = self.frame_budget.plan(self.settings.ik_time_budget_s)
        stats.level = plan.level
        driven = self.driving and self.sensor_drive is not None
        if driven:
            t0 = time.perf_counter()
            loop = getattr(self.sensor_drive, "loop", None)
            if isinstance(loop, BehaviorLoop):
                loop.time_box_s = plan.limits.box_s if plan.limits is not None else None
            try:
                report = self.sensor_drive.step()  # type: ignore[attr-defined]
                self.doc.last_report = report.loop or self.doc.last_report
                stats.timed_out = bool(report.loop is not None and report.loop.timed_out)
            except Exception as exc:  # noqa: BLE001 - a device error stops the drive, the window goes on
                self._sensor_drive_failed(exc)
            stats.solve_s = time.perf_counter() - t0
            stats.box_s, stats.solved = plan.box_s, True
            self.doc.dirty = True
            self.doc.analyses.refresh(self.env)
        else:
            was = self.doc.needs_solve
            if not plan.solve and self.manipulator.active:  # a drag's frame between solves: draw only
                self.doc.needs_solve = False
            s = self.doc.step(dt, plan.limits)
            stats.solve_s, stats.iterations = s.solve_s, s.iterations
            stats.box_s, stats.solved, stats.timed_out = s.box_s, s.solved, s.timed_out
            stats.behaviors_s = s.behaviors_s
            if was and self.manipulator.active:
                self.doc.needs_solve = True  # a drag keeps solving while the button is held
        if self.renderer is not None:
            self.renderer.render_scale = plan.render_scale
            drawn = self.renderer.frames_drawn
            t0 = time.perf_counter()
            self.draw()
            stats.draw_s = time.perf_counter() - t0
            stats.drawn = self.renderer.frames_drawn != drawn
        if driven and self.driving and getattr(getattr(self.sensor_drive, "config", None), "split", False):
            self._sensor_drive_idle(now, stats)
        self.stats = stats
        return stats

    def _sensor_drive_idle(self, start: float, stats: FrameStats) -> None:
        """A split sensor drive's idle step after the draw (:meth:`step`): until this frame's
        ``start`` + the target period, and no longer than what the solve box leaves after the
        sensor step (so the frame budget's estimate of the other costs stays theirs)."""
        t0 = time.perf_counter()
        until = min(start + self.frame_budget.target_s, t0 + max(0.0, stats.box_s - stats.solve_s))
        try:
            report = self.sensor_drive.idle(until)  # type: ignore[attr-defined]
        except Exception as exc:  # noqa: BLE001 - as in the sensor step: the drive stops, the window goes on
            report = None
            self._sensor_drive_failed(exc)
        stats.idle_s = time.perf_counter() - t0
        stats.solve_s += stats.idle_s
        if report is not None:
            self.doc.last_report = report
            stats.timed_out = stats.timed_out or report.timed_out
            stats.behaviors_s = max(0.0, stats.idle_s - report.solve_s)

    def _sensor_drive_failed(self, exc: Exception) -> None:
        """A sensor drive's step or idle step raised: driving stops, said in the log."""
        self.driving = False
        self.info(f"error: sensor drive stopped: {exc}")

    def draw(self) -> None:
        """Render the scene into the renderer's framebuffer: the document as it is (solved and
        analysed by :meth:`Document.step`), the operator's feedback and the analyses' overlays."""
        assert self.renderer is not None
        triads, lines = self.manipulator.overlay()
        self.view.upload(self.renderer, self.env)
        scene = self.view.build(self.env, self.goals, self.settings.skeleton, self.selection,
                                Overlay(triads, lines), self.settings.show_floor)
        self.view.add_terrain(self.renderer, scene, self.doc)
        self.analysis.decorate(self, scene)
        self.renderer.render(scene, self.camera.view_matrix(), self.camera.projection_matrix(self.renderer.aspect))
        self.analysis.after_draw(self)


__all__ = ["App", "BehaviorLoop", "FrameReport", "FrameStats", "GoalEntry", "Settings", "EYES"]
