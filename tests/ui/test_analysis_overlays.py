"""Analysis overlays in the 3-D view, rendered offscreen: the translucent workspace envelope, view
cones from the eyes, red colliding segments, torque colouring that follows the load."""

from pathlib import Path

import numpy as np
import pytest
from ui_support import offscreen_renderer_or_skip

from jackpy.analysis import Workspace, eye_view
from jackpy.ui.analysis_overlays import (
    COLLISION_COLOUR,
    CONE_MESH,
    WORKSPACE_MESH,
    recolour_items,
    segment_strength_colours,
    unit_cone,
    view_cone_items,
    workspace_items,
    workspace_mesh,
)
from jackpy.render import DrawItem, Scene, box

W, H = 320, 240
EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


@pytest.fixture(scope="module")
def renderer():
    r = offscreen_renderer_or_skip(W, H)
    yield r
    r.release()


def workplace_app(renderer, size=(W, H)):
    from jackpy.body import make_human
    from jackpy.scene.workplace import load_workplace, stand_figure
    from jackpy.ui.app import App

    wp = load_workplace(EXAMPLE)
    human = make_human("female", 50)
    stand_figure(human, wp.stand)
    wp.env.add(human)
    return App(wp.env, renderer, size), human


def sphere_workspace(radius=0.3, n=24) -> Workspace:
    cell = 2.0 * radius * 1.2 / n
    origin = np.full(3, -0.5 * n * cell)
    c = origin + (np.indices((n, n, n)).reshape(3, -1).T + 0.5) * cell
    occ = (np.linalg.norm(c, axis=1) <= radius).reshape(n, n, n)
    return Workspace(occ, origin, cell, 0, True, False)


def draw(renderer, scene, eye=(0.0, 0.0, 3.0), target=(0.0, 0.0, 0.0)):
    from jackpy.render.projection import look_at
    from jackpy.ui.camera import OrbitCamera

    cam = OrbitCamera(target=np.asarray(target, float), distance=3.0)
    renderer.render(scene, look_at(np.asarray(eye, float), np.asarray(target, float)),
                    cam.projection_matrix(renderer.aspect))
    return renderer.read_pixels()[..., :3].astype(int)


