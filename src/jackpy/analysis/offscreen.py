"""A small headless renderer for analyses and reports: object-ID buffers with depth (visibility,
book §5.1.1's Z-buffer perception) and shaded pictures (report images). moderngl on EGL, no window.

Kept apart from :mod:`jackpy.ui` (which nothing else may import). Cameras are 4x4 column-vector
matrices: ``view`` maps world to camera (camera looks down its -z, y up), ``projection`` camera to
clip space (OpenGL conventions). A :class:`Body` is a mesh in its own frame plus its world transform.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.errors import JackpyError
from jackpy.peabody.geometry import Mesh


@dataclass
class Body:
    """Something to draw: ``mesh`` in its own frame, ``model`` its 4x4 world transform, ``name``,
    ``colour`` (RGBA in [0, 1]) or per-vertex ``vertex_colours`` (n,3)."""

    name: str
    mesh: Mesh
    model: np.ndarray
    colour: tuple[float, float, float, float] = (0.75, 0.75, 0.78, 1.0)
    vertex_colours: np.ndarray | None = None


def look_at(eye: np.ndarray, target: np.ndarray, up: np.ndarray = np.array([0.0, 1.0, 0.0])) -> np.ndarray:
    """World-to-camera transform of a camera at ``eye`` looking at ``target`` (metres)."""
    eye, target, up = (np.asarray(a, dtype=float) for a in (eye, target, up))
    f = target - eye
    f /= np.linalg.norm(f)
    s = np.cross(f, up)
    if np.linalg.norm(s) < 1e-9:  # looking along up: pick any perpendicular
        s = np.cross(f, np.array([1.0, 0.0, 0.0]) if abs(f[0]) < 0.9 else np.array([0.0, 0.0, 1.0]))
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def perspective(fovy: float, aspect: float, near: float, far: float) -> np.ndarray:
    """OpenGL perspective projection: vertical field of view ``fovy`` radians, aspect width/height."""
    t = 1.0 / np.tan(fovy / 2)
    p = np.zeros((4, 4))
    p[0, 0], p[1, 1] = t / aspect, t
    p[2, 2] = (far + near) / (near - far)
    p[2, 3] = 2 * far * near / (near - far)
    p[3, 2] = -1.0
    return p


def linear_depth(depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """Camera-space distance along the view axis (metres) from depth-buffer values in [0, 1]."""
    z = 2.0 * depth - 1.0
    return 2.0 * near * far / (far + near - z * (far - near))


_VS = """
#version 330
uniform mat4 mvp; uniform mat4 model;
in vec3 in_pos; in vec3 in_normal; in vec3 in_colour;
out vec3 v_normal; out vec3 v_colour;
void main() {
    gl_Position = mvp * vec4(in_pos, 1.0);
    v_normal = mat3(model) * in_normal; v_colour = in_colour;
}
"""
_FS_SHADED = """
#version 330
uniform vec4 colour; uniform bool use_vertex_colour; uniform vec3 light;
in vec3 v_normal; in vec3 v_colour; out vec4 frag;
void main() {
    vec3 base = use_vertex_colour ? v_colour : colour.rgb;
    float l = 0.35 + 0.65 * abs(dot(normalize(v_normal), light));
    frag = vec4(base * l, colour.a);
}
"""
_FS_ID = """
#version 330
uniform uint body_id; out vec4 frag;
void main() {
    frag = vec4(float(body_id & 255u), float((body_id >> 8) & 255u), float((body_id >> 16) & 255u), 255.0) / 255.0;
}
"""


class OffscreenRenderer:
    """Render :class:`Body` lists to arrays at ``size`` = (width, height) pixels.

    ``ctx``: an existing moderngl context to render with (e.g. the workbench window's, where a second
    EGL context cannot live beside a GLX window); it must be current on the calling thread and is
    not released by :meth:`release`. By default a standalone EGL context is made and owned."""

    def __init__(self, size: tuple[int, int] = (512, 512), ctx=None) -> None:
        import moderngl

        self._owns_ctx = ctx is None
        if ctx is None:
            try:
                ctx = moderngl.create_standalone_context(backend="egl")
            except Exception as exc:  # no EGL/GPU driver: one clear line
                raise JackpyError(f"offscreen rendering is unavailable (moderngl EGL context: {exc})") from None
        self.ctx = ctx
        self.size = size
        self._shaded = self.ctx.program(vertex_shader=_VS, fragment_shader=_FS_SHADED)
        self._ids = self.ctx.program(vertex_shader=_VS, fragment_shader=_FS_ID)
        self._fbo = self.ctx.framebuffer(self.ctx.renderbuffer(size, 4), self.ctx.depth_texture(size))
        self._cache: dict[int, tuple[Mesh, object, dict]] = {}

    def release(self) -> None:
        """Free the GL context and everything in it (only this renderer's objects on a borrowed context)."""
        if self._owns_ctx:
            self.ctx.release()
            return
        for _, vbo, vaos in self._cache.values():
            for vao in vaos.values():
                vao.release()
            vbo.release()
        self._cache.clear()
        for obj in (self._fbo, *self._fbo.color_attachments, self._fbo.depth_attachment, self._shaded, self._ids):
            obj.release()

    def _geometry(self, body: Body, program) -> object:
        key = id(body.mesh)
        if key not in self._cache:
            m = body.mesh
            # flat shading: one vertex per corner with its face normal
            tri = m.vertices[m.faces].reshape(-1, 3)
            n = np.cross(tri[1::3] - tri[0::3], tri[2::3] - tri[0::3])
            n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
            data = np.hstack([tri, np.repeat(n, 3, axis=0), np.zeros_like(tri)]).astype("f4")
            self._cache[key] = (m, self.ctx.buffer(data.tobytes()), {})
        mesh, vbo, vaos = self._cache[key]
        if body.vertex_colours is not None:
            col = np.asarray(body.vertex_colours, dtype="f4")[mesh.faces].reshape(-1, 3)
            data = np.frombuffer(vbo.read(), dtype="f4").reshape(-1, 9).copy()
            data[:, 6:9] = col
            vbo.write(data.tobytes())
        if id(program) not in vaos:
            layout = ((vbo, "3f 3f 3f", "in_pos", "in_normal", "in_colour") if program is self._shaded
                      else (vbo, "3f 24x", "in_pos"))  # the ID shader uses positions only
            vaos[id(program)] = self.ctx.vertex_array(program, [layout])
        return vaos[id(program)]

    def _draw(self, program, bodies: list[Body], vp: np.ndarray, per_body) -> None:
        for body in bodies:
            vao = self._geometry(body, program)
            program["mvp"].write((vp @ body.model).T.astype("f4").tobytes())
            if "model" in program:
                program["model"].write(body.model.T.astype("f4").tobytes())
            per_body(body)
            vao.render()

    def render_ids(self, bodies: list[Body], view: np.ndarray, projection: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(ids, depth): per pixel the 1-based index into ``bodies`` of the nearest surface (0 for
        none) and the depth-buffer value in [0, 1]; row 0 is the top of the image."""
        import moderngl

        self._fbo.use()
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
        self._fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        index = {id(b): k + 1 for k, b in enumerate(bodies)}
        self._draw(self._ids, bodies, projection @ view,
                   lambda b: self._ids.__setitem__("body_id", index[id(b)]))
        w, h = self.size
        rgba = np.frombuffer(self._fbo.read(components=4), dtype=np.uint8).reshape(h, w, 4)[::-1]
        ids = rgba[..., 0].astype(np.int64) | (rgba[..., 1].astype(np.int64) << 8) | (rgba[..., 2].astype(np.int64) << 16)
        depth = np.frombuffer(self._fbo.depth_attachment.read(), dtype="f4").reshape(h, w)[::-1]
        return ids, depth.copy()

    def render(self, opaque: list[Body], view: np.ndarray, projection: np.ndarray,
               translucent: list[Body] = (), background: tuple[float, float, float] = (1.0, 1.0, 1.0),
               light: np.ndarray | None = None) -> np.ndarray:
        """A shaded RGB picture (h, w, 3) uint8: opaque bodies, then translucent ones blended over
        them (depth-tested, not depth-written). ``light`` is a world direction (default: from the
        camera)."""
        import moderngl

        self._fbo.use()
        self.ctx.enable(moderngl.DEPTH_TEST)
        self.ctx.disable(moderngl.CULL_FACE)
        self._fbo.clear(*background, 1.0, depth=1.0)
        cam_dir = -np.linalg.inv(view)[:3, 2] if light is None else np.asarray(light, dtype=float)
        self._shaded["light"].value = tuple(cam_dir / np.linalg.norm(cam_dir))
        vp = projection @ view

        def per_body(b: Body) -> None:
            self._shaded["colour"].value = tuple(b.colour)
            self._shaded["use_vertex_colour"].value = b.vertex_colours is not None

        self.ctx.disable(moderngl.BLEND)
        self._draw(self._shaded, list(opaque), vp, per_body)
        if translucent:
            self.ctx.enable(moderngl.BLEND)
            self.ctx.blend_func = moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA
            self.ctx.depth_mask = False
            self.ctx.enable(moderngl.CULL_FACE)  # front faces only: unsorted back faces would speckle
            self._draw(self._shaded, list(translucent), vp, per_body)
            self.ctx.disable(moderngl.CULL_FACE)
            self.ctx.depth_mask = True
            self.ctx.disable(moderngl.BLEND)
        w, h = self.size
        rgba = np.frombuffer(self._fbo.read(components=4), dtype=np.uint8).reshape(h, w, 4)[::-1]
        return rgba[..., :3].copy()
