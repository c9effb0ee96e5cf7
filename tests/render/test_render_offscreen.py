"""Offscreen rendering on EGL, checked by pixels; plus the renderer's pure-numpy geometry."""

import numpy as np
import pytest
from PIL import Image

from jackpy.ui.camera import OrbitCamera
from jackpy.render import (
    DrawItem,
    GoalMarker,
    Lines,
    Mesh,
    Scene,
    Spheres,
    Sticks,
    Triad,
    box,
    cylinder,
    offscreen_renderer,
    uv_sphere,
)
from jackpy.render.instancing import normal_matrices, segment_models
from jackpy.render.mesh import arrow, cone

W, H = 160, 120
BG = (0.1, 0.1, 0.1, 1.0)
BG8 = np.array([26, 26, 26])
RED = (0.9, 0.1, 0.1, 1.0)


# ------------------------------------------------------------------ geometry (no GL)
@pytest.mark.parametrize("mesh", [box((0.3, 0.5, 0.7)), uv_sphere(0.4), cylinder(0.2, 1.0), cone(),
                                  arrow()])
def test_primitive_meshes_wind_outward(mesh: Mesh):
    v, f = mesh.vertices.astype(float), mesh.indices
    geometric = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    area = np.linalg.norm(geometric, axis=1)
    agree = np.einsum("ij,ij->i", geometric, mesh.normals[f].sum(axis=1))
    assert np.all(agree[area > 1e-9] > 0)
    assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1.0, atol=1e-6)


def test_mesh_rejects_bad_indices():
    with pytest.raises(ValueError):
        Mesh(np.zeros((3, 3)), np.zeros((3, 3)), [[0, 1, 3]])


def test_segment_models_stretch_the_unit_y_mesh():
    a, b = np.array([[1.0, 2.0, 3.0], [0, 0, 0]]), np.array([[1.0, 2.0, 5.0], [0, 0, 0]])
    m = segment_models(a, b, 0.1)
    assert np.allclose(m[0] @ [0, 0, 0, 1], [1, 2, 3, 1])
    assert np.allclose(m[0] @ [0, 1, 0, 1], [1, 2, 5, 1])
    assert np.isclose(np.linalg.norm(m[0][:3, :3] @ [1, 0, 0]), 0.1)
    assert np.all(np.isfinite(normal_matrices(m)))  # zero-length stick stays finite


def test_normal_matrix_is_inverse_transpose_up_to_scale():
    rng = np.random.default_rng(3)
    m = np.tile(np.eye(4), (4, 1, 1))
    m[:, :3, :3] = rng.normal(size=(4, 3, 3))
    n = normal_matrices(m)
    for k in range(4):
        expected = np.linalg.inv(m[k, :3, :3]).T * np.linalg.det(m[k, :3, :3])
        assert np.allclose(n[k], expected)


# ------------------------------------------------------------------ offscreen rendering
@pytest.fixture(scope="module")
def egl_context():
    import moderngl

    try:
        ctx = moderngl.create_standalone_context(require=330, backend="egl")
    except Exception as exc:  # no EGL device at all: nothing to render with
        pytest.skip(f"no EGL OpenGL context available: {exc}")
    yield ctx
    ctx.release()


@pytest.fixture
def renderer(egl_context):
    r = offscreen_renderer(W, H, ctx=egl_context)
    r.add_mesh("box", box((0.5, 0.5, 0.5)))
    yield r
    r.release()


def front_camera() -> OrbitCamera:
    return OrbitCamera(target=np.zeros(3), distance=3.0)


def render(r, scene: Scene, cam: OrbitCamera | None = None) -> np.ndarray:
    cam = cam or front_camera()
    r.render(scene, cam.view_matrix(), cam.projection_matrix(r.aspect))
    return r.read_pixels()


def at(x=0.0, y=0.0, z=0.0) -> np.ndarray:
    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t


def rotated_z(angle: float) -> np.ndarray:
    t = np.eye(4)
    c, s = np.cos(angle), np.sin(angle)
    t[:2, :2] = [[c, -s], [s, c]]
    return t


