"""Path editor panel ([SH5] §5.2.3; issue 13): the walk of the figure of interest as a path of
floor points, top view as seen from above over the scene's objects (their floor footprints dark
grey, the outline the walker's centre keeps out of around them).

Click the floor to add a point at the end of the path (on the path: inserted there), drag a point
to move it, right-click a point (or select it and press "Delete point") to delete it. Point 0 is
where the figure stood when the path was begun (a figure without a path begins one with its first
click). The path is a Catmull-Rom spline through the points (:func:`footsteps.spline`); its
footsteps are made at once (:func:`footsteps.from_path`, standing at both ends), so the footprints
and the centre site's path (yellow) follow while a point is dragged. Spline stretches inside the
keep-out outline are drawn magenta and named, as are footprints that land on an object (orange
outline): flagged, not refused, so that nothing the user does is lost. Every add, move and delete
is one document command (Ctrl+Z undoes it); the points are kept with the footsteps in the
document's ``extras["walk_plans"]`` (:mod:`jackpy.locomotion.walk_plan`) and saved with it. The
step editor shows and edits the same plan (its footprint edits keep the path points; the next path
edit makes the footsteps from the path again) and bakes it. The imgui drawing only calls
:func:`add_point`, :func:`move_point`, :func:`delete_point`, :func:`press`, :func:`drag_to`,
:func:`release` and :func:`delete_at`, which tests drive headless or through the window.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import shapely
from shapely.geometry import Polygon

from jackpy.locomotion import footsteps, walk_plan
from jackpy.locomotion.walk_path import Footstep
from jackpy.ui.panels import Panel
from jackpy.ui.panels.steps_editor import (PATH_COLOUR, Floor, View, centre_path_of, draw_floor,
                                           draw_footprints, floor_of, footprint, footsteps_of, gait_of, path_of, store,
                                           walk_of, walker)

if TYPE_CHECKING:
    from jackpy.document import Document
    from jackpy.peabody.model import Figure
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Path editor"
PICK_PX = 10.0  # a press this close (pixels) to a point grabs it; this close to the spline inserts one
POINT_PX = 6.0  # drawn radius of a path point
SAMPLES = 24  # spline samples per path segment (as footsteps.from_path samples it)
GRID = 0.5  # m between the floor's grid lines
SPLINE_COLOUR = 0xFFF0F0F0
CROSSING_COLOUR = 0xFFFF40FF  # ABGR magenta: the spline inside the keep-out outline (red is the right foot)
LANDING_COLOUR = 0xFF00A0FF  # ABGR orange: a footprint on an object
SELECTED_COLOUR = 0xFF40E0FF
CONTROLS_H = 56.0  # pixels kept below the canvas for the selected point's controls
LEGEND = ("white: the path; yellow: the centre site; magenta: through an obstacle; orange: a footprint on an "
          "object; grey: objects and the outline the walker keeps out of")
HINT = "Click the floor to add a point (on the path: insert one), drag a point to move it, right-click it to delete it."


def defaults() -> dict[str, Any]:
    return {"selected": None, "drag": None, "view": None, "gait": {}, "walk": None, "floor": None,
            "flags": None, "centre": None, "message": ""}


# ---------------------------------------------------------------------------------- the path
def start_of(fig: "Figure") -> walk_plan.Point:
    """Where ``fig`` stands: its pelvis centre's floor point (x, z; m), a new path's point 0."""
    c = fig.site_world("pelvis", "centre")[:3, 3]
    return float(c[0]), float(c[2])


def steps_for(st: dict[str, Any], fig: "Figure", path: list[walk_plan.Point]) -> list[Footstep]:
    """The footsteps of ``fig``'s gait along the spline through ``path`` (standing at both ends,
    at the end facing along the path, as ``jackpy walk --path``)."""
    return footsteps.from_path(gait_of(st, fig), np.array(path, float))


def _apply(doc: "Document", st: dict[str, Any], fig: "Figure", path: list[walk_plan.Point]) -> None:
    store(doc, fig.name, steps_for(st, fig, path), path)


def _path_or_new(doc: "Document", fig: "Figure") -> list[walk_plan.Point]:
    """The plan's path, or a path of only where the figure stands (its first click adds point 1)."""
    return path_of(doc, fig.name) or [start_of(fig)]


