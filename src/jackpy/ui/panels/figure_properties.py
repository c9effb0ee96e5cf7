"""Figure properties: name, placement, DOFs and mass of the selected (or first) figure."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from imgui_bundle import imgui

from jackpy.ui.scene_view import SegmentPick

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState


def draw(app: "App", ui: "UiState") -> None:
    imgui.set_next_window_pos((8, 370), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((250, 220), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Figure"] = imgui.begin("Figure", ui.open_panels["Figure"])
    if visible:
        sel = app.selection
        fig = app.env.figures.get(sel.figure) if isinstance(sel, SegmentPick) else app.figure_of_interest()
        if fig is None:
            imgui.text_disabled("No figure.")
        else:
            imgui.text(fig.name)
            x, y, z = fig.location[:3, 3] * 100.0
            imgui.text(f"at ({x:.1f}, {y:.1f}, {z:.1f}) cm")
            imgui.text(f"{len(fig.segments)} segments, {fig.ndof} DOFs")
            if fig.total_mass > 0:
                com = fig.centre_of_mass() * 100.0
                imgui.text(f"mass {fig.total_mass:.1f} kg, COM y {com[1]:.1f} cm")
            inside = np.all((fig.q >= fig.lower - 1e-9) & (fig.q <= fig.upper + 1e-9))
            imgui.text("all joints within limits" if inside else "some joints outside limits")
    imgui.end()
