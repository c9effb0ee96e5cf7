"""Mouse presets (jackpy's, Blender's, Maya's): the bindings, the preference applied to every
document, and Maya's Alt-drag moving the camera even over the figure (headless App)."""

import numpy as np

from jackpy.ui import session
from jackpy.ui.app import MOD_ALT, MOUSE_LEFT, MOUSE_RIGHT, PRESS, RELEASE, App
from jackpy.ui.camera import NavAction, navigation_action
from jackpy.ui.panels.preferences import set_mouse_preset
from jackpy.ui.preferences import Preferences


def test_the_presets_bind_as_their_programs_do():
    assert navigation_action("default", "left") is NavAction.ORBIT
    assert navigation_action("default", "right") is NavAction.PAN
    assert navigation_action("blender", "middle") is NavAction.ORBIT
    assert navigation_action("blender", "middle", {"shift"}) is NavAction.PAN
    assert navigation_action("blender", "middle", {"ctrl"}) is NavAction.ZOOM
    assert navigation_action("blender", "left") is None
    assert navigation_action("maya", "left", {"alt"}) is NavAction.ORBIT
    assert navigation_action("maya", "middle", {"alt"}) is NavAction.PAN
    assert navigation_action("maya", "right", {"alt"}) is NavAction.ZOOM
    assert navigation_action("maya", "left") is None


def test_the_preference_is_saved_and_applies_to_opened_documents(tmp_path):
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    set_mouse_preset(app, "maya")
    assert Preferences.load().mouse_preset == "maya"
    app.settings.mouse_mapping = "default"
    session.save_session(app, tmp_path / "s.env")  # the file says "default"
    session.open_session(app, tmp_path / "s.env")
    assert app.settings.mouse_mapping == "maya"  # the user's preset wins


def test_maya_alt_drag_orbits_over_the_figure_and_right_zooms():
    env, base = session.default_scene()
    app = App(env)
    set_mouse_preset(app, "maya")
    fig = app.figure_of_interest()
    q0, loc0 = fig.q.copy(), fig.location.copy()
    centre = app.world_to_pixel(fig.site_world("pelvis", "centre")[:3, 3])  # on the figure
    app.on_cursor_pos(*centre)
    yaw = app.camera.yaw
    app.on_mouse_button(MOUSE_LEFT, PRESS, MOD_ALT)
    app.on_cursor_pos(centre[0] + 80, centre[1])
    app.on_mouse_button(MOUSE_LEFT, RELEASE, MOD_ALT)
    assert app.camera.yaw != yaw
    assert np.array_equal(fig.q, q0) and np.array_equal(fig.location, loc0) and app.undo_stack.undo_label is None
    dist = app.camera.distance
    app.on_mouse_button(MOUSE_RIGHT, PRESS, MOD_ALT)
    app.on_cursor_pos(centre[0] + 80, centre[1] - 60)
    app.on_mouse_button(MOUSE_RIGHT, RELEASE, MOD_ALT)
    assert app.camera.distance != dist
