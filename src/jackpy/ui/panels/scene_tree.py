"""Scene tree: figures and their segments; a click selects (and shows its joint)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from imgui_bundle import imgui

from jackpy.ui.panels import Panel
from jackpy.ui.scene_view import SegmentPick, is_object

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState


def draw(app: "App", ui: "UiState") -> None:
    imgui.set_next_window_pos((8, 30), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((250, 330), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Scene"] = imgui.begin("Scene", ui.open_panels["Scene"])
    if visible:
        for fig in app.env.figures.values():
            kind = "object" if is_object(fig) else f"{fig.ndof} DOF"
            if imgui.tree_node(f"{fig.name} ({kind})##fig-{fig.name}"):
                for seg in fig.segments:
                    target = SegmentPick(fig.name, seg)
                    clicked, _ = imgui.selectable(f"{seg}##{fig.name}/{seg}", app.selection == target)
                    if clicked:
                        app.select(target)
                imgui.tree_pop()
    imgui.end()


PANEL = Panel("Scene", draw, open=True, order=10)
