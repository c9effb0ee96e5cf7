"""Headless screenshots: render a scene offscreen (EGL) from a named view and save a PNG."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from jackpy.peabody import Environment

if TYPE_CHECKING:
    from jackpy.ui.app import App

VIEWS = ("front", "side", "top", "iso")


def render_scene(env: Environment, size: tuple[int, int] = (1280, 800), view: str = "iso",
                 skeleton: bool = False) -> np.ndarray:
    """(H, W, 4) uint8 RGBA image of ``env`` from ``view`` (``front``, ``side``, ``top``, ``iso``)."""
    from jackpy.ui.app import App, Settings
    from jackpy.render import offscreen_renderer

    if view not in VIEWS:
        raise ValueError(f"unknown view {view!r}; use one of {', '.join(VIEWS)}")
    renderer = offscreen_renderer(*size)
    try:
        app = App(env, renderer, size, Settings(skeleton=skeleton))
        app.camera.set_preset(view)
        app.frame_all()
        app.step()
        return renderer.read_pixels()
    finally:
        renderer.release()


def save_view(app: "App", path: str | os.PathLike[str]) -> None:
    """Save what the app's 3-D view shows (last frame, without the panels) as a PNG."""
    from jackpy.render import write_png

    if app.renderer is None:
        raise ValueError("no renderer: nothing has been drawn")
    write_png(Path(path), app.renderer.read_pixels())
    app.info(f"screenshot {path}")
