"""Creature editor panel (Sims Ch. 4, App. A): the "dissection table", a 2-D canvas drawn with an
imgui draw list, where the user draws nodes and links, selects, mirrors, scales, deletes and undoes,
then builds the 3-D creature into the scene or saves it as ``.fig`` (docs/creatures.md).

Mouse (Sims' three-button table, with one convenience): **left** on empty space creates a node and
starts a loose (rubber-band) link from it, or, with a loose link pending, creates a node, completes
the link and goes on from the new node; left on a node completes a pending link there, or starts one
from it (Sims: no effect). **Middle** (or ctrl + left) on empty space creates an unconnected node, on
a node deletes it; with a loose link pending it acts like left. **Right** aborts the loose link.
Shift + left drag lassoes a new selection. The head points up the screen. The imgui drawing only
calls :func:`press` and :func:`build_into_scene`, which tests drive headless.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from jackpy.locomotion.creature_editor import Drawing, Editor, analyse, build, save_figure
from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.peabody.model import Environment
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Creature editor"
#: canvas scale: pixels per drawing unit (cm)
PIXELS_PER_UNIT = 4.0
#: pick radius in drawing units
PICK = 2.0
LEFT, MIDDLE, RIGHT = 0, 2, 1  # imgui mouse button numbers


def defaults() -> dict[str, Any]:
    return {"editor": Editor(Drawing()), "loose": None, "lasso": None, "path": "creature", "message": ""}


def press(st: dict[str, Any], x: float, y: float, button: int) -> None:
    """One mouse press at drawing point ``(x, y)`` (the module docstring's table)."""
    ed: Editor = st["editor"]
    node = ed.node_at(x, y, PICK)
    loose = st["loose"]
    if button == RIGHT:
        st["loose"] = None
        return
    if loose is not None:  # left and middle alike
        if node is None:
            st["loose"] = ed.add_node(x, y, connect_from=loose)
        else:
            if node != loose:
                ed.connect(loose, node)
            st["loose"] = None
        return
    if button == LEFT:
        st["loose"] = node if node is not None else ed.add_node(x, y)
    elif button == MIDDLE:
        if node is None:
            ed.add_node(x, y)
        else:
            ed.delete([node])


def build_into_scene(env: "Environment", drawing: Drawing) -> str:
    """Build the drawing's figure and put it in ``env`` (replacing one of the same name); returns a
    one-line summary."""
    fig = build(drawing)
    env.figures.pop(fig.name, None)
    env.add(fig)
    an = analyse(drawing)
    return f"{fig.name}: {len(an.legs)} legs, {len(an.of('head'))} head, {len(an.of('tail'))} tail"


def draw(app: "App", ui: "UiState") -> None:
    from imgui_bundle import imgui

    st = ui.panel_state(TITLE, defaults())
    ed: Editor = st["editor"]
    imgui.set_next_window_size((520, 560), imgui.Cond_.first_use_ever)
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels[TITLE])
    if visible:
        if imgui.button("Undo"):
            ed.undo()
            st["loose"] = None
        imgui.same_line()
        if imgui.button("Undelete"):
            ed.undelete()
        imgui.same_line()
        if imgui.button("Select all"):
            ed.select_all()
        imgui.same_line()
        if imgui.button("Unselect"):
            ed.selection = set()
        imgui.same_line()
        if imgui.button("Mirror X copy"):
            ed.mirror_x(copy_=True)
        imgui.same_line()
        if imgui.button("Delete"):
            ed.delete()
            st["loose"] = None
        if imgui.button("Scale x1.25"):
            ed.scale(1.25)
        imgui.same_line()
        if imgui.button("Scale x0.8"):
            ed.scale(0.8)
        imgui.same_line()
        styles = ["insect", "mammal"]
        imgui.set_next_item_width(90)
        changed, k = imgui.combo("style", styles.index(ed.drawing.style), styles)
        if changed:
            ed.drawing.style = styles[k]
        imgui.set_next_item_width(160)
        st["path"] = imgui.input_text("name", st["path"])[1]
        imgui.same_line()
        if imgui.button("Build into scene"):
            try:
                ed.drawing.name = st["path"] or "creature"
                drawing = ed.drawing
                app.doc.command(f"build creature {drawing.name}",
                                lambda: st.__setitem__("message", build_into_scene(app.env, drawing)), structural=True)
            except Exception as exc:  # a drawing that is no creature: said, nothing changed
                st["message"] = str(exc)
        imgui.same_line()
        if imgui.button("Save"):
            try:
                ed.drawing.name = st["path"] or "creature"
                ed.drawing.save(f"{ed.drawing.name}.drawing.json")
                save_figure(build(ed.drawing), f"{ed.drawing.name}.fig")
                st["message"] = f"saved {ed.drawing.name}.drawing.json and {ed.drawing.name}.fig"
            except Exception as exc:
                st["message"] = str(exc)
        if st["message"]:
            imgui.text(st["message"])
        _canvas(imgui, st)
    imgui.end()


