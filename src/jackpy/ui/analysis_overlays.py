"""What the analyses (:mod:`jackpy.analysis`) add to the workbench's 3-D view, and the state behind it.

The overlay builders are pure functions from analysis results to extra draw data, so that they
can be rendered and checked offscreen:

- :func:`workspace_items`: the reachable workspace's surface as one translucent item;
- :func:`view_cone_items`: translucent view cones from the eyes (half-angles below 90 degrees;
  the 94-degree peripheral field is not a cone and is not drawn);
- :func:`segment_strength_colours`: one colour per segment from joint utilisation (white -> blue
  at full strength -> red beyond, :func:`jackpy.analysis.strength_colour`), the largest utilisation
  of the joints the segment touches;
- :func:`recolour_items`: the frame's segment items with some segments recoloured (strength
  colouring, red colliding segments);
- :func:`reach_lines`, :func:`clearance_lines`: feedback lines.

:class:`AnalysisState` (``app.analysis``) holds what the Analysis panel chose and computed, keeps the
live analyses (strength, clearance) current each frame, runs callbacks posted by worker threads on
the main thread (:meth:`AnalysisState.post`; GL work of the report must run where the window's
context is current), and decorates each frame's scene (:meth:`AnalysisState.decorate`).
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.peabody import Environment, Figure
from jackpy.ui.render import DrawItem, Lines, Scene
from jackpy.ui.render.mesh import Mesh as RenderMesh
from jackpy.ui.render.mesh import lathe

if TYPE_CHECKING:
    from jackpy.analysis import Clearance, EyeView, PointReach, Visibility, Workspace
    from jackpy.ui.app import App

WORKSPACE_MESH = "analysis:workspace"
CONE_MESH = "analysis:cone"
WORKSPACE_COLOUR = (0.25, 0.55, 1.0, 0.3)
COLLISION_COLOUR = (0.95, 0.08, 0.06, 1.0)
CONE_COLOURS: dict[str, tuple[float, float, float, float]] = {
    "optimum": (0.2, 0.9, 0.3, 0.22),
    "maximum eye rotation": (1.0, 0.85, 0.2, 0.16),
    "binocular": (0.85, 0.35, 1.0, 0.12),
}
"""Colours of the drawn view cones, by :data:`jackpy.analysis.VIEW_CONES` name."""
CONE_LENGTH = 0.6
"""Length of the drawn view cones along the gaze (m)."""


# ---------------------------------------------------------------------- pure overlay builders
def unit_cone() -> RenderMesh:
    """A cone with its apex at the origin opening along +y: rim radius 1 at y = 1, closed by a
    base disc; outward winding (for the transparent pass)."""
    return lathe([(0.0, 0.0), (1.0, 1.0), (0.0, 1.0)], sectors=48)


def _frame_along(direction: np.ndarray) -> np.ndarray:
    """A rotation whose +y column is ``direction`` (unit)."""
    y = np.asarray(direction, float) / np.linalg.norm(direction)
    helper = np.array([1.0, 0.0, 0.0]) if abs(y[0]) < 0.9 else np.array([0.0, 0.0, 1.0])
    x = np.cross(y, helper)
    x /= np.linalg.norm(x)
    z = np.cross(x, y)
    return np.column_stack([x, y, z])


def view_cone_items(eye: EyeView, length: float = CONE_LENGTH,
                    colours: Mapping[str, tuple[float, float, float, float]] = CONE_COLOURS) -> list[DrawItem]:
    """Translucent cones of :data:`jackpy.analysis.VIEW_CONES` (those in ``colours``, below 90
    degrees) with their apex at the eye point along the gaze, ``length`` m long, widest first."""
    from jackpy.analysis import VIEW_CONES

    items = []
    rot = _frame_along(eye.forward)
    for name, half in reversed(VIEW_CONES):
        if name not in colours or half >= np.radians(89.0):
            continue
        r = length * np.tan(half)
        t = np.eye(4)
        t[:3, :3] = rot @ np.diag([r, length, r])
        t[:3, 3] = eye.position
        items.append(DrawItem(CONE_MESH, t, colours[name], transparent=True))
    return items


def workspace_mesh(surface) -> RenderMesh:
    """The renderer mesh of a workspace surface (:meth:`jackpy.analysis.Workspace.surface`)."""
    return RenderMesh.from_triangles(surface.vertices, surface.faces)


def workspace_items(key: str = WORKSPACE_MESH, colour=WORKSPACE_COLOUR) -> list[DrawItem]:
    """The translucent envelope: one item of the uploaded workspace mesh (world coordinates)."""
    return [DrawItem(key, np.eye(4), colour, transparent=True)]


def segment_strength_colours(figure: Figure, joint_util: Mapping[str, float]) -> dict[str, tuple[float, ...]]:
    """``segment -> RGBA``: each segment coloured by the largest utilisation among the joints it
    touches (segments touching no joint with data: white)."""
    from jackpy.analysis import strength_colour

    worst: dict[str, float] = {s: 0.0 for s in figure.segments}
    for j in figure.joints.values():
        u = joint_util.get(j.name, float("nan"))
        if np.isnan(u):
            continue
        for s in (j.from_seg, j.to_seg):
            worst[s] = max(worst[s], float(u))
    return {s: tuple(float(c) for c in strength_colour(u)) + (1.0,) for s, u in worst.items()}


def recolour_items(items: Iterable[DrawItem], figure: str, colours: Mapping[str, Any],
                   mesh_key: Callable[[str, str], str]) -> list[DrawItem]:
    """``items`` with the segments of ``figure`` named in ``colours`` drawn in that colour (the
    items are matched by ``mesh_key(figure, segment)``); other items unchanged."""
    by_key = {mesh_key(figure, s): c for s, c in colours.items()}
    return [replace(it, color=tuple(by_key[it.mesh])) if it.mesh in by_key else it for it in items]


def reach_lines(result: PointReach) -> list[Lines]:
    """A line from the hand (after the reach) to the target: green when reached, red when short."""
    colour = (0.2, 0.95, 0.3, 1.0) if result.reached else (1.0, 0.25, 0.2, 1.0)
    seg = np.array([[result.position, result.target]], float)
    return [Lines(seg, colour, on_top=True)]


def clearance_lines(c: Clearance) -> list[Lines]:
    """The nearest points of a clearance query joined by a line."""
    return [Lines(np.array([[c.point_on_segment, c.point_on_body]], float), (1.0, 0.9, 0.2, 1.0), on_top=True)]


# ---------------------------------------------------------------------- scene targets
def scene_targets(env: Environment) -> dict[str, np.ndarray]:
    """World points (m) of the named sites of the environment's objects: ``object.site`` for CAD
    objects' own sites, ``figure.site`` for the sites of other unjointed figures (chair, table)."""
    from jackpy.scene.cad import CADObject

    out: dict[str, np.ndarray] = {}
    for name, fig in env.figures.items():
        if fig.joints:
            continue
        if isinstance(fig, CADObject):
            for site in fig.user_sites():
                out[f"{name}.{site}"] = np.asarray(fig.site_position(site), float)
            continue
        for seg in fig.segments.values():
            for site in seg.sites:
                out.setdefault(f"{name}.{site}", fig.site_world(seg.name, site)[:3, 3].copy())
    return out


