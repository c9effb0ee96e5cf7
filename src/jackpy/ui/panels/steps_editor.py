"""Step editor panel ([SH5] §5.2.4, Fig 5.10; issue 13): the footsteps of the figure of
interest's walk, drawn top view as seen from above (left feet blue, right feet red, the standing
feet grey, the centre site's path yellow), the selected footstep's controls below.

Plan a walk to a floor point (around the scene's CAD objects, as
:func:`jackpy.locomotion.walk_to.walk_to`), then drag a footprint in the canvas to move it, or
nudge the selected one (5 cm, 5°) with the buttons; add a stride after it (a footstep of each
side, halfway between their neighbours) or delete the stride it starts (it and the next
footstep), so that the feet still alternate. The walk is re-planned from the edited footsteps at
once (the path and duration shown follow). Every edit is one document command, so Ctrl+Z undoes
it; the plan lives in the document's ``extras["walk_plans"]`` (:mod:`jackpy.locomotion.walk_plan`)
and is saved with it. "Bake" writes the walk as a motion file (baked frames, on a copy of the
figure). The imgui drawing only calls :func:`plan_to`, :func:`move_footstep`, :func:`add_stride`,
:func:`delete_stride`, :func:`press`, :func:`drag_to`, :func:`release` and :func:`bake`, which
tests drive headless or through the window.
"""

from __future__ import annotations

import copy
from typing import TYPE_CHECKING, Any

import numpy as np

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


def defaults() -> dict[str, Any]:
    return {"selected": None, "drag": None, "goal": [0.0, 2.0], "path": "walk.motion.json", "message": "",
            "view": None, "gait": {}, "walk": None}


# ---------------------------------------------------------------------------------- the plan
def footsteps_of(doc: "Document", name: str) -> list[Footstep] | None:
    """The walk plan of figure ``name`` (None when it has none)."""
    data = doc.extras.get(PLANS, {}).get(name)
    return None if data is None else walk_plan.from_data(data, f"walk plan of {name}")


def _store(doc: "Document", name: str, steps: list[Footstep]) -> None:
    plans = dict(doc.extras.get(PLANS, {}))
    plans[name] = walk_plan.to_data(steps)
    doc.extras[PLANS] = plans


def gait_of(st: dict[str, Any], fig: "Figure"):
    """The figure's gait (measured once per figure and panel)."""
    from jackpy.locomotion.walk_gait import GaitParams

    key = (fig.name, id(fig))
    if key not in st["gait"]:
        st["gait"][key] = GaitParams.for_figure(fig)
    return st["gait"][key]


def plan_to(doc: "Document", st: dict[str, Any], fig: "Figure", goal, facing: float | None = None) -> None:
    """Plan a walk of ``fig`` from where it stands to floor point ``goal`` (x, z; m) around the
    scene's CAD objects: one undoable command. :class:`jackpy.errors.JackpyError` when no way."""
    from jackpy.locomotion.walk_to import walk_to
    from jackpy.scene.cad import CADObject

    objects = [o for o in doc.env.figures.values() if isinstance(o, CADObject)]
    steps, _, _ = walk_to(fig, gait_of(st, fig), (float(goal[0]), float(goal[1])), objects, facing=facing)
    doc.command(f"plan walk of {fig.name} to ({goal[0]:.2f}, {goal[1]:.2f})", lambda: _store(doc, fig.name, steps))
    st["selected"] = None


def move_footstep(doc: "Document", name: str, j: int, x: float, z: float, psi: float) -> None:
    """Move footstep ``j`` of ``name``'s plan to ``(x, z)`` heading ``psi``: one undoable command."""
    steps = walk_plan.moved(footsteps_of(doc, name) or [], j, x, z, psi)
    doc.command(f"move footstep {j} of {name}", lambda: _store(doc, name, steps))


def add_stride(doc: "Document", name: str, j: int) -> None:
    """Add a stride after footstep ``j`` (:func:`walk_plan.with_stride_added`): one command."""
    steps = walk_plan.with_stride_added(footsteps_of(doc, name) or [], j)
    doc.command(f"add a stride after footstep {j} of {name}", lambda: _store(doc, name, steps))


def delete_stride(doc: "Document", name: str, j: int) -> None:
    """Delete footsteps ``j`` and ``j + 1`` (:func:`walk_plan.with_stride_deleted`): one command."""
    steps = walk_plan.with_stride_deleted(footsteps_of(doc, name) or [], j)
    doc.command(f"delete footsteps {j}, {j + 1} of {name}", lambda: _store(doc, name, steps))


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


# ---------------------------------------------------------------------------------- the canvas
class View:
    """Top view of the floor in a canvas, seen from above: floor (x, z) m -> pixels (z up the
    screen, x to the left, as the right-handed y-up world looks from above)."""

    def __init__(self, origin, size, steps: list[Footstep]) -> None:
        pts = np.array([s.point for s in steps])
        lo, hi = pts.min(axis=0) - 0.3, pts.max(axis=0) + 0.3
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
    _store(doc, name, walk_plan.moved(steps, j, p[0], p[1], steps[j].psi))


def release(doc: "Document", st: dict[str, Any], name: str) -> None:
    """End a drag: the move is one undo step."""
    if st["drag"] is not None:
        doc.end_edit(f"move footstep {st['drag'][0]} of {name}")
        st["drag"] = None


def _footprint(view: View, s: Footstep, p) -> list[np.ndarray]:
    """Corner pixels of a footprint (heel to toe tip, :data:`FOOT_HALF_WIDTH` each side)."""
    f, w = np.array([np.sin(s.psi), np.cos(s.psi)]), np.array([np.cos(s.psi), -np.sin(s.psi)])
    back, front = float(p.foot.heel[2] - p.foot.ankle[2]), float(p.foot.tip[2] - p.foot.ankle[2])
    return [view.to_px(s.point + a * f + b * FOOT_HALF_WIDTH * w)
            for a, b in ((back, -1), (front, -1), (front, 1), (back, 1))]


def _canvas(imgui: Any, app: "App", st: dict[str, Any], fig: "Figure", steps: list[Footstep], walk: Walk) -> None:
    origin = imgui.get_cursor_screen_pos()
    avail = imgui.get_content_region_avail()
    size = (max(avail.x, 100.0), max(avail.y - CONTROLS_H, 100.0))
    if st["drag"] is None:  # the view holds still while a footprint is dragged
        st["view"] = View((origin.x, origin.y), size, steps)
    view: View = st["view"]
    imgui.invisible_button("steps_canvas", size)
    dl = imgui.get_window_draw_list()
    dl.add_rect_filled((origin.x, origin.y), (origin.x + size[0], origin.y + size[1]), 0xFF202020)
    p = gait_of(st, fig)
    for j, s in enumerate(steps):
        pts = [tuple(map(float, q)) for q in _footprint(view, s, p)]
        colour = COLOURS[s.side] if j >= 2 else 0xFF909090
        dl.add_convex_poly_filled(pts, colour)
        if st["selected"] == j:
            dl.add_polyline(pts, 0xFFFFFFFF, 2.0, imgui.ImDrawFlags_.closed)
    path = [tuple(map(float, view.to_px(q))) for q in centre_path(walk)]
    dl.add_polyline(path, PATH_COLOUR, 1.5, 0)
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
    if visible and fig is not None and fig.joints:
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
