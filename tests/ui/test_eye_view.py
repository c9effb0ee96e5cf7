"""The eye view: a second renderer on the app's own GL context, seen from the figure's eyes."""

import numpy as np
import pytest
from ui_support import offscreen_renderer_or_skip

from jackpy.analysis import eye_view
from jackpy.ui.eye_view import EYE_VIEW_SIZE, EyeViewport, hidden_segments

W, H = 240, 180


@pytest.fixture(scope="module")
def renderer():
    r = offscreen_renderer_or_skip(W, H)
    yield r
    r.release()


def make_app(renderer):
    from pathlib import Path

    from jackpy.body import make_human
    from jackpy.scene.workplace import load_workplace, stand_figure
    from jackpy.ui.app import App

    wp = load_workplace(Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json")
    human = make_human("male", 50)
    stand_figure(human, wp.stand)
    wp.env.add(human)
    return App(wp.env, renderer, (W, H)), human


def test_head_and_what_hangs_from_it_are_hidden():
    from jackpy.body import make_human

    fig = make_human("male", 50)
    hidden = hidden_segments(fig, "head")
    assert "head" in hidden and "right_palm" not in hidden and "neck" not in hidden
    kin = fig.kinematics()
    for s in hidden - {"head"}:  # every hidden segment descends from the head
        i = kin.segment_index[s]
        while kin.segment_names[i] != "head":
            i = kin.parent[i]
            assert i >= 0


def test_eye_view_renders_on_the_same_context_and_follows_the_figure(renderer):
    app, fig = make_app(renderer)
    st = app.analysis
    st.eye_view_open = True
    app.step()
    vp = st.eye_viewport
    assert isinstance(vp, EyeViewport) and vp.error is None
    assert vp.renderer.ctx is renderer.ctx  # no second context
    assert vp.renderer.size == EYE_VIEW_SIZE and vp.texture_id() > 0
    ahead = vp.read_pixels()[..., :3].astype(int)
    assert len(np.unique(ahead.reshape(-1, 3), axis=0)) > 20  # the workplace, not a blank
    assert np.allclose(vp.eye.position, eye_view(fig).position)
    # turn the figure around: the view follows at the next frame
    turn = np.eye(4)
    turn[0, 0] = turn[2, 2] = -1.0
    fig.location = turn @ fig.location
    app.step()
    behind = vp.read_pixels()[..., :3].astype(int)
    assert np.allclose(vp.eye.forward, eye_view(fig).forward) and vp.eye.forward[2] < -0.9
    assert np.mean(np.any(np.abs(behind - ahead) > 12, axis=2)) > 0.2
    # closed: no more eye renders (the texture keeps the last picture)
    st.eye_view_open = False
    fig.location = turn @ fig.location
    app.step()
    assert np.array_equal(vp.read_pixels()[..., :3], behind)


def test_eye_view_of_a_figure_without_eyes_says_so(renderer):
    from pathlib import Path

    from jackpy.peabody import Environment
    from jackpy.peabody.reader import read_figures
    from jackpy.ui.app import App

    env = Environment()
    for fig in read_figures(Path(__file__).resolve().parents[2] / "figures" / "planar_arm.fig"):
        env.add(fig)
    app = App(env, renderer, (W, H))
    app.analysis.eye_view_open = True
    app.step()
    assert app.analysis.eye_viewport.error