def add_point(doc: "Document", st: dict[str, Any], fig: "Figure", xz, k: int | None = None) -> int:
    """Add floor point ``xz`` (x, z; m) as path point ``k`` (default: the end; a figure without a
    path begins one from where it stands) and make the footsteps: one command. Returns ``k``."""
    path = _path_or_new(doc, fig)
    k = len(path) if k is None else k
    new = walk_plan.with_point_added(path, k, float(xz[0]), float(xz[1]))
    doc.command(f"add path point {k} of {fig.name}", lambda: _apply(doc, st, fig, new))
    st["selected"] = k
    return k


def move_point(doc: "Document", st: dict[str, Any], fig: "Figure", k: int, xz) -> None:
    """Move path point ``k`` (≥ 1) to ``xz``; the footsteps follow: one command."""
    new = walk_plan.with_point_moved(path_of(doc, fig.name) or [], k, float(xz[0]), float(xz[1]))
    doc.command(f"move path point {k} of {fig.name}", lambda: _apply(doc, st, fig, new))


def delete_point(doc: "Document", st: dict[str, Any], fig: "Figure", k: int) -> None:
    """Delete path point ``k`` (≥ 1; two points stay); the footsteps follow: one command."""
    new = walk_plan.with_point_deleted(path_of(doc, fig.name) or [], k)
    doc.command(f"delete path point {k} of {fig.name}", lambda: _apply(doc, st, fig, new))
    st["selected"] = None


# ---------------------------------------------------------------------------------- the checks
@dataclass
class Flags:
    """What the path runs into: ``spline`` (M, 2) the centre line through the points (m),
    ``inside`` (M − 1,) its pieces inside the keep-out outline, ``crossing`` the segments (k: point
    k to k + 1) with such pieces, ``landing`` the footsteps whose footprint overlaps an object's."""

    spline: np.ndarray
    inside: np.ndarray
    crossing: list[int]
    landing: list[int]


