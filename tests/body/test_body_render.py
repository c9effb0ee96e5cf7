"""Offscreen render of the 5th-percentile female and 95th-percentile male side by side (moderngl EGL).

Checks that both figures are visible and human-proportioned (silhouette height/width), and that the
heights in pixels keep the stature ratio. The picture is saved (tmp_path/human_pair.png) for a look.
"""

import numpy as np
import pytest

from jackpy.body.shapes import signed_volume

moderngl = pytest.importorskip("moderngl")
Image = pytest.importorskip("PIL.Image")

VS = """#version 330
in vec3 p; in vec3 n; uniform mat4 M; out vec3 nn;
void main() { gl_Position = M * vec4(p, 1.0); nn = n; }"""
FS = """#version 330
in vec3 nn; out vec4 c;
void main() { float d = max(dot(normalize(nn), normalize(vec3(0.4, 0.6, 0.8))), 0.0);
              c = vec4(vec3(0.25 + 0.7 * d), 1.0); }"""


def _world(fig, shift):
    w = fig.world_transforms()
    verts, norms, faces, base = [], [], [], 0
    for name, seg in fig.segments.items():
        if seg.psurf is None:
            continue
        m = seg.psurf.posed_mesh()
        t = w[name]
        verts.append(m.vertices @ t[:3, :3].T + t[:3, 3] + shift)
        norms.append(m.vertex_normals() @ t[:3, :3].T)
        faces.append(m.faces + base)
        base += len(m.vertices)
    return np.vstack(verts), np.vstack(norms), np.vstack(faces)


def _render(parts, size=(600, 700), extent=2.1):
    try:
        ctx = moderngl.create_standalone_context(backend="egl")
    except Exception as exc:  # noqa: BLE001 - any failure to get EGL means no offscreen GL here
        pytest.skip(f"no offscreen GL: {exc}")
    w, h = size
    fbo = ctx.simple_framebuffer(size)
    fbo.use()
    ctx.enable(moderngl.DEPTH_TEST)
    prog = ctx.program(vertex_shader=VS, fragment_shader=FS)
    m = np.diag([2 / extent * h / w, 2 / extent, -0.3, 1.0])
    m[1, 3] = -0.95
    prog["M"].write(m.T.astype("f4").tobytes())
    fbo.clear(0.0, 0.0, 0.0, 1.0, depth=1.0)
    for v, n, f in parts:
        vbo = ctx.buffer(np.hstack([v, n]).astype("f4").tobytes())
        ibo = ctx.buffer(f.astype("i4").tobytes())
        ctx.vertex_array(prog, [(vbo, "3f 3f", "p", "n")], ibo).render()
    img = np.frombuffer(fbo.read(components=3), dtype=np.uint8).reshape(h, w, 3)[::-1]
    ctx.release()
    return img


def test_render_female5_and_male95_side_by_side(female5, male95, tmp_path):
    img = _render([_world(female5, [-0.45, 0, 0]), _world(male95, [0.45, 0, 0])])
    Image.fromarray(img).save(tmp_path / "human_pair.png")
    print(f"picture: {tmp_path / 'human_pair.png'}")
    mask = img.max(axis=2) > 0
    w = mask.shape[1]
    heights = []
    for half in (mask[:, : w // 2], mask[:, w // 2:]):
        rows, cols = np.flatnonzero(half.any(axis=1)), np.flatnonzero(half.any(axis=0))
        assert rows.size and cols.size, "figure not visible"
        height, width = np.ptp(rows) + 1, np.ptp(cols) + 1
        assert 2.6 < height / width < 4.2  # a standing human with arms down
        heights.append(height)
        assert np.unique(img[:, :w // 2][half] if len(heights) == 1 else img[:, w // 2:][half], axis=0).shape[0] > 20  # shaded
    ratio = male95.body_spec.stature / female5.body_spec.stature
    assert heights[1] / heights[0] == pytest.approx(ratio, rel=0.03)


def test_surfaces_closed_outward_and_sized(male50):
    import trimesh

    total = 0
    for seg in male50.segments.values():
        if seg.psurf is None:
            continue
        m = seg.psurf.mesh
        total += len(m.faces)
        tm = trimesh.Trimesh(m.vertices, m.faces, process=False)
        assert tm.is_watertight, seg.name
        assert signed_volume(m) > 0, seg.name
    assert 10_000 <= total <= 30_000
