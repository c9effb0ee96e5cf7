"""Analysis panel: reach (workspace envelope, point reach), strength, clearance, view and the report.

Everything here acts on the app's figure of interest. The imgui drawing (:func:`draw`) only calls the
action functions below, which tests drive directly:

- :func:`start_workspace` / :func:`cancel_workspace`: the reachable workspace of the chosen hand on a
  worker thread (a copy of the figure at its current posture); the progress callback returns False
  once Cancel was pressed, so the sampling stops at the next batch. The finished envelope is shown
  translucently and the scene's sites are listed inside/outside.
- :func:`reach_target`: collision-aware point reach of a named site (``reached (2 mm)`` / ``blocked
  by partition (short by ~20 cm)`` / ``short by ~10 cm``);
  :func:`apply_reach` puts the figure in the reaching posture (one undo step).
- strength and clearance are live (:class:`~jackpy.ui.analysis_overlays.AnalysisState`).
- :func:`measure_visibility`: visible fraction of an object or site from the eyes and its occluders,
  rendered on the window's GL context.
- :func:`start_report`: the same report as ``jackpy analyze`` for the current scene (its objects, the
  figure's standing place, the chosen hand and load, standard figure sizes) into a folder, on a worker
  thread; its pictures are rendered on the main thread through :class:`MainThreadRenderer`.
"""

from __future__ import annotations

import copy
import threading
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.errors import JackpyError
from jackpy.ui.panels import Panel
from jackpy.peabody import Environment
from jackpy.ui.analysis_overlays import (
    AnalysisState,
    WorkspaceResult,
    scene_objects,
    scene_targets,
)

if TYPE_CHECKING:
    from jackpy.analysis import PointReach, Visibility
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

HANDS = ["right", "left"]


# ---------------------------------------------------------------------- background jobs
class Job:
    """Work on a daemon thread with a progress fraction, a message, cancel and a result."""

    def __init__(self) -> None:
        self.progress = 0.0
        self.message = ""
        self.done = False
        self.error: str | None = None
        self.result: Any = None
        self._cancel = threading.Event()
        self._thread: threading.Thread | None = None

    def run(self) -> Any:  # pragma: no cover - overridden
        raise NotImplementedError

    def finished(self) -> None:
        """Called on the worker thread after :meth:`run` (result or error set)."""

    def _main(self) -> None:
        try:
            self.result = self.run()
        except Exception as exc:
            self.error = f"{type(exc).__name__}: {exc}"
        finally:
            self.done = True
            self.finished()

    def start(self) -> Job:
        self._thread = threading.Thread(target=self._main, name=type(self).__name__, daemon=True)
        self._thread.start()
        return self

    def cancel(self) -> None:
        """Ask the job to stop at its next progress report."""
        self._cancel.set()

    @property
    def cancel_requested(self) -> bool:
        return self._cancel.is_set()

    def join(self, timeout: float | None = None) -> None:
        if self._thread is not None:
            self._thread.join(timeout)


class WorkspaceJob(Job):
    """The reachable workspace of ``hand`` of a figure copy, its surface and the sites' classification."""

    def __init__(self, state: AnalysisState, figure, hand: str, resolution: int,
                 sites: dict[str, np.ndarray], max_samples: int = 2_000_000, version: int = 0) -> None:
        super().__init__()
        self.state, self.figure, self.hand, self.resolution = state, figure, hand, resolution
        self.sites, self.max_samples, self.version = sites, max_samples, version
        self.reports = 0

    def progress_callback(self, p) -> bool:
        """The sampler's callback: record progress; False (cancel) once Cancel was asked for."""
        self.reports += 1
        self.progress = min(p.samples / max(p.max_samples, 1), 1.0)
        self.message = f"{p.samples:,} samples, {p.marked:,} voxels"
        return not self.cancel_requested

    def run(self) -> WorkspaceResult:
        from jackpy.analysis import Chain, figure_parts, reachable_workspace

        h = figure_parts(self.figure).hands[self.hand]
        chain = Chain.to_site(self.figure, h.start_joint, h.segment, h.site)
        ws = reachable_workspace(chain, self.resolution, max_samples=self.max_samples,
                                 progress=self.progress_callback)
        if ws.cancelled:
            self.message = f"cancelled after {ws.samples:,} samples"
            return WorkspaceResult(ws, None, {}, self.figure.name, self.hand, self.version)
        self.message = "surface"
        surface = ws.surface()
        result = WorkspaceResult(ws, surface, ws.classify(self.sites), self.figure.name, self.hand, self.version)
        self.progress, self.message = 1.0, f"{ws.volume() * 1000:.0f} litres, {ws.samples:,} samples"
        return result

    def finished(self) -> None:
        if self.result is not None and not self.result.workspace.cancelled:
            result = self.result
            self.state.post(lambda: setattr(self.state, "workspace", result))


