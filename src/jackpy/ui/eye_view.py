"""The eye view: a second viewport seen from the analysed figure's eyes, following it live.

The camera is :func:`jackpy.analysis.eye_view` (eye point between the eyes, gaze, 90 degrees
vertical at 4:3, about 106 degrees horizontal). It renders with a second
:class:`~jackpy.render.Renderer` on the SAME moderngl context as the window (a second EGL
context beside a GLX window fails under Mesa), into that renderer's own framebuffers; the window
shows the resolved colour texture with ``imgui.image``. The head and everything distal to it (eyes,
jaw) are left out of the picture: the eye point lies inside them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from jackpy.peabody import Figure
from jackpy.render import Scene
from jackpy.ui.scene_view import SceneView

if TYPE_CHECKING:
    from jackpy.analysis import EyeView
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState
    from jackpy.render import Renderer

EYE_VIEW_SIZE = (400, 300)
"""Pixels of the eye view (4:3, the eye camera's aspect)."""


def hidden_segments(figure: Figure, segment: str) -> set[str]:
    """``segment`` and every segment distal to it (away from the figure's root)."""
    kin = figure.kinematics()
    start = kin.segment_index[segment]
    out = {start}
    for s in range(len(kin.segment_names)):  # parents come before children in the flattened tree
        if kin.parent[s] in out and s != 0:
            out.add(s)
    return {kin.segment_names[s] for s in out}


def eye_scene(app: App, view: SceneView, figure: Figure) -> Scene:
    """The app's environment without the figure's head (and what hangs from it), no goal markers."""
    from jackpy.analysis import figure_parts

    scene = view.build(app.env, (), False, None, None, app.settings.show_floor)
    hide = {view.mesh_key(figure.name, s) for s in hidden_segments(figure, figure_parts(figure).eyes.segment)}
    scene.items = [it for it in scene.items if it.mesh not in hide]
    return scene


class EyeViewport:
    """Renders the eye view each frame into its own framebuffer on the app's GL context."""

    def __init__(self, size: tuple[int, int] = EYE_VIEW_SIZE) -> None:
        self.size = size
        self.renderer: Renderer | None = None
        self.view = SceneView()
        self.eye: EyeView | None = None
        self.error: str | None = None

    def render(self, app: App) -> bool:
        """Draw the current scene from the figure's eyes; False (with :attr:`error`) when the
        figure has no recognised eyes or nothing is drawn yet."""
        from jackpy.analysis import eye_view
        from jackpy.render import Renderer

        fig = app.figure_of_interest()
        if fig is None or app.renderer is None:
            self.error = "no figure"
            return False
        try:
            self.eye = eye_view(fig)
        except Exception as exc:
            self.error = f"{exc}"
            return False
        if self.renderer is None or self.renderer.ctx is not app.renderer.ctx:
            self.renderer = Renderer(app.renderer.ctx, self.size)
        self.view.upload(self.renderer, app.env)
        scene = eye_scene(app, self.view, fig)
        self.renderer.render(scene, self.eye.view_matrix(), self.eye.projection(near=0.03))
        self.error = None
        return True

    def texture_id(self) -> int | None:
        """The GL name of the resolved colour texture (for ``imgui.image``)."""
        return None if self.renderer is None else int(self.renderer.color_texture.glo)

    def read_pixels(self) -> np.ndarray:
        """The last eye view, (H, W, 4) uint8, first row at the top."""
        assert self.renderer is not None
        return self.renderer.read_pixels()

    def release(self) -> None:
        if self.renderer is not None:
            self.renderer.release()
            self.renderer = None


def draw_window(app: App, ui: UiState) -> None:
    """The imgui window showing the eye view (the App renders it after the main view)."""
    from imgui_bundle import imgui

    state = app.analysis
    state.eye_view_open = bool(ui.open_panels.get("Eye view"))
    if not state.eye_view_open:
        return
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((8, vp.size.y - EYE_VIEW_SIZE[1] - 70), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((EYE_VIEW_SIZE[0] + 16, EYE_VIEW_SIZE[1] + 60), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Eye view"] = imgui.begin("Eye view", ui.open_panels["Eye view"])
    if visible:
        ev = state.eye_viewport
        tex = ev.texture_id() if ev is not None else None
        if ev is not None and ev.error:
            imgui.text_disabled(ev.error)
        elif tex is None:
            imgui.text_disabled("(first frame)")
        else:
            avail = imgui.get_content_region_avail()
            w = max(64.0, avail.x)
            h = w * EYE_VIEW_SIZE[1] / EYE_VIEW_SIZE[0]
            # GL textures start at the bottom row: flip v
            imgui.image(imgui.ImTextureRef(tex), (w, h), (0.0, 1.0), (1.0, 0.0))
            if ev.eye is not None:
                p = ev.eye.position * 100
                imgui.text(f"eye at ({p[0]:.0f}, {p[1]:.0f}, {p[2]:.0f}) cm, 90 x 106 deg")
    imgui.end()
