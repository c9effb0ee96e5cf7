"""Step editor panel ([SH5] §5.2.4, Fig 5.10; issue 13): the footsteps of the figure of
interest's walk, drawn top view as seen from above (left feet blue, right feet red, the standing
feet grey, the centre site's path yellow) over the floor footprints of everything else in the
scene (CAD objects and other figures, dark grey; the outline the walker's centre must stay out of
around them), the selected footstep's controls below.

Plan a walk to a floor point (around the scene's objects, as
:func:`jackpy.locomotion.walk_to.walk_to`), then drag a footprint in the canvas to move it, or
nudge the selected one (5 cm, 5°) with the buttons; add a stride after it (a footstep of each
side, halfway between their neighbours) or delete the stride it starts (it and the next
footstep), so that the feet still alternate. The walk is re-planned from the edited footsteps at
once (the path and duration shown follow). Every edit is one document command, so Ctrl+Z undoes
it; the plan lives in the document's ``extras["walk_plans"]`` (:mod:`jackpy.locomotion.walk_plan`)
and is saved with it. "Bake" writes the walk as a motion file (baked frames, on a copy of the
figure). The imgui drawing only calls :func:`plan_to`, :func:`move_footstep`, :func:`add_stride`,
:func:`delete_stride`, :func:`press`, :func:`drag_to`, :func:`release` and :func:`bake`, which
tests drive headless or through the window. The path editor (:mod:`.path_editor`) edits the same
plan through its path points and draws with this module's :class:`View`, :func:`floor_of` and
:func:`draw_floor`.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from shapely.geometry import Polygon

from jackpy.locomotion import walk_plan
from jackpy.locomotion.walk_path import Footstep, Walk
from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.document import Document
    from jackpy.peabody.model import Figure
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Step editor"
PLANS = "walk_plans"
NUDGE = 0.05  # m
TURN = np.radians(5.0)
PICK_PX = 12.0  # a press this close (pixels) to a footprint's centre grabs it
FOOT_HALF_WIDTH = 0.045  # drawn footprint (m)
COLOURS = {"left": 0xFFE08040, "right": 0xFF4050E0}  # ABGR: blue-ish left, red-ish right
PATH_COLOUR = 0xFF40D0E0
CONTROLS_H = 60.0  # pixels kept below the canvas for the selected footstep's controls
OBJECT_COLOUR = 0xFF585858  # an object's floor footprint
KEEP_OUT_COLOUR = 0xFF8A8A8A  # the outline the walker's centre keeps out of


def defaults() -> dict[str, Any]:
    return {"selected": None, "drag": None, "goal": [0.0, 2.0], "path": "walk.motion.json", "message": "",
            "view": None, "gait": {}, "walk": None, "floor": None, "centre": None}


# ---------------------------------------------------------------------------------- the plan
def footsteps_of(doc: "Document", name: str) -> list[Footstep] | None:
    """The walk plan of figure ``name`` (None when it has none)."""
    data = doc.extras.get(PLANS, {}).get(name)
    return None if data is None else walk_plan.from_data(data, f"walk plan of {name}")


def path_of(doc: "Document", name: str) -> list[walk_plan.Point] | None:
    """The path points of figure ``name``'s walk plan (None when it has no plan or no path)."""
    return walk_plan.path_from_data(doc.extras.get(PLANS, {}).get(name), f"walk plan of {name}")


KEEP = object()  # _store's default: the plan keeps the path it has


def store(doc: "Document", name: str, steps: list[Footstep], path: Any = KEEP) -> None:
    """Set ``name``'s plan to ``steps`` (a footstep edit keeps the plan's path points; the path
    editor gives new ones; None drops them)."""
    plans = dict(doc.extras.get(PLANS, {}))
    if path is KEEP:
        path = walk_plan.path_from_data(plans.get(name))
    plans[name] = walk_plan.to_data(steps, path)
    doc.extras[PLANS] = plans


def walker(fig: "Figure | None") -> bool:
    """Whether ``fig`` walks here: a human figure (joints, a pelvis and a head), not a prop or a creature."""
    return fig is not None and bool(fig.joints) and {"pelvis", "head"} <= set(fig.segments)