def start_workspace(app: App, max_samples: int = 2_000_000, start: bool = True) -> WorkspaceJob:
    """Start computing the chosen hand's workspace at the figure's current posture."""
    state = app.analysis
    fig = app.figure_of_interest()
    if fig is None:
        raise JackpyError("no figure to analyse")
    if state.workspace_job is not None and not state.workspace_job.done:
        state.workspace_job.cancel()
    version = (state.workspace.version + 1) if state.workspace is not None else 1
    job = WorkspaceJob(state, copy.deepcopy(fig), state.hand, state.resolution, scene_targets(app.env),
                       max_samples, version)
    state.workspace_job = job
    return job.start() if start else job


def cancel_workspace(app: App) -> None:
    """Cancel the running workspace job (it stops at its next batch)."""
    job = app.analysis.workspace_job
    if job is not None:
        job.cancel()


# ---------------------------------------------------------------------- reach, view
def reach_target(app: App, target: str) -> PointReach:
    """Point reach of scene site ``target`` with the chosen hand (the figure's posture is kept),
    collision-aware against the scene's CAD objects (issue 16: reached / reached only by touching
    X / blocked by X / short by N cm; the hand may touch the target's own object)."""
    from jackpy.analysis import point_reach
    from jackpy.scene.cad import CADObject

    fig = app.figure_of_interest()
    points = scene_targets(app.env)
    if fig is None or target not in points:
        raise JackpyError(f"no figure or no site {target!r}")
    state = app.analysis
    state.reach_target = target
    objects = [f for f in app.env.figures.values() if isinstance(f, CADObject)]
    owner = target.split(".", 1)[0]
    state.reach = point_reach(fig, points[target], state.hand, obstacles=objects,
                              target_object=owner if any(o.name == owner for o in objects) else None)
    app.info(f"reach {target}: {state.reach.describe()}")
    return state.reach


def apply_reach(app: App) -> None:
    """Put the figure in the last point reach's posture (one undo step)."""
    r = app.analysis.reach
    fig = app.figure_of_interest()
    if r is None or fig is None:
        return

    def act() -> None:
        if r.posture is not None:  # group angles too (the shoulder complex), so a later IK starts there
            r.posture.apply(fig)
        else:
            fig.q = r.q
    app.command(f"reach {app.analysis.reach_target}", act)


def view_targets(env: Environment) -> list[str]:
    """What visibility can be measured of: every object with geometry, then every named site."""
    return [o.name for o in scene_objects(env)] + list(scene_targets(env))


def measure_visibility(app: App, target: str, size: tuple[int, int] = (256, 256)) -> Visibility:
    """Visible fraction of ``target`` (an object or ``object.site``) from the figure's eyes, and what
    hides it, rendered on the app's own GL context (main thread)."""
    from jackpy.analysis import (
        eye_view,
        figure_bodies,
        object_visibility,
        point_visibility,
    )
    from jackpy.render.bodies import BodyRenderer as OffscreenRenderer

    fig = app.figure_of_interest()
    if fig is None:
        raise JackpyError("no figure")
    ev = eye_view(fig)
    objects = {o.name: o for o in scene_objects(app.env)}
    points = scene_targets(app.env)
    obj_name = target if target in objects else target.split(".", 1)[0]
    if obj_name not in objects:
        raise JackpyError(f"nothing named {target!r} to look at")
    others = [b for o in objects.values() if o.name != obj_name for b in figure_bodies(o)]
    others += figure_bodies(fig, ev.position)
    ctx = app.renderer.ctx if app.renderer is not None else None
    renderer = OffscreenRenderer(size, ctx=ctx)
    try:
        if target in objects:
            v = object_visibility(renderer, ev.position, figure_bodies(objects[target]), others, target)
        else:
            v = point_visibility(renderer, ev.position, points[target], others + figure_bodies(objects[obj_name]), target)
    finally:
        renderer.release()
    app.analysis.visibility = v
    return v