def check(path: list[walk_plan.Point], steps: list[Footstep], p, floor: Floor) -> Flags:
    """The :class:`Flags` of ``path`` and its ``steps`` (gait ``p``) on ``floor``."""
    line = footsteps.spline(np.array(path, float), SAMPLES)
    mid = 0.5 * (line[1:] + line[:-1])
    if floor.blocked.is_empty:
        inside = np.zeros(len(mid), bool)
    else:
        inside = np.asarray(shapely.contains_xy(floor.blocked, mid[:, 0], mid[:, 1]), bool)
    crossing = sorted({int(i) // SAMPLES for i in np.flatnonzero(inside)})
    landing = [j for j, s in enumerate(steps)
               if any(Polygon(footprint(s, p)).intersects(f) for f in floor.footprints)]
    return Flags(line, inside, crossing, landing)


def flags_of(doc: "Document", st: dict[str, Any], fig: "Figure", path, steps) -> tuple[Flags, bool]:
    """:func:`check` of the plan as it is now, and whether its footsteps are no longer those of
    its path (moved in the step editor); kept until the plan or the floor changes."""
    floor = floor_of(doc, st, fig)
    key = (tuple(path), tuple((s.x, s.z, s.psi, s.side) for s in steps), id(floor))
    if st["flags"] is None or st["flags"][0] != key:
        st["flags"] = (key, (check(path, steps, gait_of(st, fig), floor), steps != steps_for(st, fig, path)))
    return st["flags"][1]


def warnings(flags: Flags) -> list[str]:
    """The flags in words (empty when the path is clear)."""
    out = []
    if flags.crossing:
        out.append("through an obstacle: " + ", ".join(f"points {k}-{k + 1}" for k in flags.crossing))
    if flags.landing:
        out.append("footsteps on an object: " + ", ".join(map(str, flags.landing)))
    return out


# ---------------------------------------------------------------------------------- the mouse
def _nearest_point(view: View, path, px) -> tuple[int, float]:
    d = [float(np.linalg.norm(view.to_px(q) - np.asarray(px, float))) for q in path]
    k = int(np.argmin(d))
    return k, d[k]


def _segment_under(view: View, path, px) -> int | None:
    """The path segment whose spline passes within :data:`PICK_PX` of ``px`` (None if none)."""
    if len(path) < 2:
        return None
    line = np.array([view.to_px(q) for q in footsteps.spline(np.array(path, float), SAMPLES)])
    d = np.linalg.norm(line - np.asarray(px, float), axis=1)
    i = int(np.argmin(d))
    return None if d[i] > PICK_PX else min(max(i - 1, 0) // SAMPLES, len(path) - 2)


def press(doc: "Document", st: dict[str, Any], fig: "Figure", px) -> int | None:
    """A left press at canvas pixel ``px``: on a path point, select it and start dragging it
    (point 0 is only selected); on the spline, insert a point there; elsewhere on the floor, add
    one at the end. An added point is dragged until the release (add and drag: one undo step)."""
    view = st["view"]
    if view is None:
        return None
    path = path_of(doc, fig.name)
    at = view.to_floor(px)
    if path:
        k, d = _nearest_point(view, path, px)
        if d <= PICK_PX:
            st["selected"] = k
            if k >= 1:
                doc.begin_edit()
                st["drag"] = (k, f"move path point {k} of {fig.name}", at - np.array(path[k]))
            return k
    path = path or [start_of(fig)]
    seg = _segment_under(view, path, px)
    k = len(path) if seg is None else seg + 1
    doc.begin_edit()
    _apply(doc, st, fig, walk_plan.with_point_added(path, k, float(at[0]), float(at[1])))
    st["selected"] = k
    st["drag"] = (k, f"add path point {k} of {fig.name}", np.zeros(2))
    return k


def drag_to(doc: "Document", st: dict[str, Any], fig: "Figure", px) -> None:
    """The dragged point follows the mouse; the footsteps are made again (undo comes at release)."""
    if st["drag"] is None:
        return
    k, _, grab = st["drag"]
    q = st["view"].to_floor(px) - grab
    _apply(doc, st, fig, walk_plan.with_point_moved(path_of(doc, fig.name) or [], k, float(q[0]), float(q[1])))


def release(doc: "Document", st: dict[str, Any], fig: "Figure") -> None:
    """End a drag: the add or move is one undo step."""
    if st["drag"] is not None:
        doc.end_edit(st["drag"][1])
        st["drag"] = None


def delete_at(doc: "Document", st: dict[str, Any], fig: "Figure", px) -> int | None:
    """A right click at ``px``: delete the path point under it (:func:`delete_point`)."""
    path, view = path_of(doc, fig.name), st["view"]
    if not path or view is None:
        return None
    k, d = _nearest_point(view, path, px)
    if d > PICK_PX:
        return None
    delete_point(doc, st, fig, k)
    return k


# ---------------------------------------------------------------------------------- drawing
def _view_points(doc: "Document", st: dict[str, Any], fig: "Figure", path, steps) -> np.ndarray:
    pts = [np.array(start_of(fig))] + [np.array(q) for q in path or []] + [s.point for s in steps or []]
    for poly in floor_of(doc, st, fig).footprints:
        pts += [np.array(c) for c in poly.exterior.coords]
    return np.array(pts)


def _grid(dl: Any, view: View, origin, size) -> None:
    lo = view.to_floor((origin[0] + size[0], origin[1] + size[1]))  # x to the left, z up
    hi = view.to_floor(origin)
    for x in np.arange(np.ceil(lo[0] / GRID) * GRID, hi[0], GRID):
        a, b = view.to_px((x, lo[1])), view.to_px((x, hi[1]))
        dl.add_line(tuple(map(float, a)), tuple(map(float, b)), 0xFF303030, 1.0)
    for z in np.arange(np.ceil(lo[1] / GRID) * GRID, hi[1], GRID):
        a, b = view.to_px((lo[0], z)), view.to_px((hi[0], z))
        dl.add_line(tuple(map(float, a)), tuple(map(float, b)), 0xFF303030, 1.0)


def _canvas(imgui: Any, app: "App", st: dict[str, Any], fig: "Figure", path, steps) -> None:
    origin = imgui.get_cursor_screen_pos()
    avail = imgui.get_content_region_avail()
    size = (max(avail.x, 100.0), max(avail.y - CONTROLS_H, 100.0))
    if st["drag"] is None:  # the view holds still while a point is dragged
        st["view"] = View((origin.x, origin.y), size, _view_points(app.doc, st, fig, path, steps), 0.5)
    view: View = st["view"]
    imgui.invisible_button("path_canvas", size, imgui.ButtonFlags_.mouse_button_left
                           | imgui.ButtonFlags_.mouse_button_right)
    dl = imgui.get_window_draw_list()
    corner = (origin.x + size[0], origin.y + size[1])
    dl.push_clip_rect((origin.x, origin.y), corner, True)
    dl.add_rect_filled((origin.x, origin.y), corner, 0xFF202020)
    _grid(dl, view, (origin.x, origin.y), size)
    draw_floor(imgui, dl, view, floor_of(app.doc, st, fig))

    def px(q) -> tuple[float, float]:
        return tuple(map(float, view.to_px(q)))

    if steps:
        p = gait_of(st, fig)
        draw_footprints(imgui, dl, view, steps, p)
        walk = walk_of(app.doc, st, fig)
        if walk is not None and st["drag"] is None:  # made again once the point is let go
            dl.add_polyline([px(q) for q in centre_path_of(st, walk)], PATH_COLOUR, 1.5, 0)
    if path:
        flags, _ = flags_of(app.doc, st, fig, path, steps)
        for j in flags.landing:
            dl.add_polyline([px(q) for q in footprint(steps[j], gait_of(st, fig))], LANDING_COLOUR, 2.5,
                            imgui.ImDrawFlags_.closed)
        line = flags.spline
        for i in range(len(line) - 1):
            inside = bool(flags.inside[i])
            dl.add_line(px(line[i]), px(line[i + 1]), CROSSING_COLOUR if inside else SPLINE_COLOUR,
                        4.0 if inside else 2.0)
        for k, q in enumerate(path):
            c = px(q)
            if k == 0:
                dl.add_rect_filled((c[0] - POINT_PX, c[1] - POINT_PX), (c[0] + POINT_PX, c[1] + POINT_PX), 0xFF909090)
            else:
                dl.add_circle_filled(c, POINT_PX, SPLINE_COLOUR)
            if st["selected"] == k:
                dl.add_circle(c, POINT_PX + 3.0, SELECTED_COLOUR, 0, 2.0)
            dl.add_text((c[0] + POINT_PX + 5.0, c[1] - 2.0 * POINT_PX - 5.0), 0xFFFFFFFF, str(k))
    dl.pop_clip_rect()
    mouse = (imgui.get_mouse_pos().x, imgui.get_mouse_pos().y)
    if imgui.is_item_clicked(0):
        press(app.doc, st, fig, mouse)
    elif imgui.is_item_clicked(1):
        try:
            delete_at(app.doc, st, fig, mouse)
            st["message"] = ""
        except ValueError as exc:  # the last two points: said, nothing changed
            st["message"] = str(exc)
    if st["drag"] is not None:
        if imgui.is_mouse_down(0):
            drag_to(app.doc, st, fig, mouse)
        else:
            release(app.doc, st, fig)


def _selection_controls(imgui: Any, app: "App", st: dict[str, Any], fig: "Figure", path) -> None:
    k = st["selected"]
    if not path or k is None or not 0 <= k < len(path):
        imgui.text("no point selected")
        return
    x, z = path[k]
    imgui.text(f"point {k}: x {x * 100:.1f} cm, z {z * 100:.1f} cm" + ("  (where the walk starts)" if k == 0 else ""))
    if k >= 1:
        imgui.same_line()
        if imgui.button("Delete point"):
            try:
                delete_point(app.doc, st, fig, k)
                st["message"] = ""
            except ValueError as exc:
                st["message"] = str(exc)


def draw(app: "App", ui: "UiState") -> None:
    from imgui_bundle import imgui

    st = ui.panel_state(TITLE, defaults())
    imgui.set_next_window_pos((120, 80), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((620, 640), imgui.Cond_.first_use_ever)
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels[TITLE])
    fig = app.figure_of_interest()
    if visible and walker(fig):
        try:
            path, steps = path_of(app.doc, fig.name), footsteps_of(app.doc, fig.name)
        except ValueError as exc:  # a plan in a file that is no walk: said, left alone
            imgui.text_wrapped(str(exc))
            imgui.end()
            return
        walk = walk_of(app.doc, st, fig) if steps else None
        if path and steps and walk is not None:
            imgui.text(f"{fig.name}: {len(path)} points, {len(steps)} footsteps, {walk.duration:.2f} s")
            flags, by_hand = flags_of(app.doc, st, fig, path, steps)
            for line in warnings(flags):
                imgui.text_colored((1.0, 0.35, 0.3, 1.0), line)
            if by_hand:
                imgui.text_wrapped("Footsteps moved in the step editor: the next path edit makes them from the path again.")
        elif steps:
            imgui.text_wrapped(f"{fig.name}'s walk has no path points (planned to a goal or loaded without): "
                               "a click on the floor begins a new path from where it stands.")
        else:
            imgui.text_wrapped(f"No walk yet: click the floor to begin a path from where {fig.name} stands.")
        imgui.text_wrapped(st["message"] or HINT)
        imgui.push_text_wrap_pos(0.0)
        imgui.text_disabled(LEGEND)
        imgui.pop_text_wrap_pos()
        _canvas(imgui, app, st, fig, path, steps)
        _selection_controls(imgui, app, st, fig, path_of(app.doc, fig.name))
    elif visible:
        imgui.text("Choose a human figure.")
    imgui.end()


PANEL = Panel(TITLE, draw, open=False, order=63)
