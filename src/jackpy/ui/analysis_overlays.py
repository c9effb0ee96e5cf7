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

:class:`AnalysisState` (``app.analysis``) holds what the Analysis panel chose and computed on top of
the document's live analyses (strength, clearance: refreshed by ``Document.step`` after the solve,
never in the draw), runs callbacks posted by worker threads on the main thread
(:meth:`AnalysisState.post`; GL work of the report must run where the window's context is current),
and decorates each frame's scene with overlays (:meth:`AnalysisState.decorate`).
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.document.analyses import (  # noqa: F401  (re-exported: the panels' names)
    LiveAnalyses,
    StrengthReadout,
    figure_of_interest,
    scene_objects,
    segment_strength_colours,
)
from jackpy.peabody import Environment, Figure
from jackpy.render import DrawItem, Lines, Scene
from jackpy.render.mesh import Mesh as RenderMesh
from jackpy.render.mesh import lathe

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
class AnalysisState(LiveAnalyses):
    """The analysis choices and results of the workbench (``app.analysis``): the document's live
    analyses (:class:`~jackpy.document.analyses.LiveAnalyses`, refreshed by ``Document.step``)
    plus the Analysis panel's jobs, overlay switches and main-thread queue."""

    resolution: int = 32
    workspace: WorkspaceResult | None = None
    show_workspace: bool = True
    workspace_job: Any = None
    show_cones: bool = False
    eye_view_open: bool = False
    reach_target: str | None = None
    reach: PointReach | None = None
    visibility: Visibility | None = None
    report_job: Any = None
    highlight_colours: dict = field(default_factory=dict)
    """Segment name -> RGBA drawn over the figure of interest (the Ergonomics panel's worst part)."""
    _main_queue: queue.Queue[Callable[[], None]] = field(default_factory=queue.Queue)
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

    def figure(self, app: App) -> Figure | None:
        """The analysed figure: the document's figure of interest."""
        return figure_of_interest(app.env)

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
        if self.highlight_colours:
            scene.items = recolour_items(scene.items, fig.name, self.highlight_colours, app.view.mesh_key)
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
        """Per frame, before the main render: run posted work, add the overlays of the results
        (the live analyses were refreshed by ``Document.step``, not here)."""
        self.pump()
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
