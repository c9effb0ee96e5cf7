"""The moderngl renderer: draws a :class:`Scene` offscreen, resolves it, and picks by id.

The renderer owns its framebuffers, so it works the same in a glfw window's context (blit the
result with :meth:`Renderer.blit`) and in a standalone EGL context (read it back with
:meth:`Renderer.read_pixels`). Meshes are uploaded once under a key; each frame only instance
records (transforms, colours, ids) are streamed.

Passes, in order: opaque instances (polygon offset, so edge overlays win the depth test),
wireframe overlays, depth-tested lines, the fading floor grid, transparent items back to front
(back faces first, depth writes off), then on-top lines. Picking draws the same opaque geometry
(and the pickable transparent items) into a 32-bit integer attachment, for one pixel only.

Cost control (see "Rendering" in docs/architecture.md): a frame whose inputs (instance records,
lines, grid, camera, meshes, size) equal the last frame's is not drawn again; instance data is
re-uploaded only where it changed; passes with nothing to draw are skipped; the singleton rigid
opaque items (a figure's segments, the workplace's furniture) are drawn as one merged draw
(:mod:`jackpy.render.rigid`), as a software rasteriser pays a fixed cost per draw call. The MSAA sample count
is a setting: 4x on a hardware GPU, none on a software rasteriser (llvmpipe, softpipe), where
multisampling costs several times the whole frame; there a frame that stays unchanged for
``refine_after_s`` is drawn once more at ``still_samples`` (4x), so a still image is anti-aliased.
:attr:`Renderer.render_scale` (< 1: the frame loop's cheaper draw while things move) draws moving
frames into a smaller framebuffer, shown stretched; the still frame is drawn at full size again,
and picking, :meth:`Renderer.read_pixels` and :meth:`Renderer.read_ids` always work at full size.
"""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

import moderngl
import numpy as np

