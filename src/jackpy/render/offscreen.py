"""Headless rendering: a standalone EGL context and an offscreen renderer on it."""

from __future__ import annotations

import moderngl

from jackpy.render.renderer import Renderer


def create_egl_context() -> moderngl.Context:
    """A standalone OpenGL 3.3+ core context on EGL (no window system needed).

    Raises whatever moderngl raises when no EGL device is available.
    """
    return moderngl.create_standalone_context(require=330, backend="egl")


def offscreen_renderer(width: int, height: int, samples: int | None = 4,
                       ctx: moderngl.Context | None = None) -> Renderer:
    """A :class:`Renderer` of ``width`` x ``height`` pixels on a new (or the given) EGL context.

    Pictures (screenshots, reports) default to 4x MSAA whatever the rasteriser; ``samples=None``
    chooses as the window does (:func:`~jackpy.render.renderer.default_samples`).
    """
    return Renderer(ctx if ctx is not None else create_egl_context(), (width, height), samples)

