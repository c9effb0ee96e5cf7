"""Figures and environments as the renderer's plain draw data (``render.Scene``), with picking ids.

The view reads state and never owns it: each frame it runs forward kinematics of every figure and
emits one :class:`~jackpy.render.DrawItem` per segment (its psurf mesh, or a box around its sites
when it has none) or, in skeleton mode, balls at the joints and sticks between them. Meshes are
uploaded to the renderer once and re-uploaded only when a segment's geometry changes (a rescale).

Pick ids are small positive integers: one per ``(figure, segment)`` and one per goal marker; the
renderer reports them back from its id buffer and :meth:`SceneView.pick_target` names the thing.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol

import numpy as np

from jackpy.peabody import Environment, Figure, Segment
from jackpy.scene.cad import CADObject
from jackpy.body.skin import bone_matrices, skins_for
from jackpy.render import DrawItem, GoalMarker, Lines, Scene, SkinnedItem, SkinnedMesh, Spheres, Sticks, Triad
from jackpy.render.mesh import Mesh as RenderMesh

if TYPE_CHECKING:
    from jackpy.render import Renderer

FIGURE_COLOR = (0.86, 0.70, 0.58, 1.0)
OBJECT_COLOR = (0.62, 0.64, 0.68, 1.0)
CAD_COLOR = (0.55, 0.65, 0.80, 0.45)
GOAL_COLOR = (1.0, 0.35, 0.1, 1.0)
GOAL_DISABLED_COLOR = (0.5, 0.5, 0.5, 1.0)
TERRAIN_MESH = "terrain"
"""Mesh key of the document's terrain (see :meth:`SceneView.add_terrain`)."""
GOAL_PICK_BASE = 1_000_000
"""Goal markers get pick ids from here on; segments count up from 1."""

ATTRIBUTE_COLORS: dict[str, tuple[float, float, float, float]] = {
    "red": (0.8, 0.2, 0.2, 1.0), "green": (0.3, 0.7, 0.3, 1.0), "blue": (0.3, 0.4, 0.85, 1.0),
    "yellow": (0.9, 0.8, 0.3, 1.0), "white": (0.92, 0.92, 0.92, 1.0), "black": (0.15, 0.15, 0.15, 1.0),
    "grey": (0.6, 0.6, 0.6, 1.0), "gray": (0.6, 0.6, 0.6, 1.0), "brown": (0.55, 0.38, 0.22, 1.0),
    "wood": (0.62, 0.45, 0.28, 1.0), "skin": FIGURE_COLOR, "metal": (0.7, 0.72, 0.76, 1.0),
}
"""Display colours of Peabody segment ``attribute`` names (anything else: the default colours)."""


@dataclass(frozen=True)
class SegmentPick:
    """A picked segment of a figure."""

    figure: str
    segment: str


@dataclass(frozen=True)
class GoalPick:
    """A picked goal marker, by the goal's key."""

    key: str


PickTarget = SegmentPick | GoalPick


class GoalView(Protocol):
    """What the view needs of a goal to draw its marker."""

    key: str
    enabled: bool

    def marker_position(self) -> np.ndarray: ...


@dataclass
class Overlay:
    """Operator feedback drawn on top: the manipulation frame, lines (wheel, spoke, red sector)."""

    triads: list[Triad] = field(default_factory=list)
    lines: list[Lines] = field(default_factory=list)


def segment_mesh(segment: Segment, figure: Figure | None = None,
                 max_triangles: int | None = None) -> RenderMesh:
    """The segment's mesh in its base frame: a CAD object's display copy (at most
    ``max_triangles``, default the object's own display budget), the posed psurf, or a box
    around its sites (m)."""
    if isinstance(figure, CADObject):
        posed = figure.display_mesh() if max_triangles is None else figure.display_mesh(max_triangles)
    else:
        posed = segment.psurf.posed_mesh() if segment.psurf is not None else None
    if posed is not None and len(posed.faces):
        return RenderMesh.from_triangles(posed.vertices, posed.faces)
    return _site_box(segment)


def _site_box(segment: Segment) -> RenderMesh:
    from jackpy.render.mesh import box

    pts = np.array([s.location[:3, 3] for s in segment.sites.values()] or [np.zeros(3)])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    size = np.maximum(hi - lo, 0.0) + 0.035
    m = box(tuple(size))
    return RenderMesh(m.vertices + 0.5 * (lo + hi), m.normals, m.indices)


