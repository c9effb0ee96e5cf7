"""The Analysis panel's actions, driven directly: workspace job (progress, cancel by the callback),
point reach, visibility, the one-click report; and the panel drawn in a real window (Xvfb)."""

import json
import os
from pathlib import Path

import numpy as np
import pytest
from ui_support import in_child_process, offscreen_renderer_or_skip

from jackpy.ui.panels import analysis as ap

W, H = 240, 180
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


@pytest.fixture(scope="module")
def renderer():
    r = offscreen_renderer_or_skip(W, H)
    yield r
    r.release()


def workplace_env():
    from jackpy.body import make_human
    from jackpy.scene.workplace import load_workplace, stand_figure

    wp = load_workplace(EXAMPLE)
    human = make_human("female", 50)
    stand_figure(human, wp.stand)
    wp.env.add(human)
    return wp.env, human


def make_app(renderer):
    from jackpy.ui.app import App

    env, human = workplace_env()
    return App(env, renderer, (W, H)), human


def test_workspace_job_is_cancelled_by_its_progress_callback(renderer):
    app, fig = make_app(renderer)
    job = ap.start_workspace(app, start=False)
    ap.cancel_workspace(app)  # Cancel pressed before the first batch is reported
    job.start()
    job.join()
    assert job.error is None and job.reports == 1  # the first callback answered False
    ws = job.result.workspace
    assert ws.cancelled and not ws.converged and ws.samples == 1 << 16
    app.step()
    assert app.analysis.workspace is None  # a cancelled job shows nothing


def test_workspace_job_reports_progress_and_classifies_sites(renderer):
    app, fig = make_app(renderer)
    q0 = fig.q.copy()
    app.analysis.resolution = 16
    job = ap.start_workspace(app)
    job.join()
    assert job.done and job.error is None and job.reports >= 2 and job.progress == 1.0
    assert np.array_equal(fig.q, q0)  # the job worked on a copy
    app.step()
    res = app.analysis.workspace
    assert res is not None and res.hand == "right" and res.workspace.volume() > 0.1
    assert set(res.sites) == {"desk.button", "desk.far_corner", "shelf.box_handle", "panel.switch"}
    assert res.sites["desk.button"][0] and not res.sites["desk.far_corner"][0]


def test_point_reach_describes_the_result_and_applies_the_posture(renderer):
    app, fig = make_app(renderer)
    q0 = fig.q.copy()
    near = ap.reach_target(app, "desk.button")
    assert near.reached and near.describe().startswith("reached (")
    assert np.array_equal(fig.q, q0)
    ap.apply_reach(app)
    assert np.allclose(fig.q, near.q)
    app.undo()
    assert np.array_equal(fig.q, q0)
    far = ap.reach_target(app, "desk.far_corner")
    assert not far.reached and far.describe().startswith("blocked by partition")  # collision-aware (issue 16)


def test_visibility_names_the_occluder(renderer):
    app, fig = make_app(renderer)
    assert "gauge" in ap.view_targets(app.env) and "panel.switch" in ap.view_targets(app.env)
    v = ap.measure_visibility(app, "gauge")
    assert v.fraction < 0.5 and "partition" in v.occluders
    assert ap.measure_visibility(app, "panel.switch").fraction > 0.9
    assert app.analysis.visibility.target == "panel.switch"


def test_report_button_writes_the_report(renderer, tmp_path):
    app, fig = make_app(renderer)
    app.analysis.load_kg = 5.0
    job = ap.start_report(app, tmp_path / "rep", "female:50", resolution=12)
    for _ in range(100_000):  # the worker's pictures are rendered here, on the main thread
        if job.done:
            break
        app.step()
        job.join(0.01)
    assert job.done and job.error is None, job.error
    assert job.progress == 1.0
    out = tmp_path / "rep"
    assert (out / "report.html").is_file() and (out / "results.csv").is_file()
    res = json.loads((out / "results.json").read_text())
    assert res["load_kg"] == 5.0 and len(res["figures"]) == 1
    r = res["figures"][0]
    assert set(r["reach"]) == {"desk.button", "desk.far_corner", "shelf.box_handle", "panel.switch"}
    assert set(r["view"]) == {"desk", "shelf", "panel", "gauge", "partition"}
    assert {"female50-overall.png", "female50-eye.png", "female50-reach.png"} <= {p.name for p in out.iterdir()}
    from jackpy.errors import JackpyError

    with pytest.raises(JackpyError):
        ap.start_report(app, tmp_path / "x", "robot:50")


def test_analysis_panel_and_eye_view_in_a_window(request):
    """Every section open, a workspace job and the eye view, in a real window (own process: GLX)."""
    if not os.environ.get("DISPLAY"):
        pytest.skip("needs an X display (xvfb-run)")
    if in_child_process(request):
        return
    from jackpy.ui.app import App
    from jackpy.ui.window import Window

    env, fig = workplace_env()
    app = App(env)
    win = Window(app, "jackpy analysis", (1000, 700), visible=False)
    try:
        win.ui.open_panels.update({"Analysis": True, "Eye view": True})
        st = app.analysis
        st.strength_live, st.torque_colouring, st.load_kg = True, True, 5.0
        st.clearance_on, st.show_cones, st.resolution = True, True, 12
        win.ui.panel_state("Analysis", ap.DEFAULTS)["open_all"] = True  # every section drawn
        job = ap.start_workspace(app)
        job.join()
        for _ in range(4):
            win.frame()
        assert st.workspace is not None and st.eye_viewport is not None and st.eye_viewport.error is None
        assert st.strength is not None and st.clearance is not None
        pixels = np.frombuffer(win.ctx.screen.read(components=3), np.uint8)
        assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50
        from PIL import Image

        shot = os.environ.get("JACKPY_ANALYSIS_SHOT")
        if shot:
            Image.fromarray(pixels.reshape(700, 1000, 3)[::-1]).save(shot)
    finally:
        win.ui.panel_state("Analysis", ap.DEFAULTS)["open_all"] = False
        win.close()