# ---------------------------------------------------------------------- report
class MainThreadRenderer:
    """Stands in for :class:`jackpy.render.bodies.BodyRenderer` on a worker thread: each
    call is posted to the main thread (where the window's context is current) and awaited."""

    def __init__(self, state: AnalysisState, ctx, size: tuple[int, int]) -> None:
        self.state, self.ctx, self.size = state, ctx, size
        self._r = None

    def _call(self, method: str, *args, **kwargs):
        box: dict[str, Any] = {}
        done = threading.Event()

        def work() -> None:
            try:
                if self._r is None and method != "release":
                    from jackpy.render.bodies import BodyRenderer as OffscreenRenderer

                    self._r = OffscreenRenderer(self.size, ctx=self.ctx)
                if self._r is not None:
                    box["value"] = getattr(self._r, method)(*args, **kwargs)
                if method == "release":
                    self._r = None
            except BaseException as exc:  # hand it to the worker
                box["error"] = exc
            finally:
                done.set()

        if threading.get_ident() == self.state.main_thread:
            work()
        else:
            self.state.post(work)
            while not done.wait(0.05):
                if self.state.closed:
                    raise JackpyError("the window closed during the report")
        if "error" in box:
            raise box["error"]
        return box.get("value")

    def render_ids(self, *args, **kwargs):
        return self._call("render_ids", *args, **kwargs)

    def render(self, *args, **kwargs):
        return self._call("render", *args, **kwargs)

    def release(self) -> None:
        self._call("release")


def workplace_from_app(app: App, reach: list[str] | None = None, view: list[str] | None = None):
    """A :class:`jackpy.scene.workplace.Workplace` of the app's scene: copies of its objects, the
    figure's standing place and heading, and the analysis plan (default: every CAD site to reach,
    every CAD object to look at; the panel's hand and load)."""
    from jackpy.scene.cad import CADObject
    from jackpy.scene.workplace import AnalysisPlan, Stand, Workplace

    env = Environment()
    for fig in app.env.figures.values():
        if not fig.joints:
            env.add(copy.deepcopy(fig))
    stand = Stand()
    fig = app.figure_of_interest()
    if fig is not None:
        loc = fig.location
        fwd = loc[:3, :3] @ np.array([0.0, 0.0, 1.0])
        stand = Stand((float(loc[0, 3]), float(loc[2, 3])), float(np.arctan2(fwd[0], fwd[2])))
    cad = [n for n, f in env.figures.items() if isinstance(f, CADObject)]
    if reach is None:
        reach = [t for t in scene_targets(env) if t.split(".", 1)[0] in cad]
    if view is None:
        view = list(cad)
    state = app.analysis
    return Workplace(env, stand, AnalysisPlan(reach, view, state.load_kg, state.hand))


class ReportJob(Job):
    """``write_report`` for the app's scene on a worker thread."""

    def __init__(self, app: App, folder: Path, figures: list[tuple[str, float]], resolution: int,
                 make_figure: Callable | None = None) -> None:
        from jackpy.analysis.report import Options

        super().__init__()
        self.wp = workplace_from_app(app)
        self.folder = Path(folder)
        self.opts = Options(figures, self.wp.plan.reach, self.wp.plan.view, self.wp.plan.load_kg,
                            self.wp.plan.hand, resolution)
        self.make_figure = make_figure
        self.renderer = (MainThreadRenderer(app.analysis, app.renderer.ctx, _picture_size())
                         if app.renderer is not None else None)

    def _progress(self, fraction: float, what: str) -> None:
        self.progress, self.message = fraction, what

    def run(self) -> Path:
        from jackpy.analysis.report import write_report

        kwargs = {"make_figure": self.make_figure} if self.make_figure is not None else {}
        try:
            write_report(self.wp, self.opts, self.folder, renderer=self.renderer, progress=self._progress, **kwargs)
        finally:
            if self.renderer is not None:
                self.renderer.release()
        self.message = f"wrote {self.folder / 'report.html'}"
        return self.folder / "report.html"


