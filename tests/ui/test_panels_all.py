"""Every panel open with every section, swept by the mouse: no imgui ID conflict anywhere; the
joint inspector and strength bars name DOFs for people. Real window under Xvfb."""

import os

import pytest
from ui_support import in_child_process

from jackpy.ui.names import dof_key_label, dof_label, joint_label

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from imgui_bundle import imgui  # noqa: E402

from jackpy.ui import session  # noqa: E402
from jackpy.ui.app import App  # noqa: E402
from jackpy.ui.panels import analysis as ap  # noqa: E402
from jackpy.ui.scene_view import SegmentPick  # noqa: E402
from jackpy.ui.window import Window  # noqa: E402

STEP = 14  # px between hover points (less than one widget row)


def conflicts_while_sweeping(win, extra=None):
    """ImGui reports an ID conflict for the hovered item only: hover a grid over the window."""
    io, g = imgui.get_io(), imgui.get_current_context()
    found = 0
    for y in range(20, 800, STEP):
        for x in range(4, 1280, STEP):
            io.add_mouse_pos_event(float(x), float(y))
            win.panels_frame(extra)
            found += g.debug_draw_id_conflicts_count
    return found


def test_every_panel_and_section_has_no_id_conflict(request):
    if in_child_process(request):
        return
    env, _ = session.default_scene()
    app = App(env)
    win = Window(app, "jackpy panels", (1280, 800), visible=False)
    try:
        assert imgui.get_io().config_debug_highlight_id_conflicts
        for title in win.ui.open_panels:
            win.ui.open_panels[title] = True
        win.ui.panel_state("Analysis", ap.DEFAULTS)["open_all"] = True
        app.analysis.strength_live = True
        app.select(SegmentPick(app.figure_of_interest().name, "right_forearm"))  # opens its joint
        for _ in range(3):
            win.frame()

        def twins():  # the negative control: two buttons with one ID
            imgui.set_next_window_pos((300, 300))
            imgui.begin("twins")
            imgui.button("Reach")
            imgui.button("Reach")
            imgui.end()

        assert conflicts_while_sweeping(win, twins) > 0  # the sweep finds a conflict when there is one
        assert conflicts_while_sweeping(win) == 0
    finally:
        win.close()


def test_dofs_are_named_for_people():
    assert dof_label("right_shoulder", 1) == "right shoulder elevation"
    assert dof_label("left_elbow", 0) == "left elbow flexion"
    assert dof_key_label("right_clavicle[1]") == "right clavicle protraction"
    assert joint_label("l4_l5") == "L4-L5"
    assert dof_label("hinge", 2) == "hinge DOF 3"  # not a human joint: numbered from 1