def scene_objects(env: Environment) -> list[Figure]:
    """The environment's unjointed figures that carry geometry (CAD objects, chairs, tables)."""
    out = []
    for fig in env.figures.values():
        if fig.joints:
            continue
        if any(s.psurf is not None and s.psurf.mesh is not None and len(s.psurf.mesh.faces) for s in fig.segments.values()):
            out.append(fig)
    return out


# ---------------------------------------------------------------------- state
@dataclass
class WorkspaceResult:
    """A finished reachable-workspace job: the voxels, their surface, and the classified sites
    (``name -> (inside, distance m)``)."""

    workspace: Workspace
    surface: Any
    sites: dict[str, tuple[bool, float]]
    figure: str
    hand: str
    version: int = 0


@dataclass
class StrengthReadout:
    """Live strength: DOF torques (N m), utilisation, per-joint utilisation, bars of the hand's chain."""

    torques: np.ndarray
    utilisation: np.ndarray
    joints: dict[str, float]
    bars: list
    segment_colours: dict[str, tuple[float, ...]]


@dataclass
class AnalysisState:
    """The analysis choices and results of the workbench (``app.analysis``)."""

    hand: str = "right"
    resolution: int = 32
    workspace: WorkspaceResult | None = None
    show_workspace: bool = True
    workspace_job: Any = None
    load_kg: float = 0.0
    strength_live: bool = False
    """Compute strength each frame (the panel sets it while its section is open)."""
    torque_colouring: bool = False
    strength: StrengthReadout | None = None
    strength_error: str | None = None
    clearance_on: bool = False
    clearance_object: str | None = None
    clearance: Clearance | None = None
    colliding: set[str] = field(default_factory=set)
    clearance_error: str | None = None
    show_cones: bool = False
    eye_view_open: bool = False
    reach_target: str | None = None
    reach: PointReach | None = None
    visibility: Visibility | None = None
    report_job: Any = None
    _main_queue: queue.Queue[Callable[[], None]] = field(default_factory=queue.Queue)
    _checker: Any = None
    _checker_key: tuple = ()
    _live_key: tuple = ()
    _tables: dict = field(default_factory=dict)
    _uploaded: dict = field(default_factory=dict)
    _eye: Any = None
    closed: bool = False
    main_thread: int = field(default_factory=threading.get_ident)

    # ------------------------------------------------------------------ main-thread work
    def post(self, fn: Callable[[], None]) -> None:
        """Run ``fn`` on the main thread at the next frame (from worker threads)."""
        self._main_queue.put(fn)

    def pump(self) -> None:
        """Run the callbacks posted by workers (the window calls this once a frame via ``draw``)."""
        while True:
            try:
                fn = self._main_queue.get_nowait()
            except queue.Empty:
                return
            fn()

    # ------------------------------------------------------------------ live analyses
    def figure(self, app: App) -> Figure | None:
        """The analysed figure: the app's figure of interest."""
        return app.figure_of_interest()

    def strength_table(self, figure: Figure):
        """The figure's strength table (cached per figure object); raises when it has none."""
        key = id(figure)
        if key not in self._tables:
            from jackpy.analysis import dof_strengths
            from jackpy.body.strength import strength_table

            try:
                self._tables[key] = (figure, dof_strengths(strength_table(figure)), None)
            except Exception as exc:  # synthetic figures have no body specification
                self._tables[key] = (figure, None, f"{exc}")
        _, table, error = self._tables[key]
        if table is None:
            raise LookupError(error)
        return table

    def update_strength(self, figure: Figure) -> None:
        """Torques and utilisation at the figure's posture holding ``load_kg`` in the chosen hand."""
        from jackpy.analysis import (
            Chain,
            Load,
            figure_parts,
            joint_torques,
            joint_utilisation,
            strength_bars,
            utilisation,
        )

        try:
            table = self.strength_table(figure)
            hand = figure_parts(figure).hands[self.hand]
        except Exception as exc:
            self.strength, self.strength_error = None, f"strength not available: {exc}"
            return
        loads = [Load.held_mass(figure, hand.segment, hand.site, self.load_kg)] if self.load_kg > 0 else []
        tau = joint_torques(figure, loads)
        util = utilisation(figure, tau, table)
        ju = joint_utilisation(figure, util)
        names = figure.dof_names()
        chain = Chain(figure, hand.start_joint, hand.segment, np.zeros(3))
        arm = [names[i] for i in chain.dofs if names[i] in table]
        self.strength = StrengthReadout(tau, util, ju, strength_bars(figure, tau, table, arm),
                                        segment_strength_colours(figure, ju))
        self.strength_error = None

    def update_clearance(self, app: App, figure: Figure) -> None:
        """Rebuild the checker when the figure or objects changed, then query this posture."""
        from jackpy.analysis import ClearanceChecker

        objects = [o for o in scene_objects(app.env) if o is not figure]
        key = (id(figure), tuple(id(o) for o in objects))
        try:
            if self._checker is None or key != self._checker_key:
                self._checker = ClearanceChecker(figure, objects)
                self._checker_key = key
            chk = self._checker
            chk.update()
            self.colliding = chk.colliding_segments()
            names = [o.name for o in objects]
            if self.clearance_object not in names:
                self.clearance_object = names[0] if names else None
            self.clearance = chk.clearance(self.clearance_object) if self.clearance_object else None
            self.clearance_error = None
        except Exception as exc:  # no python-fcl, no geometry on the figure
            self.clearance, self.colliding, self.clearance_error = None, set(), f"{exc}"

    def refresh(self, app: App) -> None:
        """Bring the live analyses up to date when the posture, placements or choices changed."""
        fig = self.figure(app)
        if fig is None:
            self.strength, self.clearance, self.colliding = None, None, set()
            return
        want_strength = self.strength_live or self.torque_colouring
        state = [fig.q.tobytes(), fig.location.tobytes(), id(fig), self.load_kg, self.hand,
                 want_strength, self.clearance_on, self.clearance_object]
        if self.clearance_on:
            state += [o.location.tobytes() for o in app.env.figures.values() if not o.joints]
            state.append(len(app.env.figures))
        key = tuple(state)
        if key == self._live_key:
            return
        self._live_key = key
        if want_strength:
            self.update_strength(fig)
        if self.clearance_on:
            self.update_clearance(app, fig)
        else:
            self.clearance, self.colliding = None, set()

    # ------------------------------------------------------------------ per frame
    def upload(self, renderer, key: str, mesh: RenderMesh, version: object) -> None:
        """Upload an overlay mesh once per ``version``."""
        if self._uploaded.get((id(renderer), key)) != version or not renderer.has_mesh(key):
            renderer.add_mesh(key, mesh, replace=True)
            self._uploaded[(id(renderer), key)] = version

    def overlay(self, app: App, scene: Scene, renderer) -> Scene:
        """Add the analyses' draw data to ``scene`` (in place; returned) and upload their meshes."""
        fig = self.figure(app)
        if fig is None:
            return scene
        if self.torque_colouring and self.strength is not None:
            scene.items = recolour_items(scene.items, fig.name, self.strength.segment_colours, app.view.mesh_key)
        if self.clearance_on and self.colliding:
            scene.items = recolour_items(scene.items, fig.name, {s: COLLISION_COLOUR for s in self.colliding},
                                         app.view.mesh_key)
        if self.clearance_on and self.clearance is not None and self.clearance.distance > 0:
            scene.lines.extend(clearance_lines(self.clearance))
        if self.reach is not None:
            scene.lines.extend(reach_lines(self.reach))
        if self.show_workspace and self.workspace is not None:
            self.upload(renderer, WORKSPACE_MESH, workspace_mesh(self.workspace.surface), self.workspace.version)
            scene.items.extend(workspace_items())
        if self.show_cones:
            from jackpy.analysis import eye_view

            try:
                ev = eye_view(fig)
            except Exception:
                ev = None
            if ev is not None:
                self.upload(renderer, CONE_MESH, unit_cone(), 1)
                scene.items.extend(view_cone_items(ev))
        return scene

    def decorate(self, app: App, scene: Scene) -> Scene:
        """Per frame, before the main render: run posted work, refresh live analyses, add overlays."""
        self.pump()
        self.refresh(app)
        return self.overlay(app, scene, app.renderer)

    def after_draw(self, app: App) -> None:
        """Per frame, after the main render: the eye view (when its window is open)."""
        if self.eye_view_open and app.renderer is not None:
            from jackpy.ui.eye_view import EyeViewport

            if self._eye is None:
                self._eye = EyeViewport()
            self._eye.render(app)

    @property
    def eye_viewport(self):
        """The eye view's :class:`~jackpy.ui.eye_view.EyeViewport` (``None`` until first drawn)."""
        return self._eye