def test_workspace_envelope_is_translucent(renderer):
    renderer.add_mesh(WORKSPACE_MESH, workspace_mesh(sphere_workspace().surface()), replace=True)
    renderer.add_mesh("wall", box((2.0, 2.0, 0.05)), replace=True)
    wall = DrawItem("wall", _at(0, 0, -0.6), (0.9, 0.2, 0.1, 1.0))
    base = Scene(items=[wall], grid=None, background=(0.1, 0.1, 0.1, 1.0))
    plain = draw(renderer, base)
    env = draw(renderer, Scene(items=[wall] + workspace_items(), grid=None, background=(0.1, 0.1, 0.1, 1.0)))
    centre = env[H // 2, W // 2]
    assert np.array_equal(env[5, 5], plain[5, 5])          # outside the envelope: unchanged
    assert centre[2] > plain[H // 2, W // 2][2] + 20        # tinted blue ...
    assert centre[0] > 60                                   # ... but the red wall still shows through
    assert centre[0] < plain[H // 2, W // 2][0]


def _at(x, y, z):
    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t


def test_view_cones_open_from_the_eyes_along_the_gaze(renderer):
    from jackpy.body import make_human

    fig = make_human("male", 50)
    ev = eye_view(fig)
    items = view_cone_items(ev, length=0.6)
    assert [it.transparent for it in items] == [True] * 3 and all(it.mesh == CONE_MESH for it in items)
    for it in items:  # apex at the eye, axis (mesh +y) along the gaze
        assert np.allclose(it.transform[:3, 3], ev.position)
        axis = it.transform[:3, 1] / np.linalg.norm(it.transform[:3, 1])
        assert np.allclose(axis, ev.forward, atol=1e-9)
    widths = [np.linalg.norm(it.transform[:3, 0]) for it in items]
    assert widths == sorted(widths, reverse=True)  # widest first (binocular, 35 deg, optimum)
    assert np.isclose(widths[-1], 0.6 * np.tan(np.radians(15)))
    renderer.add_mesh(CONE_MESH, unit_cone(), replace=True)
    side = ev.position + np.array([2.5, 0.0, 0.3])
    target = ev.position + 0.3 * ev.forward
    bg = (0.1, 0.1, 0.1, 1.0)
    empty = draw(renderer, Scene(grid=None, background=bg), side, target)
    cones = draw(renderer, Scene(items=items, grid=None, background=bg), side, target)
    changed = np.any(np.abs(cones - empty) > 8, axis=2)
    assert changed[H // 2, W // 2]                      # the gaze line passes through the cones
    assert changed.sum() > 0.05 * W * H
    assert not changed[2, 2] and not changed[H - 3, 2]


def test_recolour_items_only_touches_named_segments():
    items = [DrawItem("fig:a/arm", np.eye(4)), DrawItem("fig:a/leg", np.eye(4)), DrawItem("fig:b/arm", np.eye(4))]
    out = recolour_items(items, "a", {"arm": COLLISION_COLOUR}, lambda f, s: f"fig:{f}/{s}")
    assert tuple(out[0].color) == COLLISION_COLOUR
    assert out[1] is items[1] and out[2] is items[2]
    assert tuple(items[0].color) != COLLISION_COLOUR  # the input is not edited


def test_strength_colours_follow_the_load():
    from jackpy.analysis import (
        Load,
        dof_strengths,
        joint_torques,
        joint_utilisation,
        utilisation,
    )
    from jackpy.body import make_human
    from jackpy.body.strength import strength_table

    fig = make_human("female", 50)
    table = dof_strengths(strength_table(fig))

    def colours(kg):
        loads = [Load.held_mass(fig, "right_palm", "grip", kg)] if kg else []
        return segment_strength_colours(fig, joint_utilisation(fig, utilisation(fig, joint_torques(fig, loads), table)))

    light, heavy = colours(0.0), colours(15.0)
    assert light["right_palm"] != heavy["right_palm"]
    assert heavy["right_palm"][0] < light["right_palm"][0] or heavy["right_palm"] == (0.9, 0.05, 0.05, 1.0)
    assert light["left_palm"] == heavy["left_palm"]  # the other hand carries nothing more


def test_torque_colouring_in_the_view_changes_with_load(renderer):
    app, fig = workplace_app(renderer)
    app.camera.set_preset("front")
    app.frame_all()
    st = app.analysis
    st.torque_colouring = True
    app.step()
    plain = renderer.read_pixels()[..., :3].astype(int)
    st.load_kg = 20.0
    app.step()
    loaded = renderer.read_pixels()[..., :3].astype(int)
    assert st.strength is not None and st.strength.bars
    assert np.any(np.abs(loaded - plain) > 20, axis=2).sum() > 20


def test_colliding_segments_are_drawn_red_while_posed(renderer):
    app, fig = workplace_app(renderer)
    app.camera.set_preset("front")
    app.frame_all()
    st = app.analysis
    st.clearance_on, st.clearance_object = True, "desk"
    app.step()
    assert st.clearance is not None and st.clearance.distance > 0 and not st.colliding

    def reds():
        img = renderer.read_pixels()[..., :3].astype(int)
        return int(((img[..., 0] > 170) & (img[..., 1] < 80) & (img[..., 2] < 80)).sum())

    before = reds()
    desk = app.env.figures["desk"]
    hand = fig.site_world("right_palm", "grip")[:3, 3]
    # move the desk's top through the right hand: the next frame (as during a drag) shows it red
    v = desk.world_mesh().vertices
    top_centre = np.array([(v[:, 0].min() + v[:, 0].max()) / 2, v[:, 1].max(), (v[:, 2].min() + v[:, 2].max()) / 2])
    desk.location = desk.location.copy()
    desk.location[:3, 3] += hand - top_centre + [0.0, 0.01, 0.0]
    app.step()
    assert st.colliding and any("palm" in s or "hand" in s or "finger" in s or "forearm" in s for s in st.colliding)
    assert st.clearance.distance == 0.0
    assert reds() > before + 30


def test_screenshot_with_envelope_and_cones(renderer, tmp_path):
    from jackpy.ui.panels.analysis import start_workspace

    app, fig = workplace_app(renderer)
    app.camera.set_preset("iso")
    app.frame_all()
    st = app.analysis
    st.resolution, st.show_cones = 20, True
    job = start_workspace(app)
    job.join()
    assert job.error is None and job.result.surface is not None
    app.step()  # collects the result (posted to the main thread) and draws it
    assert st.workspace is not None
    with_overlays = renderer.read_pixels()
    st.show_workspace, st.show_cones = False, False
    app.step()
    without = renderer.read_pixels()
    assert np.any(np.abs(with_overlays[..., :3].astype(int) - without[..., :3]) > 10, axis=2).sum() > 0.05 * W * H
    from jackpy.render import write_png

    write_png(tmp_path / "envelope_and_cones.png", with_overlays)