def pixel_of(p, cam: OrbitCamera | None = None) -> tuple[int, int]:
    cam = cam or front_camera()
    clip = cam.projection_matrix(W / H) @ cam.view_matrix() @ np.append(p, 1.0)
    ndc = clip[:3] / clip[3]
    return int((ndc[0] + 1) * 0.5 * W), int((1 - ndc[1]) * 0.5 * H)


def scene(*items, **kw) -> Scene:
    return Scene(items=list(items), grid=None, background=BG, **kw)


def test_box_is_drawn_where_it_projects(renderer):
    img = render(renderer, scene(DrawItem("box", at(0.6, 0.3), RED)))
    assert img.shape == (H, W, 4) and img.dtype == np.uint8
    x, y = pixel_of([0.6, 0.3, 0.25])
    assert x > W // 2 and y < H // 2  # right of centre and in the upper half (first row = top)
    r, g, b, _ = img[y, x].astype(int)
    assert r > 120 and r > 3 * max(g, b)
    mx, my = pixel_of([-0.6, -0.3, 0.25])  # the mirror image is background
    assert np.array_equal(img[my, mx, :3], BG8)
    assert np.array_equal(img[0, 0, :3], BG8)


def test_edges_are_antialiased(renderer):
    img = render(renderer, scene(DrawItem("box", rotated_z(0.3), (1.0, 1.0, 1.0, 1.0))))
    values = img[..., 0].astype(int)
    intermediate = (values > BG8[0] + 10) & (values < values.max() - 30)
    assert intermediate.sum() > 10  # MSAA blends the slanted silhouette into the background