def _canvas(imgui: Any, st: dict[str, Any]) -> None:
    ed: Editor = st["editor"]
    origin = imgui.get_cursor_screen_pos()
    size = imgui.get_content_region_avail()
    w, h = max(size.x, 50.0), max(size.y, 50.0)
    imgui.invisible_button("canvas", (w, h), imgui.ButtonFlags_.mouse_button_left | imgui.ButtonFlags_.mouse_button_right
                           | imgui.ButtonFlags_.mouse_button_middle)
    cx, cy = origin.x + w / 2, origin.y + h / 2

    def to_screen(p):
        return imgui.ImVec2(cx + p[0] * PIXELS_PER_UNIT, cy + p[1] * PIXELS_PER_UNIT)

    mouse = imgui.get_io().mouse_pos
    mx, my = (mouse.x - cx) / PIXELS_PER_UNIT, (mouse.y - cy) / PIXELS_PER_UNIT
    dl = imgui.get_window_draw_list()
    dl.push_clip_rect(origin, imgui.ImVec2(origin.x + w, origin.y + h), True)
    dl.add_rect_filled(origin, imgui.ImVec2(origin.x + w, origin.y + h), imgui.get_color_u32((0.12, 0.12, 0.14, 1.0)))
    axis = imgui.get_color_u32((0.5, 0.5, 0.5, 0.6))
    for k in range(0, int(w), 8):  # dotted axes
        dl.add_line(imgui.ImVec2(origin.x + k, cy), imgui.ImVec2(origin.x + k + 3, cy), axis)
    for k in range(0, int(h), 8):
        dl.add_line(imgui.ImVec2(cx, origin.y + k), imgui.ImVec2(cx, origin.y + k + 3), axis)
    nodes = ed.drawing.nodes
    sel = ed.selection
    for a, b in ed.drawing.links:
        col = (1.0, 0.8, 0.2, 1.0) if a in sel and b in sel else (0.85, 0.85, 0.85, 1.0)
        dl.add_line(to_screen(nodes[a]), to_screen(nodes[b]), imgui.get_color_u32(col), 2.0)
    for i, p in enumerate(nodes):
        col = (1.0, 0.8, 0.2, 1.0) if i in sel else (0.6, 0.9, 0.6, 1.0)
        dl.add_circle_filled(to_screen(p), 3.5, imgui.get_color_u32(col))
    if imgui.is_item_hovered():
        hover = ed.node_at(mx, my, PICK)
        if hover is not None:
            dl.add_circle(to_screen(nodes[hover]), 8.0, imgui.get_color_u32((1, 1, 1, 1)))
        io = imgui.get_io()
        if st["loose"] is not None and st["loose"] < len(nodes):
            dl.add_line(to_screen(nodes[st["loose"]]), mouse, imgui.get_color_u32((0.5, 0.8, 1.0, 1.0)), 1.5)
        if io.key_shift and imgui.is_mouse_clicked(LEFT):
            st["lasso"] = [(mx, my)]
        elif st["lasso"] is not None and imgui.is_mouse_down(LEFT):
            st["lasso"].append((mx, my))
        elif st["lasso"] is not None:
            ed.select_lasso(st["lasso"])
            st["lasso"] = None
        elif imgui.is_mouse_clicked(LEFT):
            press(st, mx, my, MIDDLE if io.key_ctrl else LEFT)
        elif imgui.is_mouse_clicked(MIDDLE):
            press(st, mx, my, MIDDLE)
        elif imgui.is_mouse_clicked(RIGHT):
            press(st, mx, my, RIGHT)
    if st["lasso"]:
        pts = st["lasso"]
        for p, q in zip(pts[:-1], pts[1:]):
            dl.add_line(to_screen(p), to_screen(q), imgui.get_color_u32((1.0, 0.8, 0.2, 0.8)))
    dl.pop_clip_rect()


PANEL = Panel(TITLE, draw, order=95)
