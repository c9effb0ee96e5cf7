"""Log: what the workbench did (commands, sessions, errors), newest last."""

from __future__ import annotations

from typing import TYPE_CHECKING

from imgui_bundle import imgui

from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState


def draw(app: "App", ui: "UiState") -> None:
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((270, vp.size.y - 150), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((vp.size.x - 560, 140), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Log"] = imgui.begin("Log", ui.open_panels["Log"])
    if visible:
        s = app.stats
        imgui.text(f"IK {s.solve_s * 1e3:5.1f} ms ({s.iterations} it)   draw {s.draw_s * 1e3:5.1f} ms")
        imgui.separator()
        for line in app.log[-200:]:
            imgui.text_wrapped(line)
        if imgui.get_scroll_y() >= imgui.get_scroll_max_y():
            imgui.set_scroll_here_y(1.0)
    imgui.end()


PANEL = Panel("Log", draw, open=True, order=90)
