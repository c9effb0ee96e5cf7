"""Visibility from the eyes (ID-buffer rendering on EGL), view cones and the eye view."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from jackpy.render.bodies import Body, BodyRenderer as OffscreenRenderer
from jackpy.analysis.view import (
    EyeView, environment_bodies, eye_view, object_visibility, point_visibility,
)
from jackpy.errors import JackpyError
from jackpy.peabody import Environment, Mesh
from jackpy.peabody.synthetic import human_like_tree
from jackpy.scene.cad import CADObject, ImportSettings

EYE = np.array([0.0, 1.6, 0.0])


@pytest.fixture(scope="module")
def renderer():
    try:
        r = OffscreenRenderer((160, 160))
    except JackpyError as exc:
        pytest.skip(str(exc))
    yield r
    r.release()


def box(name: str, lo, hi) -> CADObject:
    b = trimesh.creation.box(bounds=[lo, hi])
    return CADObject(name, ImportSettings(f"{name}.stl"), Mesh(b.vertices, b.faces))


def scene(*objects: CADObject) -> Environment:
    env = Environment()
    for o in objects:
        env.add(o)
    return env


def _vis(renderer, env: Environment, target: str):
    tb = environment_bodies(env, exclude=set(env.figures) - {target})
    occ = environment_bodies(env, exclude={target})
    return object_visibility(renderer, EYE, tb, occ, target)


def test_target_in_plain_sight_is_fully_visible(renderer):
    env = scene(box("panel", [-0.1, 1.5, 1.0], [0.1, 1.7, 1.02]), box("wall", [2.0, 0.0, 0.0], [2.1, 2.0, 2.0]))
    v = _vis(renderer, env, "panel")
    assert v.fraction == pytest.approx(1.0, abs=0.01) and v.occluders == {} and v.pixels > 1000


def test_target_behind_an_opaque_box_is_hidden_and_the_box_named(renderer):
    env = scene(box("panel", [-0.1, 1.5, 1.0], [0.1, 1.7, 1.02]), box("crate", [-0.3, 1.2, 0.5], [0.3, 2.0, 0.7]))
    v = _vis(renderer, env, "panel")
    assert v.fraction == 0.0
    assert list(v.occluders) == ["crate"] and v.occluders["crate"] == pytest.approx(1.0)


def test_half_covered_target_is_about_half_visible(renderer):
    # the occluder covers x < 0 of the panel, as seen from the eye on the x = 0 plane
    env = scene(box("panel", [-0.1, 1.5, 1.0], [0.1, 1.7, 1.02]), box("board", [-0.3, 1.3, 0.5], [0.0, 1.9, 0.52]))
    v = _vis(renderer, env, "panel")
    assert v.fraction == pytest.approx(0.5, abs=0.1)
    assert v.occluders["board"] == pytest.approx(1 - v.fraction, abs=1e-9)


def test_site_on_a_surface_is_visible_unless_something_is_in_front(renderer):
    panel = box("panel", [-0.1, 1.5, 1.0], [0.1, 1.7, 1.02])
    panel.add_site("switch", np.array([0.05, 1.6, 1.0]))  # on the face towards the eye
    panel.add_site("back", np.array([0.0, 1.6, 1.02]))  # on the far face
    env = scene(panel)
    occ = environment_bodies(env)
    assert point_visibility(renderer, EYE, panel.site_position("switch"), occ, "panel.switch").fraction == 1.0
    hidden = point_visibility(renderer, EYE, panel.site_position("back"), occ, "panel.back")
    assert hidden.fraction == 0.0 and list(hidden.occluders) == ["panel"]


def test_view_cones_and_eye_view_of_the_synthetic_human():
    ev = EyeView(EYE, np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0]))
    assert ev.cone(EYE + [0, 0, 1]) == "optimum"
    assert ev.cone(EYE + [np.tan(np.radians(25)), 0, 1]) == "maximum eye rotation"
    assert ev.cone(EYE + [1, 0, 1]) == "binocular"
    assert ev.cone(EYE + [1, 0, 0]) == "peripheral"
    assert ev.cone(EYE + [0, 0, -1]) is None
    f = human_like_tree()
    e = eye_view(f)
    head = f.world_transforms()["head"]
    np.testing.assert_allclose(e.position, head[:3, :3] @ [0, 0.1, 0.08] + head[:3, 3])
    np.testing.assert_allclose(e.forward, head[:3, 2])
    v = ev.view_matrix()
    np.testing.assert_allclose(v[:3, :3] @ ev.forward, [0, 0, -1], atol=1e-12)


def test_renderer_shades_and_blends(renderer):
    b = trimesh.creation.box(extents=(1, 1, 1))
    t = np.eye(4)
    t[:3, 3] = (0, 1.6, 3)
    red = Body("red", Mesh(b.vertices, b.faces), t, (1.0, 0.0, 0.0, 1.0))
    ev = EyeView(EYE, np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0]))
    img = renderer.render([red], ev.view_matrix(), ev.projection())
    # red, lit as the workbench lights it (a faint white highlight on top), on the white background
    assert img[80, 80, 0] > 200 and img[80, 80, 0] > 4 * img[80, 80, 1] and tuple(img[0, 0]) == (255, 255, 255)
    assert img[80, 80, 1] == img[80, 80, 2]
    t2 = t.copy()
    t2[2, 3] = 2.0
    glass = Body("glass", Mesh(b.vertices, b.faces), t2, (0.0, 0.0, 1.0, 0.5))
    img = renderer.render([red], ev.view_matrix(), ev.projection(), translucent=[glass])
    assert img[80, 80, 2] > 60 and img[80, 80, 0] > 60  # blue over red
