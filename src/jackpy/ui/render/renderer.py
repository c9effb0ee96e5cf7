"""The moderngl renderer: draws a :class:`Scene` offscreen, resolves it, and picks by id.

The renderer owns its framebuffers, so it works the same in a glfw window's context (blit the
result with :meth:`Renderer.blit`) and in a standalone EGL context (read it back with
:meth:`Renderer.read_pixels`). Meshes are uploaded once under a key; each frame only instance
records (transforms, colours, ids) are streamed.

Passes, in order: opaque instances (polygon offset, so edge overlays win the depth test),
wireframe overlays, depth-tested lines, the fading floor grid, transparent items back to front
(back faces first, depth writes off), then on-top lines. Picking draws the same opaque geometry
(and the pickable transparent items) into a 32-bit integer attachment, for one pixel only.
"""

from __future__ import annotations

from pathlib import Path

import moderngl
import numpy as np

from jackpy.ui.render import shaders
from jackpy.ui.render.instancing import (
    BUILTIN_MESHES,
    INSTANCE_ATTRIBUTES,
    INSTANCE_DTYPE,
    INSTANCE_FORMAT,
    FrameBatches,
    InstanceBatch,
    back_to_front,
    build_batches,
    item_batches,
    rgba,
)
from jackpy.ui.render.image import write_png
from jackpy.ui.render.mesh import Mesh
from jackpy.ui.render.scene import Grid, Lines, Scene

KEY_LIGHT_DIRECTION = np.array([-0.45, 0.8, 0.55]) / np.linalg.norm([-0.45, 0.8, 0.55])
"""Direction towards the key light in world (front-left, above, for a figure facing +z)."""

HIGHLIGHT_COLOR = (1.0, 0.72, 0.15)


def _mat(m: np.ndarray) -> bytes:
    """A 4x4 matrix as column-major float32 bytes, as GLSL reads it."""
    return np.asarray(m, np.float32).T.tobytes()


class _GpuMesh:
    """A mesh's vertex and index buffers, a streamed instance buffer, and one VAO per program."""

    def __init__(self, ctx: moderngl.Context, mesh: Mesh) -> None:
        self.ctx = ctx
        self.vbo = ctx.buffer(np.hstack([mesh.vertices, mesh.normals]).astype(np.float32).tobytes())
        self.ibo = ctx.buffer(mesh.indices.tobytes())
        self.index_count = mesh.indices.size
        lo, hi = mesh.bounds()
        self.center = 0.5 * (lo + hi)
        self.capacity = 0
        self.instances: moderngl.Buffer | None = None
        self.vaos: dict[int, moderngl.VertexArray] = {}

    def draw(self, program: moderngl.Program, records: np.ndarray) -> None:
        """Draw ``records`` instances of this mesh with ``program``."""
        n = len(records)
        if n == 0 or self.index_count == 0:
            return
        if n > self.capacity:
            self._release_instances()
            self.capacity = max(n, 2 * self.capacity, 16)
            self.instances = self.ctx.buffer(reserve=self.capacity * INSTANCE_DTYPE.itemsize, dynamic=True)
        assert self.instances is not None
        self.instances.write(records.tobytes())
        vao = self.vaos.get(program.glo)
        if vao is None:
            vao = self.ctx.vertex_array(
                program,
                [(self.vbo, "3f 3f", "in_position", "in_normal"),
                 (self.instances, INSTANCE_FORMAT, *INSTANCE_ATTRIBUTES)],
                index_buffer=self.ibo, index_element_size=4, skip_errors=True,
            )
            self.vaos[program.glo] = vao
        vao.render(moderngl.TRIANGLES, vertices=self.index_count, instances=n)

    def _release_instances(self) -> None:
        for vao in self.vaos.values():
            vao.release()
        self.vaos.clear()
        if self.instances is not None:
            self.instances.release()

    def release(self) -> None:
        self._release_instances()
        self.vbo.release()
        self.ibo.release()


