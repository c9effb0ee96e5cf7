"""The Ergonomics panel's state functions (the imgui drawing only calls them)."""

import pytest

pytest.importorskip("imgui_bundle")

from jackpy.ui.panels import ergonomics as panel  # noqa: E402
from jackpy.ui.panels import panels  # noqa: E402


def test_the_panel_registers_itself():
    assert "Ergonomics" in [p.title for p in panels()]


def test_live_scores_follow_the_posture(poser):
    state = panel.defaults()
    neutral = panel.evaluate(poser.f, state)
    assert set(neutral) == {"rula", "reba", "lowback"} and state["error"] is None
    poser.hinge(40.0)
    for side in ("left", "right"):
        poser.arm(side, 120.0)
    bent = panel.evaluate(poser.f, state)
    assert bent["rula"].score > neutral["rula"].score
    assert bent["lowback"].score > neutral["lowback"].score


def test_task_widgets_and_a_bad_parameter(poser):
    state = panel.defaults()
    state["methods"]["niosh"] = True
    state["load_kg"] = 12.0
    r = panel.evaluate(poser.f, state)
    assert r["niosh"].worksheet["lifts"][0]["load_kg"] == 12.0
    state["lift_frequency"] = 40.0  # off the table: NIOSH's message, the other methods still scored
    r = panel.evaluate(poser.f, state)
    assert "off the NIOSH frequency table" in state["error"]
    assert "niosh" not in r and {"rula", "reba", "lowback"} <= set(r)


def test_highlight_is_the_worst_part_in_its_level_colour(poser):
    state = panel.defaults()
    assert panel.highlight(panel.evaluate(poser.f, state)) == {}  # neutral: every method at its lowest level
    poser.hinge(65.0)
    r = panel.evaluate(poser.f, state)
    colours = panel.highlight(r)
    assert colours and set(colours) <= set(poser.f.segments)
    assert len(set(colours.values())) == 1


def test_history_records_playback_and_restarts(poser):
    state = panel.defaults()
    r = panel.evaluate(poser.f, state)
    for t in (0.0, 0.1, 0.1, 0.2):
        panel.record(state, t, r)
    assert [t for t, _ in state["history"]] == [0.0, 0.1, 0.2]
    ts, vs = panel.series(state, "rula")
    assert ts == [0.0, 0.1, 0.2] and vs == [float(r["rula"].score)] * 3
    panel.record(state, 0.05, r)  # scrubbed back: a new history
    assert [t for t, _ in state["history"]] == [0.05]


def test_draw_in_a_real_imgui_context(poser):
    """The panel drawn by imgui and implot (a context without a window: textures left to a
    renderer that never runs), three frames of playback."""
    from types import SimpleNamespace

    from imgui_bundle import imgui, implot

    from jackpy.ui.panels import UiState

    ctx = imgui.create_context()
    plot = implot.create_context()
    try:
        io = imgui.get_io()
        io.display_size = (1280, 800)
        io.backend_flags |= imgui.BackendFlags_.renderer_has_textures.value
        app = SimpleNamespace(figure_of_interest=lambda: poser.f, doc=SimpleNamespace(time=0.0),
                              analysis=SimpleNamespace(highlight_colours={}))
        poser.hinge(45.0)
        ui = UiState()
        ui.open_panels[panel.TITLE] = True
        for t in (0.0, 0.1, 0.2):
            app.doc.time = t
            imgui.new_frame()
            panel.draw(app, ui)
            imgui.render()
        state = ui.panel_state(panel.TITLE)
        assert len(state["history"]) == 3 and set(state["results"]) == {"rula", "reba", "lowback"}
        assert app.analysis.highlight_colours  # the bent trunk's worst part is drawn
        ui.open_panels[panel.TITLE] = False
        imgui.new_frame()
        panel.draw(app, ui)  # closed: clears the highlight
        imgui.render()
        assert app.analysis.highlight_colours == {}
    finally:
        implot.destroy_context(plot)
        imgui.destroy_context(ctx)