def gait_of(st: dict[str, Any], fig: "Figure"):
    """The figure's gait (measured once per figure and panel)."""
    from jackpy.locomotion.walk_gait import GaitParams

    key = (fig.name, id(fig))
    if key not in st["gait"]:
        st["gait"][key] = GaitParams.for_figure(fig)
    return st["gait"][key]


class _Surface:
    """A scene figure as :mod:`jackpy.locomotion.floor_plan` reads an object: a mesh at the world
    origin whose vertices are the figure's surface points (world, m) in its current posture."""

    def __init__(self, points: np.ndarray) -> None:
        self.vertices, self.location = points, np.eye(4)

    def mesh(self) -> "_Surface":
        return self


def floor_objects(doc: "Document", fig: "Figure") -> list[Any]:
    """Everything in the scene that ``fig`` walks round: CAD objects as they are, every other
    figure (props such as the default scene's worktable and chair, other people) by its surface."""
    from jackpy.body.measure import surface_points
    from jackpy.scene.cad import CADObject

    out: list[Any] = []
    for o in doc.env.figures.values():
        if o is fig:
            continue
        if isinstance(o, CADObject):
            out.append(o)
            continue
        names = [n for n in o.segments if o.segment(n).psurf is not None]
        if names:
            out.append(_Surface(surface_points(o, names)))
    return out


@dataclass
class Floor:
    """The floor as the walker sees it (x, z; m): each object's footprint (a convex polygon of
    its part below head height + 15 cm, :func:`floor_plan.footprints`), and ``blocked``, their
    union inflated by the walker's half-width + margin, which its centre site must stay out of
    (as :func:`jackpy.locomotion.walk_to.walk_to` plans)."""

    footprints: list[Polygon]
    blocked: Any  # shapely Polygon or MultiPolygon (empty when the floor is clear)


def floor_of(doc: "Document", st: dict[str, Any], fig: "Figure") -> Floor:
    """The scene's :class:`Floor` for walker ``fig`` (kept in the panel state until an object or
    another figure moves)."""
    from jackpy.locomotion import floor_plan

    key = (fig.name, id(fig), tuple((n, o.location.tobytes(), np.asarray(o.q).tobytes())
                                    for n, o in doc.env.figures.items() if o is not fig))
    if st.get("floor") is None or st["floor"][0] != key:
        objects = floor_objects(doc, fig)
        height = float(max(fig.site_world("head", "base")[1, 3] + 0.15, 0.0))  # walk_to's cut
        radius = floor_plan.half_width(fig) + floor_plan.MARGIN
        st["floor"] = (key, Floor(floor_plan.footprints(objects, height),
                                  floor_plan.obstacles(objects, height, radius)))
    return st["floor"][1]


def plan_to(doc: "Document", st: dict[str, Any], fig: "Figure", goal, facing: float | None = None) -> None:
    """Plan a walk of ``fig`` from where it stands to floor point ``goal`` (x, z; m) around the
    scene's objects (:func:`floor_objects`): one undoable command (the plan has no path points).
    :class:`jackpy.errors.JackpyError` when there is no way."""
    from jackpy.locomotion.walk_to import walk_to

    steps, _, _ = walk_to(fig, gait_of(st, fig), (float(goal[0]), float(goal[1])), floor_objects(doc, fig),
                          facing=facing)
    doc.command(f"plan walk of {fig.name} to ({goal[0]:.2f}, {goal[1]:.2f})",
                lambda: store(doc, fig.name, steps, None))
    st["selected"] = None


def move_footstep(doc: "Document", name: str, j: int, x: float, z: float, psi: float) -> None:
    """Move footstep ``j`` of ``name``'s plan to ``(x, z)`` heading ``psi``: one undoable command."""
    steps = walk_plan.moved(footsteps_of(doc, name) or [], j, x, z, psi)
    doc.command(f"move footstep {j} of {name}", lambda: store(doc, name, steps))