class Renderer:
    """Renders scenes at ``size`` = (width, height) pixels with ``samples``-fold MSAA."""

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], samples: int = 4) -> None:
        self.ctx = ctx
        self.samples = max(0, min(samples, ctx.max_samples))
        self._mesh_program = ctx.program(vertex_shader=shaders.MESH_VERTEX,
                                         fragment_shader=shaders.MESH_FRAGMENT)
        self._pick_program = ctx.program(vertex_shader=shaders.MESH_VERTEX,
                                         fragment_shader=shaders.PICK_FRAGMENT)
        self._line_program = ctx.program(vertex_shader=shaders.LINE_VERTEX,
                                         fragment_shader=shaders.LINE_FRAGMENT)
        self._grid_program = ctx.program(vertex_shader=shaders.GRID_VERTEX,
                                         fragment_shader=shaders.GRID_FRAGMENT)
        self._mesh_program["u_highlight_color"].value = HIGHLIGHT_COLOR
        corners = np.array([-1, -1, 1, -1, 1, 1, -1, -1, 1, 1, -1, 1], np.float32)
        self._grid_vbo = ctx.buffer(corners.tobytes())
        self._grid_vao = ctx.vertex_array(self._grid_program, [(self._grid_vbo, "2f", "in_corner")])
        self._line_capacity = 0
        self._line_vbo: moderngl.Buffer | None = None
        self._line_vao: moderngl.VertexArray | None = None
        self._meshes: dict[str, _GpuMesh] = {}
        for key, mesh in BUILTIN_MESHES.items():
            self.add_mesh(key, mesh)
        self._framebuffers: list[moderngl.Framebuffer | moderngl.Renderbuffer | moderngl.Texture] = []
        self._allocate(size)
        self._last: tuple[FrameBatches, list[InstanceBatch], np.ndarray, np.ndarray] | None = None

    # ------------------------------------------------------------------ resources
    def _allocate(self, size: tuple[int, int]) -> None:
        for obj in self._framebuffers:
            obj.release()
        ctx, self.size = self.ctx, (int(size[0]), int(size[1]))
        color_rb = ctx.renderbuffer(self.size, 4, samples=self.samples)
        depth_rb = ctx.depth_renderbuffer(self.size, samples=self.samples)
        self._msaa_fbo = ctx.framebuffer([color_rb], depth_rb)
        self.color_texture = ctx.texture(self.size, 4)
        self._resolve_fbo = ctx.framebuffer([self.color_texture])
        pick_tex = ctx.texture(self.size, 1, dtype="i4")
        pick_tex.filter = (moderngl.NEAREST, moderngl.NEAREST)
        pick_depth = ctx.depth_renderbuffer(self.size)
        self._pick_fbo = ctx.framebuffer([pick_tex], pick_depth)
        self._framebuffers = [self._msaa_fbo, self._resolve_fbo, self._pick_fbo, color_rb, depth_rb,
                              self.color_texture, pick_tex, pick_depth]

    def resize(self, width: int, height: int) -> None:
        """Reallocate the framebuffers for a new viewport size in pixels."""
        if (width, height) != self.size:
            self._allocate((width, height))
            self._last = None

    @property
    def aspect(self) -> float:
        """Width / height of the viewport."""
        return self.size[0] / self.size[1]

    def add_mesh(self, key: str, mesh: Mesh, replace: bool = False) -> None:
        """Upload ``mesh`` under ``key``; an existing key is kept unless ``replace``."""
        if key in self._meshes:
            if not replace:
                return
            self._meshes.pop(key).release()
        self._meshes[key] = _GpuMesh(self.ctx, mesh)

    def has_mesh(self, key: str) -> bool:
        """Whether a mesh is cached under ``key``."""
        return key in self._meshes

    def remove_mesh(self, key: str) -> None:
        """Free the GPU buffers of a cached mesh."""
        self._meshes.pop(key).release()

    def release(self) -> None:
        """Free every GPU resource of this renderer."""
        for mesh in self._meshes.values():
            mesh.release()
        self._meshes.clear()
        for obj in self._framebuffers:
            obj.release()
        for obj in (self._line_vao, self._line_vbo, self._grid_vao, self._grid_vbo, self._mesh_program,
                    self._pick_program, self._line_program, self._grid_program):
            if obj is not None:
                obj.release()

    # ------------------------------------------------------------------ drawing
    def render(self, scene: Scene, view: np.ndarray, projection: np.ndarray) -> None:
        """Draw ``scene`` seen through 4x4 ``view`` (world to camera) and ``projection``."""
        unknown = {i.mesh for i in scene.items} - self._meshes.keys()
        if unknown:
            raise KeyError(f"meshes not uploaded: {sorted(unknown)}")
        ctx, fbo = self.ctx, self._msaa_fbo
        batches = build_batches(scene)
        centers = {k: m.center for k, m in self._meshes.items()}
        transparent = item_batches(back_to_front(batches.transparent, view, centers))

        fbo.use()
        fbo.depth_mask = True
        fbo.clear(*rgba(scene.background, 1)[0], depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
        ctx.depth_func = "<"
        self._set_mesh_uniforms(view, projection)
        prog = self._mesh_program

        ctx.polygon_offset = (1.0, 1.0)
        self._draw(prog, batches.opaque)
        ctx.polygon_offset = (0.0, 0.0)
        ctx.depth_func = "<="
        self._draw_wireframe(batches.wireframe)
        self._draw_lines([ln for ln in scene.lines if not ln.on_top], view, projection)

        ctx.enable(moderngl.BLEND)
        ctx.blend_func = (moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA,
                          moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA)
        fbo.depth_mask = False
        if scene.grid is not None:
            self._draw_grid(scene.grid, view, projection)
        ctx.enable(moderngl.CULL_FACE)
        for batch in transparent:
            for face in ("front", "back"):  # cull front faces first: back faces are drawn first
                ctx.cull_face = face
                self._draw(prog, [batch])
            if batch.wireframe:
                ctx.disable(moderngl.CULL_FACE)
                self._draw_wireframe([batch])
                ctx.enable(moderngl.CULL_FACE)
        ctx.disable(moderngl.CULL_FACE | moderngl.DEPTH_TEST)
        self._draw_lines([ln for ln in scene.lines if ln.on_top], view, projection)
        fbo.depth_mask = True
        ctx.disable(moderngl.BLEND)

        ctx.copy_framebuffer(self._resolve_fbo, fbo)
        pickable = [i for i in batches.transparent if i.pick_id is not None]
        self._last = (batches, item_batches(pickable), np.array(view), np.array(projection))

    def _set_mesh_uniforms(self, view: np.ndarray, projection: np.ndarray) -> None:
        rotation = np.asarray(view, float)[:3, :3]
        for prog in (self._mesh_program, self._pick_program):
            prog["u_view"].write(_mat(view))
            prog["u_proj"].write(_mat(projection))
        prog = self._mesh_program
        prog["u_key_direction"].value = tuple(rotation @ KEY_LIGHT_DIRECTION)
        prog["u_up"].value = tuple(rotation[:, 1])
        prog["u_orthographic"].value = bool(projection[3, 3] == 1.0)
        prog["u_flat"].value = False

    def _draw(self, program: moderngl.Program, batches: list[InstanceBatch]) -> None:
        for batch in batches:
            self._meshes[batch.mesh].draw(program, batch.records)

    def _draw_wireframe(self, batches: list[InstanceBatch]) -> None:
        if not batches:
            return
        self._mesh_program["u_flat"].value = True
        self.ctx.wireframe = True
        self._draw(self._mesh_program, batches)
        self.ctx.wireframe = False
        self._mesh_program["u_flat"].value = False

    def _draw_lines(self, lines: list[Lines], view: np.ndarray, projection: np.ndarray) -> None:
        if not lines:
            return
        parts = []
        for ln in lines:
            seg = np.asarray(ln.segments, np.float32).reshape(-1, 2, 3)
            color = np.repeat(rgba(ln.color, len(seg)), 2, axis=0)
            parts.append(np.hstack([seg.reshape(-1, 3), color]))
        data = np.ascontiguousarray(np.concatenate(parts), np.float32)
        if len(data) == 0:
            return
        if data.nbytes > self._line_capacity:
            if self._line_vao is not None and self._line_vbo is not None:
                self._line_vao.release()
                self._line_vbo.release()
            self._line_capacity = max(data.nbytes, 2 * self._line_capacity)
            self._line_vbo = self.ctx.buffer(reserve=self._line_capacity, dynamic=True)
            self._line_vao = self.ctx.vertex_array(
                self._line_program, [(self._line_vbo, "3f 4f", "in_position", "in_color")])
        assert self._line_vbo is not None and self._line_vao is not None
        self._line_vbo.write(data.tobytes())
        self._line_program["u_view"].write(_mat(view))
        self._line_program["u_proj"].write(_mat(projection))
        self._line_vao.render(moderngl.LINES, vertices=len(data))

    def _draw_grid(self, grid: Grid, view: np.ndarray, projection: np.ndarray) -> None:
        eye = np.linalg.inv(view)[:3, 3]
        prog = self._grid_program
        prog["u_view"].write(_mat(view))
        prog["u_proj"].write(_mat(projection))
        prog["u_center"].value = (float(eye[0]), float(eye[2]))
        prog["u_extent"].value = float(grid.fade_distance)
        prog["u_spacing"].value = float(grid.spacing)
        prog["u_major_every"].value = float(grid.major_every)
        prog["u_fade_distance"].value = float(grid.fade_distance)
        prog["u_minor_color"].value = tuple(rgba(grid.minor_color, 1)[0])
        prog["u_major_color"].value = tuple(rgba(grid.major_color, 1)[0])
        self._grid_vao.render(moderngl.TRIANGLES)

    # ------------------------------------------------------------------ output
    def read_pixels(self) -> np.ndarray:
        """The last rendered image, (height, width, 4) uint8 RGBA, first row at the top."""
        w, h = self.size
        data = self._resolve_fbo.read(components=4, alignment=1)
        return np.frombuffer(data, np.uint8).reshape(h, w, 4)[::-1].copy()

    def blit(self, destination: moderngl.Framebuffer) -> None:
        """Copy the last rendered image into ``destination`` (e.g. a window's ``ctx.screen``)."""
        self.ctx.copy_framebuffer(destination, self._resolve_fbo)

    def save_png(self, path: str | Path) -> None:
        """Write the last rendered image to a PNG file."""
        write_png(path, self.read_pixels())

    def pick(self, x: int, y: int) -> int | None:
        """Pick id of the thing drawn at pixel (x, y) of the last frame (origin top-left), or None.

        Only that pixel is rasterised (scissor), so a pick costs about one draw call per batch.
        """
        w, h = self.size
        if self._last is None or not (0 <= x < w and 0 <= y < h):
            return None
        batches, transparent, view, projection = self._last
        ctx, fbo = self.ctx, self._pick_fbo
        gl_y = h - 1 - int(y)
        fbo.use()
        fbo.scissor = (int(x), gl_y, 1, 1)
        fbo.depth_mask = True
        fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
        ctx.depth_func = "<"
        self._set_mesh_uniforms(view, projection)
        self._draw(self._pick_program, batches.opaque)
        self._draw(self._pick_program, transparent)
        value = np.frombuffer(fbo.read(viewport=(int(x), gl_y, 1, 1), components=1, dtype="i4"), np.int32)
        fbo.scissor = None
        pick_id = int(value[0])
        return pick_id if pick_id != 0 else None