def _picture_size() -> tuple[int, int]:
    from jackpy.analysis.report import PICTURE_SIZE

    return PICTURE_SIZE


def start_report(app: App, folder: str | Path, figures: str = "female:5,male:95",
                 resolution: int | None = None, make_figure: Callable | None = None) -> ReportJob:
    """One click: write ``report.html`` (and results.json/csv, pictures) for the current scene into
    ``folder``. ``figures`` as ``jackpy analyze --figures``."""
    from jackpy.analysis.report import parse_figures

    state = app.analysis
    if state.report_job is not None and not state.report_job.done:
        raise JackpyError("a report is already being written")
    job = ReportJob(app, Path(folder).expanduser(), parse_figures(figures),
                    resolution or max(state.resolution, 16), make_figure)
    state.report_job = job
    app.info(f"report into {job.folder}")
    return job.start()


# ---------------------------------------------------------------------- imgui
DEFAULTS = {"target": 0, "clear": 0, "view": 0, "folder": "report", "figures": "female:5,male:95", "open_all": False}
"""The panel's widget state (in the UI state, ``ui.panel_state("Analysis")``); ``open_all`` opens
every section (tests)."""


def _header(w: dict, label: str, default_open: bool = False) -> bool:
    from imgui_bundle import imgui

    if w["open_all"]:
        imgui.set_next_item_open(True)
    return imgui.collapsing_header(label, imgui.TreeNodeFlags_.default_open if default_open else 0)


def _combo(w: dict, label: str, key: str, items: list[str]) -> str | None:
    from imgui_bundle import imgui

    if not items:
        imgui.text_disabled(f"{label}: none in the scene")
        return None
    w[key] = min(w[key], len(items) - 1)
    w[key] = imgui.combo(label, w[key], items)[1]
    return items[w[key]]


def _progress_row(job: Job | None, cancel: Callable[[], None] | None) -> bool:
    """Progress bar (and Cancel) of a running job; True while it runs."""
    from imgui_bundle import imgui

    if job is None:
        return False
    if not job.done:
        imgui.progress_bar(job.progress, (-70 if cancel else -1, 0), job.message or "...")
        if cancel is not None:
            imgui.same_line()
            if imgui.button("Cancel"):
                cancel()
        return True
    if job.error:
        imgui.text_colored((1.0, 0.4, 0.3, 1.0), job.error)
    elif job.message:
        imgui.text_disabled(job.message)
    return False


def _run(app: App, action: Callable[[], object]) -> None:
    try:
        action()
    except (JackpyError, ValueError, OSError) as exc:
        app.info(f"error: {exc}")


