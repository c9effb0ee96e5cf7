"""The workbench window: glfw + moderngl + Dear ImGui (imgui-bundle's C++ glfw/opengl3 backends).

The window owns the GL context and forwards every glfw callback first to ImGui, then, unless ImGui
or the gizmo wants the mouse or keyboard, to the :class:`~jackpy.ui.app.App` handlers. Cursor
positions arrive in window coordinates and are scaled to framebuffer pixels. One
:meth:`Window.frame` = poll events, ImGui frame with panels and gizmo, ``app.step()`` (IK, then the
3-D view into the renderer's framebuffer, shown as an image in the dock's central node behind every window), ImGui, swap.

:meth:`Window.run` does not spin when nothing happens: after ``IDLE_AFTER_FRAMES`` frames without
input, solving, sensor streaming or a redrawn 3-D view, it sleeps in ``glfw.wait_events_timeout``
until input arrives or ``IDLE_WAIT_S`` passes (so progress bars, autosave and the renderer's
anti-aliased still frame still come). An unchanged 3-D view is not redrawn (see ``Renderer.render``).
"""

from __future__ import annotations

import ctypes
import time
from collections.abc import Callable
from pathlib import Path

import imgui_bundle  # noqa: F401  (first: points the glfw package at imgui-bundle's libglfw)
import glfw
import moderngl
from imgui_bundle import imgui

from jackpy.errors import JackpyError
from jackpy.ui.app import App, KEY_ESCAPE, MOD_CONTROL, MOD_SHIFT, PRESS
from jackpy.ui.gizmo import Gizmo
from jackpy.ui.layout import Layout, Rect
from jackpy.ui.panels import UiState, draw_all, panels
from jackpy.ui.status import FrameRate, Notifications, draw_status_bar
from jackpy.render import Renderer

KEY_O, KEY_Q, KEY_S, KEY_T, KEY_R, KEY_P = ord("O"), ord("Q"), ord("S"), ord("T"), ord("R"), ord("P")
IDLE_AFTER_FRAMES = 3
"""Quiet frames (ImGui settles hover and layout in one or two) before the loop sleeps."""
IDLE_WAIT_S = 0.25
"""Longest sleep of an idle loop, s."""


class WindowError(JackpyError):
    """No window could be opened (no display, no OpenGL 3.3)."""


