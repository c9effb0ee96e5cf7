"""Pictures and ID buffers of lists of bodies, for the analyses and reports, drawn by the one
:class:`~jackpy.render.Renderer` (the window's shaders, lighting and perspective).

A :class:`Body` is a mesh in its own frame plus its 4x4 world transform, a colour or per-vertex
colours. :class:`BodyRenderer` draws lists of them offscreen: :meth:`BodyRenderer.render` a shaded
RGB picture, :meth:`BodyRenderer.render_ids` per pixel the 1-based index of the nearest body and
its depth (book §5.1.1's Z-buffer perception). It knows neither figures nor windows.
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from jackpy.errors import JackpyError
from jackpy.render.mesh import Mesh as RenderMesh
from jackpy.render.projection import linear_depth, look_at, perspective_matrix
from jackpy.render.scene import DrawItem, Scene

__all__ = ["Body", "BodyRenderer", "linear_depth", "look_at", "perspective_matrix"]


@dataclass
class Body:
    """Something to draw: ``mesh`` (any object with ``vertices`` (n,3) m and ``faces`` (m,3), and
    optionally unit vertex ``normals`` (n,3), else computed with creases) in its own frame, ``model`` its 4x4 world transform, ``name``, ``colour`` (RGBA in [0, 1]) or
    per-vertex ``vertex_colours`` (n,3)."""

    name: str
    mesh: Any
    model: np.ndarray
    colour: tuple[float, float, float, float] = (0.75, 0.75, 0.78, 1.0)
    vertex_colours: np.ndarray | None = None


class BodyRenderer:
    """Draw :class:`Body` lists at ``size`` = (width, height) pixels with a :class:`Renderer`.

    ``ctx``: an existing moderngl context (e.g. the workbench window's, where a second EGL context
    cannot live beside a GLX window); it must be current on the calling thread and is not released
    by :meth:`release`. By default a standalone EGL context is made and owned. ``samples``: MSAA of
    the pictures (ID buffers are never multisampled)."""

    MAX_CACHED = 512

    def __init__(self, size: tuple[int, int] = (512, 512), ctx: Any = None, samples: int = 4) -> None:
        from jackpy.render.offscreen import create_egl_context
        from jackpy.render.renderer import Renderer

        self._owns_ctx = ctx is None
        if ctx is None:
            try:
                ctx = create_egl_context()
            except Exception as exc:  # no EGL/GPU driver: one clear line
                raise JackpyError(f"offscreen rendering is unavailable (moderngl EGL context: {exc})") from None
        self.ctx = ctx
        self.size = (int(size[0]), int(size[1]))
        self.renderer = Renderer(ctx, self.size, samples, samples)
        self._uploaded: dict[str, None] = {}  # keys in least-recently-used order

    def release(self) -> None:
        """Free the renderer (and the GL context when it was made here)."""
        self.renderer.release()
        if self._owns_ctx:
            self.ctx.release()

    def _key(self, body: Body) -> str:
        """The renderer's mesh of ``body``, keyed by its content (vertices, faces, colours), so equal
        geometry is uploaded once however often it is rebuilt (posed skin pieces are new objects
        every picture); at most ``MAX_CACHED`` meshes are kept, the least recently used go first."""
        colours = body.vertex_colours
        v = np.ascontiguousarray(body.mesh.vertices, float)
        f = np.ascontiguousarray(np.asarray(body.mesh.faces, np.int64).reshape(-1, 3))
        digest = hashlib.blake2b(v.tobytes(), digest_size=16)
        digest.update(f.tobytes())
        normals = getattr(body.mesh, "normals", None)
        for extra in (colours, normals):
            digest.update(b"-" if extra is None else np.ascontiguousarray(extra, float).tobytes())
        key = f"body:{digest.hexdigest()}"
        if key in self._uploaded:
            self._uploaded[key] = self._uploaded.pop(key)  # most recently used last
            return key
        if colours is None and normals is None:
            mesh = RenderMesh.from_triangles(v, f)
        else:  # given normals, or per-vertex colours on their vertices: smooth, no crease splits
            from jackpy.render.mesh import vertex_normals

            mesh = RenderMesh(v, vertex_normals(v, f) if normals is None else normals, f,
                              None if colours is None else np.asarray(colours, float).reshape(-1, 3))
        self.renderer.add_mesh(key, mesh, replace=True)
        self._uploaded[key] = None
        while len(self._uploaded) > self.MAX_CACHED:
            oldest = next(iter(self._uploaded))
            self.renderer.remove_mesh(oldest)
            del self._uploaded[oldest]
        return key

    def _scene(self, opaque: Sequence[Body], translucent: Sequence[Body], background) -> Scene:
        scene = Scene(grid=None, background=tuple(background) + (1.0,) if len(background) == 3 else tuple(background))
        for k, b in enumerate(opaque):
            colour = (1.0, 1.0, 1.0, b.colour[3]) if b.vertex_colours is not None else tuple(b.colour)
            scene.items.append(DrawItem(self._key(b), np.asarray(b.model, float), colour, pick_id=k + 1))
        for b in translucent:
            scene.items.append(DrawItem(self._key(b), np.asarray(b.model, float), tuple(b.colour), transparent=True))
        return scene

    def render(self, opaque: Sequence[Body], view: np.ndarray, projection: np.ndarray,
               translucent: Sequence[Body] = (), background: tuple[float, ...] = (1.0, 1.0, 1.0),
               light: np.ndarray | None = None) -> np.ndarray:
        """A shaded RGB picture (h, w, 3) uint8: opaque bodies, then translucent ones blended over
        them. Lit as the workbench's view is (``light`` is accepted for callers of the former
        report renderer and not used: the key light is fixed in the world)."""
        self.renderer.render(self._scene(list(opaque), list(translucent), background), view, projection)
        return self.renderer.read_pixels()[..., :3].copy()

    def render_ids(self, bodies: Sequence[Body], view: np.ndarray, projection: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(ids, depth): per pixel the 1-based index into ``bodies`` of the nearest surface (0 for
        none) and the depth-buffer value in [0, 1]; row 0 is the top of the image."""
        self.renderer.render(self._scene(list(bodies), [], (0.0, 0.0, 0.0)), view, projection)
        return self.renderer.read_ids()