def draw(app: App, ui: UiState) -> None:
    from imgui_bundle import imgui

    state: AnalysisState = app.analysis
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((vp.size.x - 600, 30), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((300, 560), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Analysis"] = imgui.begin("Analysis", ui.open_panels["Analysis"])
    w = ui.panel_state("Analysis", DEFAULTS)
    state.strength_live = False
    if visible:
        fig = app.figure_of_interest()
        if fig is None:
            imgui.text_disabled("No figure.")
        else:
            imgui.text(f"figure: {fig.name}")
            imgui.set_next_item_width(90)
            state.hand = HANDS[imgui.combo("hand", HANDS.index(state.hand), HANDS)[1]]
            _reach_section(app, state, w)
            _strength_section(app, state, w)
            _clearance_section(app, state, w)
            _view_section(app, state, ui, w)
            _report_section(app, state, w)
    imgui.end()


def _reach_section(app: App, state: AnalysisState, w: dict) -> None:
    from imgui_bundle import imgui

    if not _header(w, "Reach##section", True):
        return
    imgui.set_next_item_width(120)
    state.resolution = imgui.slider_int("resolution", state.resolution, 8, 96)[1]
    if not _progress_row(state.workspace_job, lambda: cancel_workspace(app)):
        if imgui.button("Compute workspace"):
            _run(app, lambda: start_workspace(app))
    ws = state.workspace
    if ws is not None:
        imgui.same_line()
        state.show_workspace = imgui.checkbox("show", state.show_workspace)[1]
        imgui.text(f"{ws.hand} hand: {ws.workspace.volume() * 1000:.0f} litres")
        for name, (inside, dist) in ws.sites.items():
            if inside:
                imgui.text_colored((0.4, 1.0, 0.5, 1.0), f"  {name}: inside")
            else:
                imgui.text_colored((1.0, 0.5, 0.4, 1.0), f"  {name}: outside by {dist * 100:.0f} cm")
    imgui.separator()
    target = _combo(w, "site", "target", list(scene_targets(app.env)))
    if target is not None:
        if imgui.button("Reach"):
            _run(app, lambda: reach_target(app, target))
        if state.reach is not None:
            imgui.same_line()
            if imgui.button("Apply posture"):
                apply_reach(app)
            imgui.same_line()
            if imgui.small_button("clear"):
                state.reach = None
        if state.reach is not None:
            imgui.text(f"{state.reach_target}: {state.reach.describe()}")


def _strength_section(app: App, state: AnalysisState, w: dict) -> None:
    from imgui_bundle import imgui

    from jackpy.analysis import strength_colour
    from jackpy.ui.names import dof_key_label

    if not _header(w, "Strength##section"):
        return
    state.strength_live = True
    imgui.set_next_item_width(120)
    state.load_kg = max(0.0, imgui.drag_float("load in hand (kg)", state.load_kg, 0.1, 0.0, 100.0, "%.1f")[1])
    state.torque_colouring = imgui.checkbox("colour body by torque", state.torque_colouring)[1]
    if state.strength_error:
        imgui.text_disabled(state.strength_error)
    s = state.strength
    if s is None:
        return
    for bar in s.bars:
        u = bar.required / bar.strength if bar.strength > 0 else (np.inf if bar.required > 0 else 0.0)
        r, g, b = strength_colour(min(u, 2.0))
        imgui.push_style_color(imgui.Col_.plot_histogram, imgui.ImVec4(float(r), float(g), float(b), 1.0))
        imgui.text(dof_key_label(bar.dof))  # its own line: never clipped by the bar
        imgui.progress_bar(float(min(u, 1.0)), (-1, 0),
                           f"{bar.required:.0f} / {bar.strength:.0f} N m ({100 * u:.0f}%)")
        imgui.pop_style_color()


def _clearance_section(app: App, state: AnalysisState, w: dict) -> None:
    from imgui_bundle import imgui

    if not _header(w, "Clearance##section"):
        return
    state.clearance_on = imgui.checkbox("live clearance and collisions", state.clearance_on)[1]
    names = [o.name for o in scene_objects(app.env)]
    chosen = _combo(w, "object", "clear", names)
    if chosen is not None:
        state.clearance_object = chosen
    if not state.clearance_on:
        return
    if state.clearance_error:
        imgui.text_disabled(state.clearance_error)
    c = state.clearance
    if c is not None:
        imgui.text(f"clearance {c.distance * 100:.1f} cm ({c.segment})")
    if state.colliding:
        imgui.text_colored((1.0, 0.3, 0.25, 1.0), "colliding: " + ", ".join(sorted(state.colliding)))


def _view_section(app: App, state: AnalysisState, ui: UiState, w: dict) -> None:
    from imgui_bundle import imgui

    if not _header(w, "View##section"):
        return
    state.show_cones = imgui.checkbox("view cones", state.show_cones)[1]
    imgui.same_line()
    ui.open_panels["Eye view"] = imgui.checkbox("eye view", bool(ui.open_panels.get("Eye view")))[1]
    target = _combo(w, "target", "view", view_targets(app.env))
    if target is not None and imgui.button("Measure visibility"):
        _run(app, lambda: measure_visibility(app, target))
    v = state.visibility
    if v is not None:
        imgui.text(f"{v.target}: {100 * v.fraction:.0f}% visible")
        for name, share in v.occluders.items():
            imgui.text(f"  hidden by {name} ({100 * share:.0f}%)")


def _report_section(app: App, state: AnalysisState, w: dict) -> None:
    from imgui_bundle import imgui

    if not _header(w, "Report##section"):
        return
    imgui.set_next_item_width(180)
    w["folder"] = imgui.input_text("folder", w["folder"])[1]
    imgui.set_next_item_width(180)
    w["figures"] = imgui.input_text("figures", w["figures"])[1]
    if not _progress_row(state.report_job, None):
        if imgui.button("Report..."):
            _run(app, lambda: start_report(app, w["folder"], w["figures"]))


PANEL = Panel("Analysis", draw, order=60)
