"""The skins' coarse level of detail: what it keeps, and which frames draw it."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.body import make_human
from jackpy.body.skin import skins_for
from jackpy.peabody import Environment
from jackpy.render import Renderer, SkinnedMesh, create_egl_context, look_at, perspective_matrix
from jackpy.render.skinning import COARSE_FRACTION, coarse_indices
from jackpy.ui.scene_view import SceneView


@pytest.fixture(scope="module")
def human():
    fig = make_human("male", 50)
    env = Environment()
    env.figures[fig.name] = fig
    return fig, env


def test_coarse_skin_reuses_vertices_within_budget_and_stays_close(human):
    fig, _ = human
    for skin in skins_for(fig):
        mesh = SkinnedMesh.of(skin)
        c = coarse_indices(mesh)
        assert 0 < len(c) <= COARSE_FRACTION * len(mesh.indices)
        assert c.max() < len(mesh.vertices)
        assert np.all((c[:, 0] != c[:, 1]) & (c[:, 1] != c[:, 2]) & (c[:, 0] != c[:, 2]))
        kept = mesh.vertices[np.unique(c)]
        # every rest vertex lies near a kept one (about one cell: a few centimetres)
        d = np.min(np.linalg.norm(mesh.vertices[:, None, :] - kept[None, ::3, :], axis=2), axis=1)
        assert np.max(d) < 0.08
        # the coarse surface keeps the bounding box within a cell
        assert np.allclose(kept.min(axis=0), mesh.vertices.min(axis=0), atol=0.04)
        assert np.allclose(kept.max(axis=0), mesh.vertices.max(axis=0), atol=0.04)


def _draw(renderer, view, env, fig, nudge):
    c = fig.world_transforms()["t6"][:3, 3]
    renderer.render(view.build(env), look_at(c + [1.6, 0.3, 1.2 + nudge], c),
                    perspective_matrix(np.radians(40), 1.0, 0.05, 10.0))


def test_moving_small_frames_draw_the_coarse_skin_still_frames_the_full(human):
    fig, env = human
    try:
        ctx = create_egl_context()
    except Exception as exc:  # no EGL device at all
        pytest.skip(f"no EGL OpenGL context available: {exc}")
    r = Renderer(ctx, (160, 160), samples=0)
    view = SceneView()
    view.upload(r, env)
    gpu = r._skinned[view.skin_key(fig.name, 0)]
    try:
        r.render_scale = 0.5
        _draw(r, view, env, fig, 0.0)
        assert gpu.drawn_count == gpu.coarse_count < gpu.index_count
        small = r.read_pixels()  # a read-back redraws at full size: the full skin
        assert gpu.drawn_count == gpu.index_count
        r.render_scale = 0.75  # above coarse_skin_scale: the full skin even while moving
        _draw(r, view, env, fig, 1e-3)
        assert gpu.drawn_count == gpu.index_count
        r.render_scale, r.coarse_skin_scale = 0.5, 0.0  # switched off
        _draw(r, view, env, fig, 2e-3)
        assert gpu.drawn_count == gpu.index_count
        r.coarse_skin_scale = 0.5
        _draw(r, view, env, fig, 3e-3)
        assert gpu.drawn_count == gpu.coarse_count
        assert r.refine()  # the still frame: full size, full skin
        assert gpu.drawn_count == gpu.index_count
        # the full-size picture does not depend on the coarse level having been drawn before
        r.render_scale = 1.0
        _draw(r, view, env, fig, 0.0)
        assert np.array_equal(r.read_pixels(), small)
    finally:
        r.release()


@pytest.mark.parametrize("nearest", [True, False])
def test_a_small_frame_is_stretched_with_the_stretch_filter(human, nearest):
    import moderngl

    fig, env = human
    try:
        ctx = create_egl_context()
    except Exception as exc:  # no EGL device at all
        pytest.skip(f"no EGL OpenGL context available: {exc}")
    r = Renderer(ctx, (160, 160), samples=0)
    assert r.stretch_filter == (moderngl.NEAREST if r.software else moderngl.LINEAR)
    r.stretch_filter = moderngl.NEAREST if nearest else moderngl.LINEAR
    view = SceneView()
    view.upload(r, env)
    screen = ctx.framebuffer([ctx.renderbuffer((160, 160), 4)])
    try:
        r.render_scale = 0.5
        _draw(r, view, env, fig, 0.0)
        r.blit(screen)
        img = np.frombuffer(screen.read(components=4), np.uint8).reshape(160, 160, 4).astype(int)
        blocks = img.reshape(80, 2, 80, 2, 4)
        doubled = np.all(blocks == blocks[:, :1, :, :1, :])  # every 2x2 block one pixel of the small frame
        assert doubled == nearest
    finally:
        screen.release()
        r.release()
