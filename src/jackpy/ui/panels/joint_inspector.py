"""Joint inspector: a slider per DOF of the selected figure, in degrees (cm for translations),
bounded by the DOF's limits. One slider drag is one undo step."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from imgui_bundle import imgui

from jackpy.ui.names import dof_label, dof_name, joint_label, is_human
from jackpy.ui.panels import Panel
from jackpy.ui.scene_view import SegmentPick, is_object

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState


LABEL_WIDTH = 110.0
"""Pixels of a DOF's name left of its slider."""
DEFAULTS: dict[str, str | None] = {"focus": None}
"""The panel's state: the joint opened for the last selection (a new selection opens its joint once)."""


def draw(app: "App", ui: "UiState") -> None:
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((vp.size.x - 290, 30), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((280, 360), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Joints"] = imgui.begin("Joints", ui.open_panels["Joints"])
    if visible:
        sel = app.selection
        fig = app.env.figures.get(sel.figure) if isinstance(sel, SegmentPick) else app.figure_of_interest()
        if fig is None or is_object(fig):
            imgui.text_disabled("Select a segment of a figure.")
        else:
            focus = None
            if isinstance(sel, SegmentPick) and sel.figure == fig.name:
                kin = fig.kinematics()
                pj = kin.parent_joint[kin.segment_index[sel.segment]]
                focus = kin.joint_names[pj] if pj >= 0 else None
            state = ui.panel_state("Joints", DEFAULTS)
            refocus = focus is not None and focus != state["focus"]
            state["focus"] = focus
            human = is_human(fig)
            for joint in fig.joints.values():
                if refocus:
                    imgui.set_next_item_open(joint.name == focus, imgui.Cond_.always)
                if not imgui.tree_node(f"{joint_label(joint.name) if human else joint.name}##{joint.name}"):
                    continue
                for k, dof in enumerate(joint.dofs):
                    rot = dof.kind == "R"
                    f = 180.0 / np.pi if rot else 100.0
                    unit = "deg" if rot else "cm"
                    imgui.text(dof_name(joint.name, k) if human else f"{dof.kind}{k + 1}")
                    imgui.same_line(LABEL_WIDTH)
                    imgui.set_next_item_width(-1)
                    changed, v = imgui.slider_float(f"##{joint.name}{k}",
                                                    float(joint.displacement[k] * f),
                                                    float(dof.lower * f), float(dof.upper * f),
                                                    f"%.1f {unit}")
                    if imgui.is_item_activated():
                        app.begin_edit()
                    if changed:
                        app.doc.set_dof(fig, joint.name, k, v / f)  # through the figure, clamped
                    if imgui.is_item_deactivated_after_edit():
                        app.end_edit(f"set {dof_label(joint.name, k) if human else f'{joint.name}[{k}]'}")
                imgui.tree_pop()
    imgui.end()


PANEL = Panel("Joints", draw, open=True, order=20)