from jackpy.render import shaders
from jackpy.render.instancing import (
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
from jackpy.render.image import write_png
from jackpy.render.mesh import Mesh
from jackpy.render.rigid import RigidBatch, item_texels, mergeable_mesh, split_rigid
from jackpy.render.scene import DrawItem, Grid, Lines, Scene
from jackpy.render.skinning import GpuSkinnedMesh, SkinnedMesh, bone_texels, stand_in

KEY_LIGHT_DIRECTION = np.array([-0.45, 0.8, 0.55]) / np.linalg.norm([-0.45, 0.8, 0.55])
"""Direction towards the key light in world (front-left, above, for a figure facing +z)."""

HIGHLIGHT_COLOR = (1.0, 0.72, 0.15)

SOFTWARE_RENDERERS = ("llvmpipe", "softpipe", "swrast", "software rasterizer", "swiftshader")
"""Substrings of ``GL_RENDERER`` (lower case) that mean a CPU rasteriser."""

HARDWARE_SAMPLES = 4
"""Default MSAA samples on a GPU, and of the refined still frame on a software rasteriser."""


RIGID_CACHE = 4
"""Merged rigid batches kept (:meth:`Renderer._rigid_batch`)."""

SOFTWARE_DISPLAY_TRIANGLES = 50_000
"""Display budget of one CAD object on a software rasteriser (triangles; ``None`` on a GPU, where
the object's own budget applies). At workbench sizes 50k triangles are still below a pixel each."""


def is_software_gl(ctx: moderngl.Context) -> bool:
    """Whether ``ctx`` rasterises on the CPU (Mesa llvmpipe or softpipe, SwiftShader)."""
    name = str(ctx.info.get("GL_RENDERER", "")).lower()
    return any(s in name for s in SOFTWARE_RENDERERS)


def default_samples(ctx: moderngl.Context) -> int:
    """MSAA samples for interactive frames: 4 on a GPU, 0 on a software rasteriser."""
    return 0 if is_software_gl(ctx) else min(HARDWARE_SAMPLES, ctx.max_samples)


def _mat(m: np.ndarray) -> bytes:
    """A 4x4 matrix as column-major float32 bytes, as GLSL reads it."""
    return np.asarray(m, np.float32).T.tobytes()


class _GpuMesh:
    """A mesh's vertex and index buffers, a streamed instance buffer, and one VAO per program."""

    def __init__(self, ctx: moderngl.Context, mesh: Mesh, version: int = 0) -> None:
        self.ctx = ctx
        self.version = version
        """The renderer's mesh version when this was uploaded (names this upload)."""
        self.mergeable = mesh if mergeable_mesh(mesh) else None
        """The mesh, kept where its items may be merged into one draw (:mod:`jackpy.render.rigid`)."""
        colors = mesh.colors if mesh.colors is not None else np.ones_like(mesh.vertices)
        self.vbo = ctx.buffer(np.hstack([mesh.vertices, mesh.normals, colors]).astype(np.float32).tobytes())
        self.ibo = ctx.buffer(mesh.indices.tobytes())
        self.index_count = mesh.indices.size
        lo, hi = mesh.bounds()
        self.center = 0.5 * (lo + hi)
        self.capacity = 0
        self.instances: moderngl.Buffer | None = None
        self.uploaded = b""
        self.vaos: dict[int, moderngl.VertexArray] = {}

    def draw(self, program: moderngl.Program, records: np.ndarray) -> None:
        """Draw ``records`` instances of this mesh with ``program``.

        The instance buffer grows by doubling and is written only when the records differ from
        what it holds (still things, and a mesh drawn in several passes, upload nothing).
        """
        n = len(records)
        if n == 0 or self.index_count == 0:
            return
        if n > self.capacity:
            self._release_instances()
            self.capacity = max(n, 2 * self.capacity, 4)
            self.instances = self.ctx.buffer(reserve=self.capacity * INSTANCE_DTYPE.itemsize, dynamic=True)
            self.uploaded = b""
        assert self.instances is not None
        data = records.tobytes()
        if data != self.uploaded:
            self.instances.write(data)
            self.uploaded = data
        vao = self.vaos.get(program.glo)
        if vao is None:
            vao = self.ctx.vertex_array(
                program,
                [(self.vbo, "3f 3f 3f", "in_position", "in_normal", "in_vertex_color"),
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
    """Renders scenes at ``size`` = (width, height) pixels.

    ``samples`` is the MSAA sample count of ordinary frames; ``None`` picks
    :func:`default_samples` (4 on a GPU, 0 on a software rasteriser). ``still_samples`` is the
    count a frame is redrawn at once it has stayed unchanged for ``refine_after_s`` seconds; by
    default 4 when ``samples`` was chosen automatically, else ``samples`` (no refinement).
    """

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int], samples: int | None = None,
                 still_samples: int | None = None) -> None:
        self.ctx = ctx
        self.software = is_software_gl(ctx)
        self.samples = default_samples(ctx) if samples is None else max(0, min(samples, ctx.max_samples))
        if still_samples is None:
            still_samples = HARDWARE_SAMPLES if samples is None else self.samples
        self.still_samples = max(self.samples, min(still_samples, ctx.max_samples))
        self.refine_after_s = 0.3
        self.render_scale = 1.0
        """Fraction (0.25-1) of :attr:`size` that moving frames are drawn at (each side); the
        still frame and every read-back are full size."""
        self.coarse_skin_scale = 0.5
        """A moving frame drawn at this :attr:`render_scale` or below draws each skin's coarse
        level of detail (:func:`~jackpy.render.skinning.coarse_indices`); 0 never does."""
        self.stretch_filter = moderngl.NEAREST if self.software else moderngl.LINEAR
        """How a frame drawn smaller is stretched (:meth:`blit`, a window's image of
        :attr:`color_texture`): bilinear on a GPU; nearest on a software rasteriser, where
        bilinear sampling over a 1280x800 view cost ~24 ms, ~1.6x nearest (moving frames only;
        the still frame is copied 1:1)."""
        self.display_triangles: int | None = SOFTWARE_DISPLAY_TRIANGLES if self.software else None
        """Triangle budget for a CAD object's display copy (see ``SceneView.upload``)."""
        self._mesh_program = ctx.program(vertex_shader=shaders.MESH_VERTEX,
                                         fragment_shader=shaders.MESH_FRAGMENT)
        self._pick_program = ctx.program(vertex_shader=shaders.MESH_VERTEX,
                                         fragment_shader=shaders.PICK_FRAGMENT)
        self._line_program = ctx.program(vertex_shader=shaders.LINE_VERTEX,
                                         fragment_shader=shaders.LINE_FRAGMENT)
        self._grid_program = ctx.program(vertex_shader=shaders.GRID_VERTEX,
                                         fragment_shader=shaders.GRID_FRAGMENT)
        self._skin_program = ctx.program(vertex_shader=shaders.SKIN_VERTEX,
                                         fragment_shader=shaders.MESH_FRAGMENT)
        self._skin_pick_program = ctx.program(vertex_shader=shaders.SKIN_VERTEX,
                                              fragment_shader=shaders.PICK_FRAGMENT)
        self._rigid_program = ctx.program(vertex_shader=shaders.RIGID_VERTEX,
                                          fragment_shader=shaders.MESH_FRAGMENT)
        self._rigid_pick_program = ctx.program(vertex_shader=shaders.RIGID_VERTEX,
                                               fragment_shader=shaders.PICK_FRAGMENT)
        self._rigid_program["u_highlight_color"].value = HIGHLIGHT_COLOR
        self._skin_program["u_highlight_color"].value = HIGHLIGHT_COLOR
        self._mesh_program["u_highlight_color"].value = HIGHLIGHT_COLOR
        corners = np.array([-1, -1, 1, -1, 1, 1, -1, -1, 1, 1, -1, 1], np.float32)
        self._grid_vbo = ctx.buffer(corners.tobytes())
        self._grid_vao = ctx.vertex_array(self._grid_program, [(self._grid_vbo, "2f", "in_corner")])
        self._present_program = ctx.program(vertex_shader=shaders.PRESENT_VERTEX,
                                            fragment_shader=shaders.PRESENT_FRAGMENT)
        self._present_vao = ctx.vertex_array(self._present_program, [])
        self._line_capacity = 0
        self._line_vbo: moderngl.Buffer | None = None
        self._line_vao: moderngl.VertexArray | None = None
        self._meshes: dict[str, _GpuMesh] = {}
        self._skinned: dict[str, GpuSkinnedMesh] = {}
        self._last_skins: list[tuple[str, np.ndarray]] = []
        self.merge_rigid = True
        """Draw a frame's singleton rigid opaque items as one merged draw (:mod:`jackpy.render.rigid`;
        the same image, ~45 draw calls fewer for a figure)."""
        self._rigid: dict[tuple, tuple[str, RigidBatch]] = {}
        """Merged batches by their items' (mesh key, upload version), most recent last."""
        self._rigid_names: dict[str, RigidBatch] = {}
        self._rigid_serial = 0
        self._mesh_version = 0
        for key, mesh in BUILTIN_MESHES.items():
            self.add_mesh(key, mesh)
        self._framebuffers: list[moderngl.Framebuffer | moderngl.Renderbuffer | moderngl.Texture] = []
        self._msaa: dict[int, tuple[moderngl.Framebuffer, list]] = {}
        self._allocate(size)
        self._last: tuple[FrameBatches, list[InstanceBatch], np.ndarray, np.ndarray] | None = None
        self._last_scene: Scene | None = None
        self._frame_key: bytes | None = None
        self._key_since = 0.0
        self.drawn_samples = -1
        """MSAA samples of the image in :attr:`color_texture` (-1: nothing drawn yet)."""
        self.drawn_scale = 1.0
        """The :attr:`render_scale` the image in :attr:`color_texture` was drawn at."""
        self.drawn_coarse = False
        """Whether that image drew the skins' coarse level of detail."""
        self.frames_drawn = 0
        """Frames actually drawn (a :meth:`render` of an unchanged frame draws nothing)."""

    # ------------------------------------------------------------------ resources
    def _allocate(self, size: tuple[int, int]) -> None:
        for obj in self._framebuffers:
            obj.release()
        for fbo, objs in self._msaa.values():
            for obj in objs:
                obj.release()
        self._msaa = {}
        for fbo, objs in getattr(self, "_scaled", {}).values():
            for obj in objs:
                obj.release()
        self._scaled: dict[tuple[int, int], tuple[moderngl.Framebuffer, list]] = {}
        ctx, self.size = self.ctx, (int(size[0]), int(size[1]))
        self._full_texture = ctx.texture(self.size, 4)
        self.color_texture = self._full_texture
        """The texture holding the last drawn image (smaller than :attr:`size` when it was drawn at
        a :attr:`render_scale` below 1; a window shows it stretched over the view)."""
        depth = ctx.depth_renderbuffer(self.size)
        self._resolve_fbo = ctx.framebuffer([self._full_texture], depth)
        pick_tex = ctx.texture(self.size, 1, dtype="i4")
        pick_tex.filter = (moderngl.NEAREST, moderngl.NEAREST)
        pick_depth = ctx.depth_texture(self.size)
        self._pick_fbo = ctx.framebuffer([pick_tex], pick_depth)
        self._framebuffers = [self._resolve_fbo, self._pick_fbo, self._full_texture, depth, pick_tex, pick_depth]
        self._frame_key = None
        self.drawn_samples = -1
        self.drawn_scale = 1.0

    def _scaled_size(self, scale: float) -> tuple[int, int]:
        s = min(1.0, max(0.25, float(scale)))
        return max(1, round(self.size[0] * s)), max(1, round(self.size[1] * s))

    def _scaled_target(self, size: tuple[int, int]) -> tuple[moderngl.Framebuffer, moderngl.Texture]:
        """The single-sample framebuffer (and its colour texture) of a frame drawn at ``size``."""
        if size not in self._scaled:
            tex = self.ctx.texture(size, 4)
            depth = self.ctx.depth_renderbuffer(size)
            fbo = self.ctx.framebuffer([tex], depth)
            self._scaled[size] = (fbo, [fbo, tex, depth])
        fbo, objs = self._scaled[size]
        return fbo, objs[1]

    def _target(self, samples: int) -> moderngl.Framebuffer:
        """The framebuffer a frame with ``samples`` is drawn into: the resolve target itself when
        not multisampled, else a multisampled one made on first use."""
        if samples == 0:
            return self._resolve_fbo
        if samples not in self._msaa:
            color = self.ctx.renderbuffer(self.size, 4, samples=samples)
            depth = self.ctx.depth_renderbuffer(self.size, samples=samples)
            fbo = self.ctx.framebuffer([color], depth)
            self._msaa[samples] = (fbo, [fbo, color, depth])
        return self._msaa[samples][0]

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
        self._mesh_version += 1
        self._meshes[key] = _GpuMesh(self.ctx, mesh, self._mesh_version)

    def remove_mesh(self, key: str) -> None:
        """Free the mesh (plain or skinned) cached under ``key``, if any."""
        for cache in (self._meshes, self._skinned):
            if key in cache:
                cache.pop(key).release()
                self._mesh_version += 1

    def has_mesh(self, key: str) -> bool:
        """Whether a mesh (plain or skinned) is cached under ``key``."""
        return key in self._meshes or key in self._skinned

    def add_skinned_mesh(self, key: str, mesh: SkinnedMesh, replace: bool = False) -> None:
        """Upload skinned ``mesh`` under ``key`` (drawn by a :class:`SkinnedItem` of that key); an
        existing key is kept unless ``replace``."""
        if key in self._skinned:
            if not replace:
                return
            self._skinned.pop(key).release()
        self._skinned[key] = GpuSkinnedMesh(self.ctx, mesh)
        self._mesh_version += 1

    def release(self) -> None:
        """Free every GPU resource of this renderer."""
        for mesh in self._meshes.values():
            mesh.release()
        self._meshes.clear()
        for skinned in self._skinned.values():
            skinned.release()
        self._skinned.clear()
        for batch in self._rigid_names.values():
            batch.release()
        self._rigid.clear()
        self._rigid_names.clear()
        for obj in self._framebuffers:
            obj.release()
        for _, objs in self._msaa.values():
            for obj in objs:
                obj.release()
        self._msaa = {}
        for obj in (self._line_vao, self._line_vbo, self._grid_vao, self._grid_vbo, self._mesh_program,
                    self._pick_program, self._line_program, self._grid_program, self._skin_program,
                    self._skin_pick_program, self._rigid_program, self._rigid_pick_program):
            if obj is not None:
                obj.release()

    # ------------------------------------------------------------------ drawing
    @property
    def refine_pending(self) -> bool:
        """Whether the image on show was drawn with fewer samples than a still frame gets: a later
        :meth:`render` (or :meth:`refine`) of the same frame will draw it again, anti-aliased."""
        return 0 <= self.drawn_samples and (self.drawn_samples < self.still_samples or self.drawn_scale < 1.0
                                          or self.drawn_coarse)

    def render(self, scene: Scene, view: np.ndarray, projection: np.ndarray) -> bool:
        """Draw ``scene`` seen through 4x4 ``view`` (world to camera) and ``projection``.

        Returns whether anything was drawn: a frame equal to the last one is kept as it is,
        unless it has now been still for :attr:`refine_after_s` and is redrawn at
        :attr:`still_samples`.
        """
        items, skinned_items = stand_in(scene.items, scene.skins)  # skins take their bones' items' looks
        scene = replace(scene, items=items, skins=skinned_items)
        unknown = ({i.mesh for i in scene.items} - self._meshes.keys()) | (
            {s.mesh for s in scene.skins} - self._skinned.keys())
        if unknown:
            raise KeyError(f"meshes not uploaded: {sorted(unknown)}")
        rigid: list[tuple[str, np.ndarray]] = []
        if self.merge_rigid:
            kept, merged = split_rigid(scene.items, {k for k, m in self._meshes.items() if m.mergeable is not None})
            if merged:
                scene = replace(scene, items=kept)
                rigid = [(self._rigid_batch(merged), item_texels(merged))]
        batches = build_batches(scene)
        skins = rigid + [(s.mesh, bone_texels(s, self._skinned[s.mesh].n_bones)) for s in scene.skins]
        key = _frame_key(scene, batches, view, projection, self._mesh_version, skins)
        now = time.monotonic()
        if key != self._frame_key:
            self._frame_key, self._key_since = key, now
            samples, scale = self.samples, self.render_scale
        elif self.refine_pending and now - self._key_since >= self.refine_after_s:
            samples, scale = self.still_samples, 1.0
        else:
            return False
        self._draw_frame(scene, batches, skins, view, projection, samples, scale)
        return True

    def _rigid_batch(self, items: list[DrawItem]) -> str:
        """The name of the merged batch of ``items``' meshes, built on first use; the few most
        recent sets are kept (a selection or an analysis can switch between them)."""
        key = tuple((i.mesh, self._meshes[i.mesh].version) for i in items)
        entry = self._rigid.pop(key, None)
        if entry is None:
            self._rigid_serial += 1
            name = f"jackpy:rigid/{self._rigid_serial}"
            entry = (name, RigidBatch(self.ctx, [self._meshes[i.mesh].mergeable for i in items]))
            self._rigid_names[name] = entry[1]
        self._rigid[key] = entry  # most recent last
        while len(self._rigid) > RIGID_CACHE:
            old = next(iter(self._rigid))
            self._rigid_names.pop(self._rigid.pop(old)[0]).release()
        return entry[0]

    def refine(self) -> bool:
        """Redraw the last frame at :attr:`still_samples` and full size now if it was drawn with
        fewer samples or smaller."""
        if self._last is None or self._last_scene is None or not self.refine_pending:
            return False
        batches, _, view, projection = self._last
        self._draw_frame(self._last_scene, batches, self._last_skins, view, projection, self.still_samples)
        return True

    def _full_size(self) -> None:
        """Redraw the last frame at full size (same samples) if it was drawn smaller."""
        if (self.drawn_scale < 1.0 or self.drawn_coarse) and self._last is not None and self._last_scene is not None:
            batches, _, view, projection = self._last
            self._draw_frame(self._last_scene, batches, self._last_skins, view, projection, self.drawn_samples)

    def _draw_frame(self, scene: Scene, batches: FrameBatches, skins: list[tuple[str, np.ndarray]],
                    view: np.ndarray, projection: np.ndarray, samples: int, scale: float = 1.0) -> None:
        ctx = self.ctx
        size = self._scaled_size(scale)
        coarse = scale < 1.0 and scale <= self.coarse_skin_scale  # a moving frame at low quality
        if size == self.size:
            fbo, texture = self._target(samples), self._full_texture
            scale = 1.0
        else:  # a moving frame drawn smaller: single-sampled
            (fbo, texture), samples = self._scaled_target(size), 0
            texture.filter = (self.stretch_filter, self.stretch_filter)  # as the blit or window shows it
        centers = {k: m.center for k, m in self._meshes.items()}
        transparent = item_batches(back_to_front(batches.transparent, view, centers))
        lines = [ln for ln in scene.lines if not ln.on_top] + [ln for ln in scene.lines if ln.on_top]
        n_under, n_top = self._upload_lines(lines)

        fbo.use()
        ctx.viewport = (0, 0, *size)
        fbo.depth_mask = True
        fbo.clear(*rgba(scene.background, 1)[0], depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
        ctx.depth_func = "<"
        self._set_mesh_uniforms(view, projection)
        prog = self._mesh_program

        ctx.polygon_offset = (1.0, 1.0)
        self._draw(prog, batches.opaque)
        self._draw_skins(skins, coarse)
        ctx.polygon_offset = (0.0, 0.0)
        ctx.depth_func = "<="
        self._draw_wireframe(batches.wireframe)
        if n_under or n_top:
            self._line_program["u_view"].write(_mat(view))
            self._line_program["u_proj"].write(_mat(projection))
        self._draw_lines(0, n_under)

        ctx.enable(moderngl.BLEND)
        ctx.blend_func = (moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA,
                          moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA)
        fbo.depth_mask = False
        if scene.grid is not None:
            self._draw_grid(scene.grid, view, projection)
        if transparent:
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
        self._draw_lines(n_under, n_top)
        fbo.depth_mask = True
        ctx.disable(moderngl.BLEND)

        if samples and texture is self._full_texture:
            ctx.copy_framebuffer(self._resolve_fbo, fbo)
        self.color_texture = texture
        self.drawn_scale = scale
        self.drawn_coarse = coarse
        pickable = [i for i in batches.transparent if i.pick_id is not None]
        self._last = (batches, item_batches(pickable), np.array(view), np.array(projection))
        self._last_skins = skins
        self._last_scene = scene
        self.drawn_samples = samples
        self.frames_drawn += 1

    def _set_mesh_uniforms(self, view: np.ndarray, projection: np.ndarray) -> None:
        rotation = np.asarray(view, float)[:3, :3]
        for prog in (self._mesh_program, self._pick_program, self._skin_program, self._skin_pick_program,
                     self._rigid_program, self._rigid_pick_program):
            prog["u_view"].write(_mat(view))
            prog["u_proj"].write(_mat(projection))
        for prog in (self._mesh_program, self._skin_program, self._rigid_program):
            prog["u_key_direction"].value = tuple(rotation @ KEY_LIGHT_DIRECTION)
            prog["u_up"].value = tuple(rotation[:, 1])
            prog["u_orthographic"].value = bool(projection[3, 3] == 1.0)
            prog["u_flat"].value = False

    def _draw(self, program: moderngl.Program, batches: list[InstanceBatch]) -> None:
        for batch in batches:
            self._meshes[batch.mesh].draw(program, batch.records)

    def _draw_skins(self, skins: list[tuple[str, np.ndarray]], coarse: bool = False, pick: bool = False) -> None:
        """The skins (their coarse level of detail if ``coarse``) and merged rigid batches, into
        the colour or (``pick``) the id attachment."""
        for key, texels in skins:
            rigid = self._rigid_names.get(key)
            if rigid is not None:
                rigid.draw(self._rigid_pick_program if pick else self._rigid_program, texels)
            else:
                self._skinned[key].draw(self._skin_pick_program if pick else self._skin_program, texels, coarse)

    def _draw_wireframe(self, batches: list[InstanceBatch]) -> None:
        if not batches:
            return
        self._mesh_program["u_flat"].value = True
        self.ctx.wireframe = True
        self._draw(self._mesh_program, batches)
        self.ctx.wireframe = False
        self._mesh_program["u_flat"].value = False

    def _upload_lines(self, lines: list[Lines]) -> tuple[int, int]:
        """Write every line vertex of the frame into one buffer (depth-tested ones first); returns
        the vertex counts (depth-tested, on top)."""
        if not lines:
            return 0, 0
        parts = []
        for ln in lines:
            seg = np.asarray(ln.segments, np.float32).reshape(-1, 2, 3)
            color = np.repeat(rgba(ln.color, len(seg)), 2, axis=0)
            parts.append(np.hstack([seg.reshape(-1, 3), color]))
        data = np.ascontiguousarray(np.concatenate(parts), np.float32)
        n_top = sum(2 * len(np.asarray(ln.segments).reshape(-1, 2, 3)) for ln in lines if ln.on_top)
        if len(data) == 0:
            return 0, 0
        if data.nbytes > self._line_capacity:
            if self._line_vao is not None and self._line_vbo is not None:
                self._line_vao.release()
                self._line_vbo.release()
            self._line_capacity = max(data.nbytes, 2 * self._line_capacity)
            self._line_vbo = self.ctx.buffer(reserve=self._line_capacity, dynamic=True)
            self._line_vao = self.ctx.vertex_array(
                self._line_program, [(self._line_vbo, "3f 4f", "in_position", "in_color")])
        assert self._line_vbo is not None
        self._line_vbo.write(data.tobytes())
        return len(data) - n_top, n_top

    def _draw_lines(self, first: int, count: int) -> None:
        if count and self._line_vao is not None:
            self._line_vao.render(moderngl.LINES, vertices=count, first=first)

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
        """The last rendered image at full size, (height, width, 4) uint8 RGBA, first row at the
        top (a frame drawn smaller is drawn again at full size first)."""
        self._full_size()
        w, h = self.size
        data = self._resolve_fbo.read(components=4, alignment=1)  # the colour attachment
        return np.frombuffer(data, np.uint8).reshape(h, w, 4)[::-1].copy()

    def blit(self, destination: moderngl.Framebuffer) -> None:
        """Copy the last rendered image into ``destination`` (e.g. a window's ``ctx.screen``); one
        drawn smaller is stretched over it (with :attr:`stretch_filter`)."""
        if self.color_texture is self._full_texture:
            self.ctx.copy_framebuffer(destination, self._resolve_fbo)
            return
        ctx = self.ctx
        destination.use()
        ctx.viewport = (0, 0, *destination.size)
        ctx.disable(moderngl.DEPTH_TEST | moderngl.BLEND | moderngl.CULL_FACE)
        self.color_texture.use(0)
        self._present_program["u_image"].value = 0
        self._present_vao.render(moderngl.TRIANGLES, vertices=3)

    def save_png(self, path: str | Path) -> None:
        """Write the last rendered image to a PNG file."""
        write_png(path, self.read_pixels())

    def read_ids(self) -> tuple[np.ndarray, np.ndarray]:
        """(ids, depth) of the whole last frame: per pixel the pick id of the nearest opaque (or
        pickable transparent) surface, 0 for none, and its depth-buffer value in [0, 1]; row 0 is
        the top of the image (the ID buffer of visibility analyses, book §5.1.1)."""
        w, h = self.size
        if self._last is None:
            raise ValueError("nothing rendered yet")
        batches, transparent, view, projection = self._last
        ctx, fbo = self.ctx, self._pick_fbo
        fbo.use()
        fbo.scissor = None
        fbo.depth_mask = True
        fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
        ctx.depth_func = "<"
        self._set_mesh_uniforms(view, projection)
        self._draw(self._pick_program, batches.opaque)
        self._draw_skins(self._last_skins, pick=True)
        self._draw(self._pick_program, transparent)
        ids = np.frombuffer(fbo.read(components=1, dtype="i4"), np.int32).reshape(h, w)[::-1]
        depth = np.frombuffer(fbo.depth_attachment.read(), np.float32).reshape(h, w)[::-1]
        return ids.astype(np.int64), depth.copy()

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
        self._draw_skins(self._last_skins, pick=True)
        self._draw(self._pick_program, transparent)
        value = np.frombuffer(fbo.read(viewport=(int(x), gl_y, 1, 1), components=1, dtype="i4"), np.int32)
        fbo.scissor = None
        pick_id = int(value[0])
        return pick_id if pick_id != 0 else None


def _frame_key(scene: Scene, batches: FrameBatches, view: np.ndarray, projection: np.ndarray,
               mesh_version: int, skins: list[tuple[str, np.ndarray]] = ()) -> bytes:
    """Bytes that change whenever the drawn image could: every instance record, skinned item's
    bone texels, transparent item, line, the grid, background, camera and the cached meshes."""
    parts = [np.asarray(view, np.float64).tobytes(), np.asarray(projection, np.float64).tobytes(),
             repr((mesh_version, scene.grid, tuple(scene.background))).encode()]
    for key, texels in skins:
        parts += [b"S" + key.encode(), texels.tobytes()]
    for group in (batches.opaque, batches.wireframe):
        for b in group:
            parts += [b"%s:%d" % (b.mesh.encode(), len(b.records)), b.records.tobytes()]
    for item in batches.transparent:
        parts += [repr((item.mesh, tuple(item.color), item.pick_id, item.wireframe, item.highlighted)).encode(),
                  np.asarray(item.transform, np.float64).tobytes()]
    for ln in scene.lines:
        parts += [b"L%d" % ln.on_top, np.asarray(ln.segments, np.float64).tobytes(),
                  np.asarray(ln.color, np.float64).tobytes()]
    return b"|".join(parts)
