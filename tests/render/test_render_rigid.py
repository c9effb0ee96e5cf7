"""Rigid items merged into one draw: which items merge, and that the merged draw is the same image,
ID buffer and picks as drawing them one by one."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.render import DrawItem, Renderer, Scene, box, create_egl_context, look_at, perspective_matrix, uv_sphere
from jackpy.render.mesh import Mesh
from jackpy.render.rigid import MIN_ITEMS, rigid_mask, split_rigid


def _rot_y(a: float, t=(0.0, 0.0, 0.0)) -> np.ndarray:
    m = np.eye(4)
    m[[0, 0, 2, 2], [0, 2, 0, 2]] = np.cos(a), np.sin(a), -np.sin(a), np.cos(a)
    m[:3, 3] = t
    return m


def test_rigid_mask_accepts_rotations_and_translations_only():
    scaled, mirrored, projective = np.diag([2.0, 1, 1, 1]), np.diag([-1.0, 1, 1, 1]), np.eye(4)
    projective[3, 0] = 0.1
    mask = rigid_mask(np.array([np.eye(4), _rot_y(0.7, (1, 2, 3)), scaled, mirrored, projective]))
    assert mask.tolist() == [True, True, False, False, False]
    assert rigid_mask(np.zeros((0, 4, 4))).tolist() == []


def test_split_merges_singleton_opaque_rigid_items_and_keeps_the_rest_in_order():
    items = [DrawItem("a", np.eye(4)), DrawItem("b", _rot_y(0.3)), DrawItem("s", np.eye(4)),
             DrawItem("s", _rot_y(1.0)),  # a mesh drawn twice: stays instanced
             DrawItem("c", np.eye(4), transparent=True), DrawItem("d", np.eye(4), wireframe=True),
             DrawItem("e", np.diag([1.0, 2.0, 1.0, 1.0])),  # scaled: its normals need the cofactor
             DrawItem("f", np.eye(4)), DrawItem("vc", np.eye(4))]
    kept, merged = split_rigid(items, {"a", "b", "s", "c", "d", "e", "f"})  # "vc": not mergeable
    assert [i.mesh for i in merged] == ["a", "b", "f"]
    assert [i.mesh for i in kept] == ["s", "s", "c", "d", "e", "vc"]
    kept, merged = split_rigid(items[:MIN_ITEMS - 1], {"a"})
    assert merged == [] and kept == items[:MIN_ITEMS - 1]


def _scene(highlight: bool = False) -> Scene:
    items = [DrawItem("ball", _rot_y(0.4, (-0.5, 0.5, 0.0)), (0.9, 0.3, 0.2, 1.0), pick_id=1),
             DrawItem("box", _rot_y(-0.6, (0.4, 0.4, 0.1)), (0.3, 0.8, 0.4), pick_id=2, highlighted=highlight),
             DrawItem("slab", _rot_y(0.1, (0.0, 0.05, 0.0)), (0.6, 0.6, 0.7, 1.0), pick_id=1_000_007),
             DrawItem("tinted", _rot_y(0.2, (0.0, 1.0, -0.3)), (1.0, 1.0, 1.0, 1.0), pick_id=3),
             DrawItem("box", _rot_y(0.9, (0.5, 1.1, -0.2)), (0.5, 0.5, 0.9, 1.0), pick_id=4)]
    return Scene(items=items)


@pytest.fixture(scope="module")
def renderer():
    try:
        ctx = create_egl_context()
    except Exception as exc:  # pragma: no cover - no EGL on this machine
        pytest.skip(f"no EGL context: {exc}")
    r = Renderer(ctx, (160, 120), samples=0)
    r.add_mesh("ball", uv_sphere(0.3, rings=10, sectors=16))
    r.add_mesh("box", box((0.3, 0.2, 0.25)))
    r.add_mesh("slab", box((1.6, 0.1, 0.8)))
    b = uv_sphere(0.2, rings=6, sectors=8)
    r.add_mesh("tinted", Mesh(b.vertices, b.normals, b.indices, np.full_like(b.vertices, 0.5)))  # vertex colours
    yield r
    r.release()
    ctx.release()


VIEW = look_at(np.array([1.2, 1.4, 2.4]), np.array([0.0, 0.5, 0.0]))
PROJ = perspective_matrix(np.radians(45), 160 / 120, 0.05, 20.0)


def _frame(r: Renderer, merge: bool, scene: Scene) -> tuple[np.ndarray, np.ndarray, list]:
    r.merge_rigid = merge
    r.render(scene, VIEW, PROJ)
    picks = [r.pick(x, y) for x in range(0, 160, 8) for y in range(0, 120, 8)]
    return r.read_pixels(), r.read_ids()[0], picks


@pytest.mark.parametrize("highlight", [False, True])
def test_the_merged_draw_is_the_same_image_ids_and_picks(renderer, highlight):
    scene = _scene(highlight)
    one_by_one = _frame(renderer, False, scene)
    merged = _frame(renderer, True, scene)
    assert len(renderer._rigid_names) == 1  # ball and slab merged ("box" twice, "tinted" coloured: not)
    assert np.array_equal(one_by_one[0], merged[0])
    assert np.array_equal(one_by_one[1], merged[1])
    assert one_by_one[2] == merged[2]
    assert {1, 1_000_007} <= set(np.unique(merged[1]))  # the merged items are in the ID buffer
    assert one_by_one[0][..., :3].std() > 10  # a picture, not a blank


def test_a_moved_item_is_drawn_where_it_went_and_the_batch_is_reused(renderer):
    scene = _scene()
    _frame(renderer, True, scene)
    names = set(renderer._rigid_names)
    scene.items[0].transform = _rot_y(0.4, (-0.2, 0.9, 0.3))
    moved = _frame(renderer, True, scene)
    assert set(renderer._rigid_names) == names  # same items: the same merged buffer
    assert np.array_equal(moved[0], _frame(renderer, False, scene)[0])


def test_changed_sets_of_items_get_their_own_batches_within_the_cache(renderer):
    from jackpy.render.renderer import RIGID_CACHE

    base = _scene()
    for k in range(RIGID_CACHE + 2):
        extra = f"extra{k}"
        renderer.add_mesh(extra, box((0.05, 0.05, 0.05)))
        scene = Scene(items=base.items + [DrawItem(extra, _rot_y(0.0, (0.8, 0.2 + 0.1 * k, 0.4)), pick_id=50 + k)])
        image = _frame(renderer, True, scene)
        assert len(renderer._rigid_names) <= RIGID_CACHE
        assert np.array_equal(image[0], _frame(renderer, False, scene)[0])
        assert renderer.pick(*_pixel_of(np.array([0.8, 0.2 + 0.1 * k, 0.4]))) == 50 + k


def _pixel_of(p: np.ndarray) -> tuple[int, int]:
    clip = PROJ @ VIEW @ np.append(p, 1.0)
    ndc = clip[:3] / clip[3]
    return int((ndc[0] + 1) * 0.5 * 160), int((1 - ndc[1]) * 0.5 * 120)