def add_stride(doc: "Document", name: str, j: int) -> None:
    """Add a stride after footstep ``j`` (:func:`walk_plan.with_stride_added`): one command."""
    steps = walk_plan.with_stride_added(footsteps_of(doc, name) or [], j)
    doc.command(f"add a stride after footstep {j} of {name}", lambda: store(doc, name, steps))


def delete_stride(doc: "Document", name: str, j: int) -> None:
    """Delete footsteps ``j`` and ``j + 1`` (:func:`walk_plan.with_stride_deleted`): one command."""
    steps = walk_plan.with_stride_deleted(footsteps_of(doc, name) or [], j)
    doc.command(f"delete footsteps {j}, {j + 1} of {name}", lambda: store(doc, name, steps))


def walk_of(doc: "Document", st: dict[str, Any], fig: "Figure") -> Walk | None:
    """The walk of the figure's plan as it is now (re-planned whenever the plan changed)."""
    steps = footsteps_of(doc, fig.name)
    if steps is None:
        return None
    key = (fig.name, tuple((s.x, s.z, s.psi, s.side) for s in steps))
    cached = st["walk"]
    if cached is None or cached[0] != key:
        cached = st["walk"] = (key, Walk(steps, gait_of(st, fig)))
    return cached[1]


def centre_path(walk: Walk, dt: float = 0.05) -> np.ndarray:
    """The centre site's floor path (N, 2) of ``walk`` sampled every ``dt`` seconds."""
    ts = np.append(np.arange(0.0, walk.duration, dt), walk.duration)
    return np.array([walk.at(float(t)).pelvis[[0, 2], 3] for t in ts])


def centre_path_of(st: dict[str, Any], walk: Walk) -> np.ndarray:
    """:func:`centre_path` of ``walk``, kept in the panel state while the walk is the same (it
    takes about a second under load: each sample evaluates the whole gait)."""
    if st.get("centre") is None or st["centre"][0] is not walk:
        st["centre"] = (walk, centre_path(walk))
    return st["centre"][1]


# ---------------------------------------------------------------------------------- the canvas
class View:
    """Top view of the floor in a canvas at ``origin`` of ``size`` (pixels), seen from above:
    floor (x, z) m -> pixels (z up the screen, x to the left, as the right-handed y-up world looks
    from above), fitting ``points`` ((N, 2) floor points) with ``margin`` (m) around them."""

    def __init__(self, origin, size, points, margin: float = 0.3) -> None:
        pts = np.asarray(points, float).reshape(-1, 2)
        lo, hi = pts.min(axis=0) - margin, pts.max(axis=0) + margin
        self.scale = float(min(size[0] / (hi[0] - lo[0]), size[1] / (hi[1] - lo[1])))
        self.centre = 0.5 * (lo + hi)
        self.mid = np.array([origin[0] + 0.5 * size[0], origin[1] + 0.5 * size[1]])

    def to_px(self, p) -> np.ndarray:
        d = (np.asarray(p, float) - self.centre) * self.scale
        return self.mid - d

    def to_floor(self, px) -> np.ndarray:
        return self.centre - (np.asarray(px, float) - self.mid) / self.scale


def press(doc: "Document", st: dict[str, Any], name: str, px) -> int | None:
    """A left press at canvas pixel ``px``: select the nearest movable footprint within
    :data:`PICK_PX` and start dragging it (the edit's undo state is taken now)."""
    steps, view = footsteps_of(doc, name), st["view"]
    if not steps or view is None:
        return None
    d = [float(np.linalg.norm(view.to_px(s.point) - np.asarray(px, float))) for s in steps]
    j = int(np.argmin(d))
    if d[j] > PICK_PX:
        return None
    st["selected"] = j
    if j >= 2:
        st["drag"] = (j, view.to_floor(px) - steps[j].point)
        doc.begin_edit()
    return j


def drag_to(doc: "Document", st: dict[str, Any], name: str, px) -> None:
    """The dragged footprint follows the mouse (the plan changes live; undo comes at release)."""
    if st["drag"] is None:
        return
    j, grab = st["drag"]
    steps = footsteps_of(doc, name)
    p = st["view"].to_floor(px) - grab
    store(doc, name, walk_plan.moved(steps, j, p[0], p[1], steps[j].psi))