class Window:
    """A glfw window showing an :class:`App`; ``visible=False`` for tests that only need the loop."""

    def __init__(self, app: App, title: str = "jackpy", size: tuple[int, int] = (1280, 800),
                 visible: bool = True, layout_file: Path | None = None) -> None:
        reporting, glfw.ERROR_REPORTING = glfw.ERROR_REPORTING, "ignore"  # our own one-line error instead
        try:
            ok = glfw.init()
        finally:
            glfw.ERROR_REPORTING = reporting
        if not ok:
            raise WindowError("cannot initialise glfw (is there a display? set DISPLAY or use xvfb-run)")
        glfw.window_hint(glfw.CONTEXT_VERSION_MAJOR, 3)
        glfw.window_hint(glfw.CONTEXT_VERSION_MINOR, 3)
        glfw.window_hint(glfw.OPENGL_PROFILE, glfw.OPENGL_CORE_PROFILE)
        glfw.window_hint(glfw.OPENGL_FORWARD_COMPAT, True)
        glfw.window_hint(glfw.VISIBLE, visible)
        self.handle = glfw.create_window(size[0], size[1], title, None, None)
        if not self.handle:
            glfw.terminate()
            raise WindowError("cannot create an OpenGL 3.3 core window")
        glfw.make_context_current(self.handle)
        glfw.swap_interval(1 if visible else 0)
        self.ctx = moderngl.create_context()
        self._addr = ctypes.cast(self.handle, ctypes.c_void_p).value
        self.imgui_ctx = imgui.create_context()
        imgui.get_io().config_flags |= imgui.ConfigFlags_.nav_enable_keyboard
        self.layout = Layout(layout_file)  # docking, the user's saved layout ($JACKPY_HOME/layout.ini)
        imgui.backends.glfw_init_for_opengl(self._addr, False)
        imgui.backends.opengl3_init("#version 330")
        self.app = app
        app.frame_budget.adaptive = True  # interactive frames: the solve's box is strict (ui.frame_budget)
        fb = glfw.get_framebuffer_size(self.handle)
        app.renderer = Renderer(self.ctx, fb)
        app.resize(*fb)
        self.view_rect = Rect(0.0, 0.0, float(size[0]), float(size[1]))
        """The 3-D view's rect (the dock's central node) in window coordinates."""
        self.notifications = Notifications()
        app.on_log = self.notifications.push
        self.rate = FrameRate()
        self.ui = UiState()
        self.gizmo = Gizmo()
        self._closed = False
        self._title = title
        self._quiet = 0  # frames since the last input or activity
        self.after_swap: list[Callable[[], None]] = []
        """Called after each frame's swap (the test engine's PostSwap)."""
        self.new_frame: Callable[[], None] = imgui.new_frame
        self.end_frame: Callable[[], None] = imgui.end_frame
        """ImGui's NewFrame and EndFrame; :class:`jackpy.ui.gui_driver.GuiDriver` swaps in calls
        that release the GIL, so that imgui's test engine can run its Python tests on its thread."""
        # keep references: glfw holds only C pointers to these
        self._callbacks = (self.cursor_pos_callback, self.mouse_button_callback, self.scroll_callback,
                           self.key_callback, self.char_callback, self.framebuffer_size_callback)
        glfw.set_cursor_pos_callback(self.handle, self.cursor_pos_callback)
        glfw.set_mouse_button_callback(self.handle, self.mouse_button_callback)
        glfw.set_scroll_callback(self.handle, self.scroll_callback)
        glfw.set_key_callback(self.handle, self.key_callback)
        glfw.set_char_callback(self.handle, self.char_callback)
        glfw.set_framebuffer_size_callback(self.handle, self.framebuffer_size_callback)
        self._settle_layout()

    def _settle_layout(self) -> None:
        """Two ImGui frames of the panels without solving or drawing the 3-D view, so that the
        dock's central node (the 3-D view's rect and size) is final before the first real frame."""
        for _ in range(2):
            self.panels_frame()

    def panels_frame(self, extra: Callable[[], None] | None = None) -> None:
        """One ImGui frame of the panels (and ``extra``) only: no events polled, no solve, no 3-D
        view drawn, nothing shown (layout settling; tests that sweep the mouse over widgets)."""
        imgui.backends.opengl3_new_frame()
        imgui.backends.glfw_new_frame()
        self.new_frame()
        draw_all(self.app, self.ui, self._chrome)
        if extra is not None:
            extra()
        self.end_frame()

    # ------------------------------------------------------------------ glfw callbacks
    def _scale(self) -> tuple[float, float]:
        w, h = glfw.get_window_size(self.handle)
        fw, fh = glfw.get_framebuffer_size(self.handle)
        return fw / max(w, 1), fh / max(h, 1)

    def _viewport_has_mouse(self) -> bool:
        """The 3-D view gets the mouse unless ImGui or the gizmo wants it (a drag keeps it)."""
        if self.app.manipulator.active or self.app.dragging:
            return True
        return not imgui.get_io().want_capture_mouse and not self.gizmo.wants_mouse()

    def cursor_pos_callback(self, window: object, x: float, y: float) -> None:
        self._quiet = 0
        imgui.backends.glfw_cursor_pos_callback(self._addr, x, y)
        sx, sy = self._scale()
        r = self.view_rect
        self.app.on_cursor_pos((x - r.x) * sx, (y - r.y) * sy)

    def view_to_window(self, p: "tuple[float, float] | object") -> tuple[float, float]:
        """Window coordinates of 3-D view pixel ``p`` (framebuffer pixels of the view, e.g.
        :meth:`App.world_to_pixel`): the inverse of what :meth:`cursor_pos_callback` does."""
        sx, sy = self._scale()
        x, y = p  # type: ignore[misc]
        return self.view_rect.x + float(x) / sx, self.view_rect.y + float(y) / sy

    def mouse_button_callback(self, window: object, button: int, action: int, mods: int) -> None:
        self._quiet = 0
        imgui.backends.glfw_mouse_button_callback(self._addr, button, action, mods)
        if action != PRESS or self._viewport_has_mouse():
            self.app.on_mouse_button(button, action, mods)

    def scroll_callback(self, window: object, dx: float, dy: float) -> None:
        self._quiet = 0
        imgui.backends.glfw_scroll_callback(self._addr, dx, dy)
        if not imgui.get_io().want_capture_mouse:
            self.app.on_scroll(dx, dy)

    def key_callback(self, window: object, key: int, scancode: int, action: int, mods: int) -> None:
        self._quiet = 0
        imgui.backends.glfw_key_callback(self._addr, key, scancode, action, mods)
        if imgui.get_io().want_text_input and key != KEY_ESCAPE:
            return  # typing in a text field; anywhere else the shortcuts work (a panel has the focus)
        if self.ui.files.active or self.ui.confirm is not None:
            return  # a file dialog or prompt is open: its buttons answer, not the shortcuts
        if action == PRESS and mods & MOD_CONTROL and key in (KEY_O, KEY_S, KEY_Q, KEY_P):
            self._shortcut(key, bool(mods & MOD_SHIFT))
            return
        if action == PRESS and not mods and key in (KEY_T, KEY_R):
            self.gizmo.rotate = key == KEY_R
            return
        self.app.on_key(key, scancode, action, mods)

    def char_callback(self, window: object, codepoint: int) -> None:
        self._quiet = 0
        imgui.backends.glfw_char_callback(self._addr, codepoint)

    def framebuffer_size_callback(self, window: object, width: int, height: int) -> None:
        self._quiet = 0  # the next frame sizes the 3-D view to the dock's central node

    def _shortcut(self, key: int, shift: bool = False) -> None:
        from jackpy.ui import commands

        if key == KEY_Q:
            self.ui.quit_requested = True
        elif key == KEY_O:
            commands.ask_file(self.app, self.ui, "open")
        elif key == KEY_P:
            self.ui.palette_open = shift or self.ui.palette_open
        elif shift:
            commands.ask_file(self.app, self.ui, "save_as")
        else:
            commands.save(self.app, self.ui)

    # ------------------------------------------------------------------ loop
    def frame(self) -> None:
        """Poll input and draw one frame."""
        glfw.poll_events()
        imgui.backends.opengl3_new_frame()
        imgui.backends.glfw_new_frame()
        self.new_frame()
        self.rate.tick()
        draw_all(self.app, self.ui, self._chrome)
        self.notifications.draw(self.view_rect)
        fw, fh = glfw.get_framebuffer_size(self.handle)
        r = self.view_rect
        self.gizmo.draw(self.app, r.w, r.h, r.x, r.y)
        self.end_frame()
        imgui.render()
        drawn = self.app.renderer.frames_drawn if self.app.renderer is not None else 0
        self.ctx.screen.use()
        self.ctx.viewport = (0, 0, fw, fh)
        self.ctx.screen.clear(0.12, 0.12, 0.13, 1.0)
        if fw > 0 and fh > 0:
            self.app.step()
            self.ctx.screen.use()
            self.ctx.viewport = (0, 0, fw, fh)
        imgui.backends.opengl3_render_draw_data(imgui.get_draw_data())
        self.update_title()
        glfw.swap_buffers(self.handle)
        for hook in self.after_swap:
            hook()
        busy = self.app.needs_solve or self.app.driving or (
            self.app.renderer is not None and self.app.renderer.frames_drawn != drawn)
        self._quiet = 0 if busy else self._quiet + 1

    def _chrome(self) -> None:
        """Between the menu bar and the panels: the status bar, the dockspace (its central node
        is the 3-D view, sized to it) and the 3-D view's image behind every window."""
        draw_status_bar(self.app, self.rate)
        if self.ui.reset_layout:
            self.layout.request_reset()
            self.ui.reset_layout = False
        r = self.view_rect = self.layout.begin([p.title for p in panels()])
        sx, sy = self._scale()
        size = (max(int(r.w * sx), 1), max(int(r.h * sy), 1))
        if size != self.app.size:
            self.app.resize(*size)
        if self.app.renderer is not None:
            tex = imgui.ImTextureRef(int(self.app.renderer.color_texture.glo))
            imgui.get_background_draw_list().add_image(tex, (r.x, r.y), (r.x + r.w, r.y + r.h),
                                                       (0.0, 1.0), (1.0, 0.0))

    @property
    def idle(self) -> bool:
        """Nothing has changed for a few frames: no input, no solve, no streaming, no redraw."""
        return self._quiet >= IDLE_AFTER_FRAMES

    @property
    def should_close(self) -> bool:
        """Whether to end: a quit (Ctrl+Q, File → Quit, the window's close button) of a clean
        document, or one confirmed by Discard or a Save; with unsaved changes a quit asks first."""
        asked = bool(glfw.window_should_close(self.handle)) or self.ui.quit_requested
        if asked and self.app.dirty and not self.ui.quit_confirmed:
            glfw.set_window_should_close(self.handle, False)
            self.ui.quit_requested = False
            self.ui.confirm = "quit"  # Save / Discard / Cancel (menu_bar)
            return False
        return asked

    def update_title(self) -> None:
        """``name — jackpy`` with ``*`` when the document has unsaved changes."""
        title = f"{self.app.doc.title} \u2014 jackpy"
        if title != self._title:
            glfw.set_window_title(self.handle, title)
            self._title = title

    def run(self, autosave: Callable[[], object] | None = None) -> None:
        """Run frames until the window is closed; ``autosave`` is called every ``settings.autosave_s``
        while there are unsaved changes (it writes in the background, :func:`jackpy.ui.session.autosave`),
        and never while a crash's recovery file is still offered (the autosave would overwrite the
        work the offer is about). With nothing unsaved the run's recovery files go; a failed write
        is in the log; the end of the run waits for a pending write and deletes them."""
        from jackpy.ui import session

        last = time.monotonic()
        while not self.should_close:
            if self.idle:
                glfw.wait_events_timeout(IDLE_WAIT_S)  # wakes on input
            self.frame()
            if autosave is not None and time.monotonic() - last >= self.app.settings.autosave_s:
                if self.app.dirty and self.ui.recovery_offer is None:
                    autosave()
                elif not self.app.dirty:
                    session.drop_autosave(self.app)
                last = time.monotonic()
            session.report_autosave(self.app)
        session.finish_autosave(self.app)

    def close(self) -> None:
        """Free the GL and ImGui resources and the window."""
        if self._closed:
            return
        self._closed = True
        glfw.make_context_current(self.handle)
        if self.app.renderer is not None:
            self.app.renderer.release()
            self.app.renderer = None
        imgui.backends.opengl3_shutdown()
        imgui.backends.glfw_shutdown()
        imgui.destroy_context(self.imgui_ctx)
        self.ctx.release()
        glfw.destroy_window(self.handle)
        glfw.terminate()
