"""Headless rendering: a standalone EGL context, an offscreen renderer, PNG output."""

from __future__ import annotations

from pathlib import Path

import moderngl
import numpy as np
from PIL import Image

from jackpy.ui.render.renderer import Renderer


def create_egl_context() -> moderngl.Context:
    """A standalone OpenGL 3.3+ core context on EGL (no window system needed).

    Raises whatever moderngl raises when no EGL device is available.
    """
    return moderngl.create_standalone_context(require=330, backend="egl")


def offscreen_renderer(width: int, height: int, samples: int = 4,
                       ctx: moderngl.Context | None = None) -> Renderer:
    """A :class:`Renderer` of ``width`` x ``height`` pixels on a new (or the given) EGL context."""
    return Renderer(ctx if ctx is not None else create_egl_context(), (width, height), samples)


def write_png(path: str | Path, pixels: np.ndarray) -> None:
    """Save (H, W, 4) uint8 RGBA pixels, first row at the top, as a PNG file."""
    Image.fromarray(np.asarray(pixels, np.uint8), "RGBA").save(Path(path))