def test_pick_returns_the_id_at_the_box_centre_and_none_on_background(renderer):
    render(renderer, scene(DrawItem("box", at(), RED, pick_id=42)))
    assert renderer.pick(W // 2, H // 2) == 42
    assert renderer.pick(2, 2) is None
    assert renderer.pick(-1, 5) is None and renderer.pick(W, 5) is None


def test_pick_sees_the_nearest_thing(renderer):
    near = DrawItem("box", at(0.0, 0.0, 1.0), RED, pick_id=1)
    far = DrawItem("box", at(0.0, 0.0, -1.0), RED, pick_id=2)
    hidden_by_unpickable = DrawItem("box", at(0.0, 0.0, 1.0), RED)
    render(renderer, scene(far, near))
    assert renderer.pick(W // 2, H // 2) == 1
    render(renderer, scene(far, hidden_by_unpickable))
    assert renderer.pick(W // 2, H // 2) is None


def test_transparency_blends_over_what_is_behind(renderer):
    blue = (0.1, 0.2, 1.0, 0.5)
    opaque = render(renderer, scene(DrawItem("box", at(z=-1.0), RED)))[H // 2, W // 2].astype(int)
    glass = DrawItem("box", at(z=0.8), blue, transparent=True)
    mixed = render(renderer, scene(DrawItem("box", at(z=-1.0), RED), glass))[H // 2, W // 2].astype(int)
    assert mixed[2] > opaque[2] + 40  # the blue glass adds blue
    assert mixed[0] > 40              # and the red box still shows through
    assert mixed[0] < opaque[0]
    # order of the items does not matter: transparent items are drawn after the opaque ones
    again = render(renderer, scene(glass, DrawItem("box", at(z=-1.0), RED)))[H // 2, W // 2].astype(int)
    assert np.allclose(again, mixed, atol=2)
    # transparent volumes do not hide opaque ones from picking unless they have a pick id
    render(renderer, scene(DrawItem("box", at(z=-1.0), RED, pick_id=5), glass))
    assert renderer.pick(W // 2, H // 2) == 5


def test_skeleton_spheres_and_sticks_are_visible_and_pickable(renderer):
    centers = np.array([[-0.5, 0.0, 0.0], [0.5, 0.0, 0.0]])
    img = render(renderer, scene(
        spheres=[Spheres(centers, 0.08, (1.0, 0.9, 0.1, 1.0), pick_ids=[11, 12])],
        sticks=[Sticks(centers[:1], centers[1:], 0.02, (0.2, 1.0, 0.2, 1.0), pick_ids=[13])],
    ))
    for c in centers:
        x, y = pixel_of(c)
        r, g, b, _ = img[y, x].astype(int)
        assert r > 120 and g > 100 and b < 80  # yellow ball
    x, y = pixel_of([0.0, 0.0, 0.0])
    r, g, b, _ = img[y, x].astype(int)
    assert g > 120 and g > 2 * max(r, b)  # green stick in between
    assert renderer.pick(*pixel_of(centers[0])) == 11
    assert renderer.pick(*pixel_of(centers[1])) == 12
    assert renderer.pick(x, y) == 13


def test_triad_axes_are_coloured(renderer):
    img = render(renderer, scene(triads=[Triad(at(), 0.8)]))
    x, y = pixel_of([0.5, 0.0, 0.0])
    r, g, b, _ = img[y, x].astype(int)
    assert r > 2 * max(g, b)
    x, y = pixel_of([0.0, 0.5, 0.0])
    r, g, b, _ = img[y, x].astype(int)
    assert g > 2 * max(r, b)


def test_goal_marker_and_on_top_lines(renderer):
    img = render(renderer, scene(markers=[GoalMarker(np.array([0.0, 0.0, 0.0]), (0.1, 0.9, 0.9, 1.0),
                                                     size=0.3)]))
    x, y = pixel_of([0.2, 0.0, 0.0])
    assert img[y, x, 1] > 100 and img[y, x, 2] > 100
    # an on-top line stays visible in front of an opaque box, a depth-tested one behind it is not
    seg = np.array([[[-1.0, 0.1, -0.5], [1.0, 0.1, -0.5]]])
    box_item = DrawItem("box", at(), RED)
    yellow = (1.0, 1.0, 0.0, 1.0)
    hidden = render(renderer, scene(box_item, lines=[Lines(seg, yellow)]))
    shown = render(renderer, scene(box_item, lines=[Lines(seg, yellow, on_top=True)]))
    x, y = pixel_of([0.0, 0.1, -0.5])
    column = slice(y - 1, y + 2)
    assert shown[column, x, 1].max() > 200
    assert hidden[column, x, 1].max() < 100


def test_wireframe_and_highlight_change_the_look(renderer):
    plain = render(renderer, scene(DrawItem("box", rotated_z(0.5), RED)))
    wire = render(renderer, scene(DrawItem("box", rotated_z(0.5), RED, wireframe=True)))
    lit = render(renderer, scene(DrawItem("box", rotated_z(0.5), RED, highlighted=True)))
    changed = np.any(plain != wire, axis=2)
    assert 20 < changed.sum() < 0.5 * (plain[..., 0] > 60).sum()  # thin edges, not the whole face
    cx, cy = W // 2, H // 2
    assert lit[cy, cx, 1] > plain[cy, cx, 1] + 20  # the highlight tints towards yellow


def test_floor_grid_draws_below_the_horizon_only(renderer):
    cam = OrbitCamera(target=np.array([0.0, 0.5, 0.0]), distance=3.0, pitch=0.35)
    img = render(renderer, Scene(background=BG), cam)
    below = img[H - 30:, :, :3].astype(int)
    above = img[:10, :, :3]
    assert np.any(np.abs(below - BG8).sum(axis=2) > 30)
    assert np.all(above == BG8)


def test_orthographic_view_renders(renderer):
    cam = front_camera()
    cam.orthographic = True
    img = render(renderer, scene(DrawItem("box", at(), RED, pick_id=3)), cam)
    assert img[H // 2, W // 2, 0] > 120
    assert renderer.pick(W // 2, H // 2) == 3


def test_meshes_are_cached_by_key(renderer):
    renderer.add_mesh("box", cylinder())  # kept: the key exists
    img = render(renderer, scene(DrawItem("box", at(), RED)))
    x, y = pixel_of([0.24, 0.24, 0.25])  # a box corner, outside any unit cylinder's silhouette
    assert img[y, x, 0] > 100
    renderer.add_mesh("box", uv_sphere(0.1), replace=True)
    img = render(renderer, scene(DrawItem("box", at(), RED)))
    assert np.array_equal(img[y, x, :3], BG8)
    with pytest.raises(KeyError):
        render(renderer, scene(DrawItem("missing", at(), RED)))


def test_resize_and_save_png(renderer, tmp_path):
    renderer.resize(80, 60)
    img = render(renderer, scene(DrawItem("box", at(), RED)))
    assert img.shape == (60, 80, 4)
    path = tmp_path / "frame.png"
    renderer.save_png(path)
    assert np.array_equal(np.asarray(Image.open(path)), img)


def test_unchanged_frames_are_not_redrawn_and_changes_are(renderer):
    a = scene(DrawItem("box", at(-0.5), RED, pick_id=1), lines=[Lines(np.zeros((1, 2, 3)))])
    b = scene(DrawItem("box", at(0.5), RED, pick_id=1), lines=[Lines(np.zeros((1, 2, 3)))])
    img_a = render(renderer, a)
    drawn = renderer.frames_drawn
    cam = front_camera()
    assert not renderer.render(a, cam.view_matrix(), cam.projection_matrix(renderer.aspect))
    assert renderer.frames_drawn == drawn
    img_b = render(renderer, b)  # the instance moved: drawn, with the new instance data uploaded
    assert renderer.frames_drawn == drawn + 1 and not np.array_equal(img_a, img_b)
    assert np.array_equal(render(renderer, a), img_a)  # and back
    assert renderer.pick(*pixel_of([-0.5, 0.0, 0.25])) == 1
    cam.yaw = 0.2  # a camera move is a change
    assert renderer.render(a, cam.view_matrix(), cam.projection_matrix(renderer.aspect))
    moved_line = scene(DrawItem("box", at(-0.5), RED, pick_id=1), lines=[Lines(np.ones((1, 2, 3)))])
    assert renderer.render(moved_line, cam.view_matrix(), cam.projection_matrix(renderer.aspect))


def test_software_gl_draws_without_msaa_and_refines_a_still_frame(egl_context):
    from jackpy.render import Renderer
    from jackpy.render.renderer import default_samples, is_software_gl

    r = Renderer(egl_context, (W, H))  # automatic, as the window makes it
    try:
        assert r.samples == default_samples(egl_context)
        if not is_software_gl(egl_context):
            assert r.samples == min(4, egl_context.max_samples) and not r.refine_pending
            return
        assert r.samples == 0 and r.still_samples == min(4, egl_context.max_samples)
        assert r.display_triangles is not None
        r.add_mesh("box", box((0.5, 0.5, 0.5)))
        s = scene(DrawItem("box", rotated_z(0.3), (1.0, 1.0, 1.0, 1.0), pick_id=9))
        aliased = render(r, s)
        assert r.drawn_samples == 0 and r.refine_pending
        values = aliased[..., 0].astype(int)
        assert ((values > BG8[0] + 10) & (values < values.max() - 30)).sum() < 10  # hard edges
        assert r.pick(W // 2, H // 2) == 9
        cam = front_camera()
        r.refine_after_s = 0.0  # still at once: the same frame is drawn again, anti-aliased
        assert r.render(s, cam.view_matrix(), cam.projection_matrix(r.aspect))
        assert r.drawn_samples == r.still_samples and not r.refine_pending
        smooth = r.read_pixels()[..., 0].astype(int)
        assert ((smooth > BG8[0] + 10) & (smooth < smooth.max() - 30)).sum() > 10
        assert not r.render(s, cam.view_matrix(), cam.projection_matrix(r.aspect))  # and then kept
        assert r.pick(W // 2, H // 2) == 9
    finally:
        r.release()


def test_msaa_setting_follows_the_gl_renderer_string():
    from types import SimpleNamespace

    from jackpy.render.renderer import default_samples, is_software_gl

    def ctx(name):
        return SimpleNamespace(info={"GL_RENDERER": name}, max_samples=8)

    assert is_software_gl(ctx("llvmpipe (LLVM 15.0.6, 256 bits)"))
    assert is_software_gl(ctx("softpipe"))
    assert not is_software_gl(ctx("NVIDIA GeForce RTX 3060/PCIe/SSE2"))
    assert default_samples(ctx("llvmpipe (LLVM 15.0.6, 256 bits)")) == 0
    assert default_samples(ctx("Mesa Intel(R) UHD Graphics 620 (KBL GT2)")) == 4


def test_cad_display_copy_keeps_to_the_renderers_triangle_budget():
    from jackpy.peabody import Environment
    from jackpy.peabody import Mesh as PeabodyMesh
    from jackpy.scene.cad import CADObject, ImportSettings
    from jackpy.ui.scene_view import SceneView

    class FakeRenderer:
        display_triangles: int | None = 2_000

        def __init__(self):
            self.meshes = {}

        def has_mesh(self, key):
            return key in self.meshes

        def add_mesh(self, key, mesh, replace=False):
            self.meshes[key] = mesh

    m = uv_sphere(0.4, rings=50, sectors=100)  # 10k triangles
    env = Environment()
    cad = env.add(CADObject("cad", ImportSettings("cad.stl"), PeabodyMesh(m.vertices, m.indices)))
    view, r = SceneView(), FakeRenderer()
    view.upload(r, env)
    key = view.mesh_key(cad.name, next(iter(cad.segments)))
    assert 500 < len(r.meshes[key].indices) <= 2_000
    r.display_triangles = None  # a GPU: the object's own budget, here the whole mesh
    view.upload(r, env)
    assert len(r.meshes[key].indices) == len(m.indices)


def test_crease_normals_split_sharp_edges_and_keep_smooth_ones():
    from jackpy.render.mesh import Mesh, crease_normals

    # a cube: 8 shared corners, every edge a 90 degree crease -> 24 vertices with face normals
    import trimesh

    cube = trimesh.creation.box(extents=(1, 1, 1))
    v, n, f = crease_normals(cube.vertices, cube.faces, 60.0)
    assert len(v) == 24
    face_n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    face_n /= np.linalg.norm(face_n, axis=1, keepdims=True)
    for k in range(3):  # every corner's normal is its face's normal
        assert np.allclose(n[f[:, k]], face_n, atol=1e-6)
    # a sphere is smooth everywhere: nothing is split
    sphere = trimesh.creation.icosphere(subdivisions=3)
    m = Mesh.from_triangles(sphere.vertices, sphere.faces)
    assert len(m.vertices) == len(sphere.vertices)
    assert np.allclose(np.linalg.norm(m.normals, axis=1), 1.0, atol=1e-5)


def test_a_frame_drawn_at_half_scale_is_shown_stretched_and_read_back_at_full_size(renderer):
    """render_scale 0.5: the moving frame is drawn into a texture half the size each side (what a
    window stretches over the view, and blit stretches); read_pixels draws it at full size again,
    equal to a frame drawn at full size; the still frame is due (refine_pending)."""
    s = scene(DrawItem("box", at(0.3, 0.1), RED))
    cam = front_camera()
    full = render(renderer, s, cam)
    renderer.render_scale = 0.5
    cam.yaw += 0.2  # a new frame (an unchanged one is not drawn again)
    renderer.render(s, cam.view_matrix(), cam.projection_matrix(renderer.aspect))
    assert renderer.color_texture.size == (W // 2, H // 2) and renderer.drawn_scale == 0.5
    assert renderer.refine_pending
    screen = renderer.ctx.framebuffer([renderer.ctx.renderbuffer((W, H), 4)])
    renderer.blit(screen)
    shown = np.frombuffer(screen.read(components=4), np.uint8).reshape(H, W, 4)[::-1]
    img = renderer.read_pixels()
    assert img.shape == (H, W, 4) and renderer.drawn_scale == 1.0
    assert renderer.color_texture.size == (W, H)
    red = (img[..., 0] > 120) & (img[..., 0] > 3 * img[..., 1])
    shown_red = (shown[..., 0] > 120) & (shown[..., 0] > 3 * shown[..., 1])
    assert red.sum() > 50 and abs(int(shown_red.sum()) - int(red.sum())) < 0.2 * red.sum()
    renderer.render_scale = 1.0
    cam.yaw -= 0.2
    assert np.array_equal(render(renderer, s, cam)[..., :3], full[..., :3])
    screen.release()
