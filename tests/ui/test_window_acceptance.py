"""Issue 5 acceptance in a real glfw window (Xvfb): the same callbacks glfw calls, frame by frame.

Open the default scene (the 50th-percentile male beside a chair and a work table), pick the right
hand, drag it 20 cm along +x with the left button: the behaviors follow (the body leans, balance
holds), the hand ends within 1 cm of the target, the planted feet neither move nor turn, every joint
stays within its limits; undo restores the posture exactly; save (the generated human's surfaces
written beside the scene), reopen, same posture.
"""

import os

import numpy as np
import pytest
from ui_support import in_child_process

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from jackpy.ui import session  # noqa: E402
from jackpy.ui.app import (MOD_CONTROL, MOUSE_LEFT, PRESS, RELEASE, App, effector_segments,  # noqa: E402
                           find_effectors)
from jackpy.ui.window import Window  # noqa: E402




@pytest.fixture
def window(request):
    if in_child_process(request):
        yield None
        return
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    win = Window(app, "jackpy test", (1024, 768), visible=False)
    app.camera.set_preset("front")
    win.frame()
    yield win
    win.close()


def site_world(fig, site):
    return fig.site_world(*site.split(".", 1))


def test_drag_hand_undo_save_reopen(window, tmp_path):
    if window is None:
        return
    app = window.app
    h = window.handle
    fig = app.figure_of_interest()
    eff = find_effectors(fig)
    hand, feet = eff["right_hand"], [eff["right_foot"], eff["left_foot"]]
    q0 = fig.q.copy()
    feet0 = [site_world(fig, f).copy() for f in feet]
    start = site_world(fig, hand)[:3, 3].copy()
    target = start + [0.2, 0.0, 0.0]
    p0, p1 = app.world_to_pixel(start), app.world_to_pixel(target)

    window.cursor_pos_callback(h, *window.view_to_window(p0))
    window.frame()
    window.mouse_button_callback(h, MOUSE_LEFT, PRESS, 0)
    assert app.selection is not None
    assert effector_segments(fig, eff)[app.selection.segment] == "right_hand"  # palm or thumb
    for t in np.linspace(0.0, 1.0, 12)[1:]:
        window.cursor_pos_callback(h, *window.view_to_window(p0 + t * (p1 - p0)))
        window.frame()
    window.mouse_button_callback(h, MOUSE_LEFT, RELEASE, 0)
    # until the posture settles: a few frames on an idle machine; on a loaded one the frame budget
    # cuts the solves short and the figure takes more frames (under load 3-4 on 2 cores, 55-131)
    for _ in range(300):
        window.frame()
        if not app.needs_solve:
            break
    assert not app.needs_solve

    assert np.linalg.norm(site_world(fig, hand)[:3, 3] - target) < 0.01
    for f, w in zip(feet, feet0):
        assert np.allclose(site_world(fig, f), w, atol=1e-6)
    assert fig.name in app.loops and app.last_report is not None  # the behaviors did it
    assert np.all(fig.q >= fig.lower - 1e-9) and np.all(fig.q <= fig.upper + 1e-9)
    dragged = fig.q.copy()

    window.key_callback(h, ord("Z"), 0, PRESS, MOD_CONTROL)
    window.frame()
    assert np.array_equal(fig.q, q0)
    window.key_callback(h, ord("Y"), 0, PRESS, MOD_CONTROL)
    window.frame()
    assert np.array_equal(fig.q, dragged)

    path = tmp_path / "scene.env"
    app.session_path = path
    window.key_callback(h, ord("S"), 0, PRESS, MOD_CONTROL)  # Ctrl+S saves to the session path
    assert path.is_file()
    fig.q = q0
    session.open_session(app, path)
    window.frame()
    reopened = app.figure_of_interest()
    assert np.array_equal(reopened.q, dragged)
    assert np.linalg.norm(site_world(reopened, hand)[:3, 3] - target) < 0.01


def test_empty_space_drag_orbits_and_wheel_zooms(window):
    if window is None:
        return
    app, h = window.app, window.handle
    yaw, dist = app.camera.yaw, app.camera.distance
    window.cursor_pos_callback(h, *window.view_to_window((200, 30)))  # empty space in the 3-D view
    window.frame()
    window.mouse_button_callback(h, MOUSE_LEFT, PRESS, 0)
    window.cursor_pos_callback(h, *window.view_to_window((290, 30)))
    window.mouse_button_callback(h, MOUSE_LEFT, RELEASE, 0)
    window.scroll_callback(h, 0.0, 2.0)
    window.frame()
    assert app.camera.yaw != yaw and app.camera.distance < dist
    assert app.undo_stack.undo_label is None