def _geometry_key(segment: Segment) -> tuple:
    """Changes whenever what :func:`segment_mesh` returns would change."""
    ps = segment.psurf
    if ps is None or ps.mesh is None:
        return ("sites", tuple(s.location[:3, 3].round(9).tobytes() for s in segment.sites.values()))
    return ("psurf", id(ps.mesh), len(ps.mesh.vertices), ps.transform.round(12).tobytes())


def is_object(figure: Figure) -> bool:
    """A figure without joints (a chair, a table, CAD) rather than an articulated figure."""
    return not figure.joints


class SceneView:
    """Builds the renderer's :class:`Scene` for an environment and resolves pick ids."""

    def __init__(self) -> None:
        self._segment_ids: dict[tuple[str, str], int] = {}
        self._targets: dict[int, PickTarget] = {}
        self._geometry: dict[str, tuple] = {}

    # ------------------------------------------------------------------ picking ids
    def segment_pick_id(self, figure: str, segment: str) -> int:
        """The stable pick id of a figure's segment."""
        key = (figure, segment)
        pid = self._segment_ids.get(key)
        if pid is None:
            pid = len(self._segment_ids) + 1
            self._segment_ids[key] = pid
            self._targets[pid] = SegmentPick(figure, segment)
        return pid

    def pick_target(self, pick_id: int | None) -> PickTarget | None:
        """What a pick id names (``None`` for empty space or an unknown id)."""
        if pick_id is None:
            return None
        return self._targets.get(pick_id)

    # ------------------------------------------------------------------ meshes
    def mesh_key(self, figure: str, segment: str) -> str:
        return f"fig:{figure}/{segment}"

    def skin_key(self, figure: str, index: int) -> str:
        return f"skin:{figure}/{index}"

    def upload(self, renderer: "Renderer", env: Environment) -> None:
        """Upload every segment mesh that the renderer lacks or whose geometry changed.

        CAD objects are uploaded as their display copy within the renderer's
        ``display_triangles`` budget (lower on a software rasteriser)."""
        budget = getattr(renderer, "display_triangles", None)
        for fig in env.figures.values():
            cad = isinstance(fig, CADObject)
            for seg in fig.segments.values():
                key = self.mesh_key(fig.name, seg.name)
                gkey = (_geometry_key(seg), budget if cad else None)
                if self._geometry.get(key) == gkey and renderer.has_mesh(key):
                    continue
                renderer.add_mesh(key, segment_mesh(seg, fig, budget if cad else None), replace=True)
                self._geometry[key] = gkey
            for k, skin in enumerate(() if cad else skins_for(fig)):  # a standard human's torso and limbs
                key = self.skin_key(fig.name, k)
                if self._geometry.get(key) is not skin or not renderer.has_mesh(key):
                    renderer.add_skinned_mesh(key, SkinnedMesh.of(skin), replace=True)
                    self._geometry[key] = skin

    # ------------------------------------------------------------------ scene
    def build(self, env: Environment, goals: Sequence[GoalView] = (), skeleton: bool = False,
              highlight: SegmentPick | GoalPick | None = None, overlay: Overlay | None = None,
              show_floor: bool = True) -> Scene:
        """The frame's scene: every figure posed by forward kinematics, goal markers, overlays."""
        scene = Scene()
        if not show_floor:
            scene.grid = None
        for fig in env.figures.values():
            kin = fig.kinematics()
            fk = kin.forward(fig.q, fig.location)
            hl_fig = isinstance(highlight, SegmentPick) and highlight.figure == fig.name
            if skeleton and not is_object(fig):
                self._skeleton(scene, fig, fk.segments, highlight if hl_fig else None)
                continue
            cad = isinstance(fig, CADObject)
            for i, name in enumerate(kin.segment_names):
                seg = fig.segments[name]
                color = CAD_COLOR if cad else ATTRIBUTE_COLORS.get(
                    (seg.attribute or "").lower(), OBJECT_COLOR if is_object(fig) else FIGURE_COLOR)
                scene.items.append(DrawItem(
                    self.mesh_key(fig.name, name), fk.segments[i], color,
                    pick_id=self.segment_pick_id(fig.name, name), transparent=cad,
                    highlighted=hl_fig and (is_object(fig) or highlight.segment == name)))
            for k, skin in enumerate(() if cad else skins_for(fig)):  # each stands in for its bones' items
                scene.skins.append(SkinnedItem(self.skin_key(fig.name, k), bone_matrices(skin, fk.segments,
                                                                                         kin.segment_names),
                                               bone_items=[self.mesh_key(fig.name, b) for b in skin.bones]))
        for k, g in enumerate(goals):
            pid = GOAL_PICK_BASE + k
            self._targets[pid] = GoalPick(g.key)
            selected = isinstance(highlight, GoalPick) and highlight.key == g.key
            color = (1.0, 0.8, 0.2, 1.0) if selected else GOAL_COLOR if g.enabled else GOAL_DISABLED_COLOR
            scene.markers.append(GoalMarker(np.asarray(g.marker_position(), float), color, 0.04, pick_id=pid))
        if overlay is not None:
            scene.triads.extend(overlay.triads)
            scene.lines.extend(overlay.lines)
        return scene

    def add_terrain(self, renderer: "Renderer", scene: Scene, doc: object) -> None:
        """Draw the document's terrain (:mod:`jackpy.document.terrain`), if it has one: the height
        grid shaded, forbidden footholds tinted (:mod:`jackpy.locomotion.terrain_mesh`). The terrain
        is the ground then, so the floor grid is not drawn (it would fight the terrain at y = 0)."""
        from jackpy.document.terrain import terrain_of
        from jackpy.locomotion.terrain_mesh import display_mesh

        terrain = terrain_of(doc)  # type: ignore[arg-type]
        if terrain is None:
            return
        if self._geometry.get(TERRAIN_MESH) is not terrain or not renderer.has_mesh(TERRAIN_MESH):
            renderer.add_mesh(TERRAIN_MESH, RenderMesh(*display_mesh(terrain)), replace=True)
            self._geometry[TERRAIN_MESH] = terrain
        scene.items.append(DrawItem(TERRAIN_MESH, np.eye(4), (1.0, 1.0, 1.0, 1.0)))
        scene.grid = None

    def _skeleton(self, scene: Scene, fig: Figure, W: np.ndarray, highlight: SegmentPick | None) -> None:
        kin = fig.kinematics()
        joints = list(fig.joints.values())
        n = len(kin.segment_names)
        inbound = np.empty((n, 3))
        inbound[0] = fig.location[:3, 3]
        for s in range(1, n):
            j = joints[kin.parent_joint[s]]
            seg, site = (j.to_seg, j.to_site)
            inbound[s] = (W[kin.segment_index[seg]] @ fig.site_location(seg, site))[:3, 3]
        ids = [self.segment_pick_id(fig.name, name) for name in kin.segment_names]
        has_child = np.zeros(n, bool)
        has_child[kin.parent[1:]] = True
        starts, ends, stick_ids = [], [], []
        for s in range(1, n):
            starts.append(inbound[kin.parent[s]])
            ends.append(inbound[s])
            stick_ids.append(ids[kin.parent[s]])
        for s in np.flatnonzero(~has_child):  # leaves: out to their farthest site
            seg = fig.segments[kin.segment_names[s]]
            tips = [(W[s] @ site.location)[:3, 3] for site in seg.sites.values()]
            if tips:
                far = max(tips, key=lambda p: float(np.linalg.norm(p - inbound[s])))
                if np.linalg.norm(far - inbound[s]) > 1e-4:
                    starts.append(inbound[s])
                    ends.append(far)
                    stick_ids.append(ids[s])
        colors = np.tile(np.array([0.95, 0.78, 0.35, 1.0]), (n, 1))
        if highlight is not None and (highlight.figure, highlight.segment) in self._segment_ids:
            colors[kin.segment_index[highlight.segment]] = (1.0, 0.45, 0.15, 1.0)
        scene.spheres.append(Spheres(inbound, 0.018, colors, ids))
        if starts:
            scene.sticks.append(Sticks(np.array(starts), np.array(ends), 0.009, (0.78, 0.8, 0.86, 1.0),
                                       stick_ids))