def release(doc: "Document", st: dict[str, Any], name: str) -> None:
    """End a drag: the move is one undo step."""
    if st["drag"] is not None:
        doc.end_edit(f"move footstep {st['drag'][0]} of {name}")
        st["drag"] = None


def footprint(s: Footstep, p) -> np.ndarray:
    """Floor corners (4, 2) of footstep ``s``'s drawn footprint (heel to toe tip of gait ``p``'s
    foot, :data:`FOOT_HALF_WIDTH` each side; m)."""
    f, w = np.array([np.sin(s.psi), np.cos(s.psi)]), np.array([np.cos(s.psi), -np.sin(s.psi)])
    back, front = float(p.foot.heel[2] - p.foot.ankle[2]), float(p.foot.tip[2] - p.foot.ankle[2])
    return np.array([s.point + a * f + b * FOOT_HALF_WIDTH * w for a, b in ((back, -1), (front, -1), (front, 1), (back, 1))])


def _px(view: View, pts) -> list[tuple[float, float]]:
    return [tuple(map(float, view.to_px(q))) for q in pts]


def draw_floor(imgui: Any, dl: Any, view: View, floor: Floor) -> None:
    """The objects' footprints filled and the keep-out outline around them."""
    for poly in floor.footprints:
        dl.add_convex_poly_filled(_px(view, poly.exterior.coords[:-1]), OBJECT_COLOUR)
    for poly in getattr(floor.blocked, "geoms", [floor.blocked]):
        if not poly.is_empty:
            dl.add_polyline(_px(view, poly.exterior.coords[:-1]), KEEP_OUT_COLOUR, 1.0, imgui.ImDrawFlags_.closed)


def draw_footprints(imgui: Any, dl: Any, view: View, steps: list[Footstep], p, selected: int | None = None) -> None:
    """Footprints in their side's colour (the standing feet grey), the selected one outlined."""
    for j, s in enumerate(steps):
        pts = _px(view, footprint(s, p))
        dl.add_convex_poly_filled(pts, COLOURS[s.side] if j >= 2 else 0xFF909090)
        if selected == j:
            dl.add_polyline(pts, 0xFFFFFFFF, 2.0, imgui.ImDrawFlags_.closed)


def _canvas(imgui: Any, app: "App", st: dict[str, Any], fig: "Figure", steps: list[Footstep], walk: Walk) -> None:
    origin = imgui.get_cursor_screen_pos()
    avail = imgui.get_content_region_avail()
    size = (max(avail.x, 100.0), max(avail.y - CONTROLS_H, 100.0))
    if st["drag"] is None:  # the view holds still while a footprint is dragged
        st["view"] = View((origin.x, origin.y), size, [s.point for s in steps])
    view: View = st["view"]
    imgui.invisible_button("steps_canvas", size)
    dl = imgui.get_window_draw_list()
    corner = (origin.x + size[0], origin.y + size[1])
    dl.push_clip_rect((origin.x, origin.y), corner, True)
    dl.add_rect_filled((origin.x, origin.y), corner, 0xFF202020)
    draw_floor(imgui, dl, view, floor_of(app.doc, st, fig))
    draw_footprints(imgui, dl, view, steps, gait_of(st, fig), st["selected"])
    if st["drag"] is None:  # made again once the footprint is let go
        dl.add_polyline(_px(view, centre_path_of(st, walk)), PATH_COLOUR, 1.5, 0)
    dl.pop_clip_rect()
    mouse = imgui.get_mouse_pos()
    if imgui.is_item_clicked(0):
        press(app.doc, st, fig.name, (mouse.x, mouse.y))
    if st["drag"] is not None:
        if imgui.is_mouse_down(0):
            drag_to(app.doc, st, fig.name, (mouse.x, mouse.y))
        else:
            release(app.doc, st, fig.name)


def _selection_controls(imgui: Any, app: "App", st: dict[str, Any], fig: "Figure", steps: list[Footstep]) -> None:
    """Below the canvas (so that selecting does not move it): the selected footstep, its nudges,
    adding and deleting a stride."""
    j = st["selected"]
    if j is None or not 2 <= j < len(steps):
        imgui.text("no movable footstep selected (0 and 1 are the standing feet)")
        return
    s = steps[j]
    imgui.text(f"footstep {j} ({s.side}): x {s.x * 100:.1f} cm, z {s.z * 100:.1f} cm, "
               f"heading {np.degrees(s.psi):.1f} deg")
    for label, dx, dz, dpsi in (("-x", -NUDGE, 0, 0), ("+x", NUDGE, 0, 0), ("-z", 0, -NUDGE, 0),
                                ("+z", 0, NUDGE, 0), ("turn L", 0, 0, TURN), ("turn R", 0, 0, -TURN)):
        if imgui.button(label):
            move_footstep(app.doc, fig.name, j, s.x + dx, s.z + dz, s.psi + dpsi)
        imgui.same_line()
    for label, edit in (("Add stride after", add_stride), ("Delete stride", delete_stride)):
        if imgui.button(label):
            try:
                edit(app.doc, fig.name, j)
                st["message"] = ""
            except ValueError as exc:  # at the ends of the walk: said, nothing changed
                st["message"] = str(exc)
        imgui.same_line()
    imgui.new_line()


def bake(st: dict[str, Any], fig: "Figure", walk: Walk) -> None:
    """Write ``walk`` as a motion file of baked frames at 30 fps to ``st["path"]`` (solved on a
    copy of ``fig``: the document's figure keeps its posture)."""
    from jackpy.locomotion import walk_solve
    from jackpy.motion import motion_file

    spec = getattr(fig, "body_spec", None)
    human = f"{spec.sex}:{spec.percentile:g}" if spec is not None else None
    mf = walk_solve.motion_file(copy.deepcopy(fig), walk, 30.0, human)
    motion_file.save(mf, st["path"])
    st["message"] = f"baked {walk.duration:.2f} s to {st['path']}"


def draw(app: "App", ui: "UiState") -> None:
    from imgui_bundle import imgui

    from jackpy.errors import JackpyError

    st = ui.panel_state(TITLE, defaults())
    imgui.set_next_window_pos((60, 60), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((560, 620), imgui.Cond_.first_use_ever)
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels[TITLE])
    fig = app.figure_of_interest()
    if visible and walker(fig):
        imgui.set_next_item_width(160)
        _, st["goal"] = imgui.input_float2("goal x, z (m)", st["goal"])
        imgui.same_line()
        if imgui.button("Plan walk"):
            try:
                plan_to(app.doc, st, fig, st["goal"])
                st["message"] = ""
            except (JackpyError, ValueError) as exc:
                st["message"] = str(exc)
        try:
            steps, walk = footsteps_of(app.doc, fig.name), walk_of(app.doc, st, fig)
        except ValueError as exc:  # a plan in a file that is no walk: said, left alone
            steps, walk = None, None
            st["message"] = str(exc)
        if steps is not None and walk is not None:
            imgui.text(f"{fig.name}: {len(steps)} footsteps, {walk.duration:.2f} s")
            imgui.set_next_item_width(200)
            st["path"] = imgui.input_text("motion file", st["path"])[1]
            imgui.same_line()
            if imgui.button("Bake"):
                try:
                    bake(st, fig, walk)
                except (JackpyError, OSError, ValueError) as exc:
                    st["message"] = str(exc)
            imgui.text_wrapped(st["message"] or "Click a footprint to select it, drag it to move it.")
            _canvas(imgui, app, st, fig, steps, walk)
            _selection_controls(imgui, app, st, fig, steps)
        else:
            imgui.text_wrapped(st["message"] or "No walk yet: give a goal and press Plan walk.")
    elif visible:
        imgui.text("Choose a human figure.")
    imgui.end()


PANEL = Panel(TITLE, draw, open=False, order=62)
