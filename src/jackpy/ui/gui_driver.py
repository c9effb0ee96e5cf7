"""Drive the workbench window with Dear ImGui's test engine (``imgui.test_engine``, shipped in
imgui-bundle): tests that click widgets by their labels, type and press keys as a user does.

The test engine runs each test function on its own thread (a coroutine), resumed from inside
ImGui's ``NewFrame`` and ``EndFrame``. In Python both threads need the GIL: Hello ImGui's runner
releases it around those two calls in C++, but our window runs its own glfw loop and calls them
from Python through imgui-bundle's bindings, which keep the GIL, so the test thread would wait
for the GIL forever. :class:`GuiDriver` therefore calls ``ImGui::NewFrame`` and
``ImGui::EndFrame`` of imgui-bundle's own library through :mod:`ctypes`, which releases the GIL for
the call (the same library, so the same ImGui context). The window keeps its loop, its glfw
callbacks and its 3-D view; only those two calls change (:attr:`Window.new_frame`,
:attr:`Window.end_frame`). The symbols are looked up by their Itanium C++ names (Linux, macOS).

Inputs the engine simulates reach ImGui only, not the window's glfw callbacks: a test clicks
menus, buttons and fields; keyboard shortcuts and 3-D view drags are tested through the window's
callbacks (tests/ui/test_window_*.py) and xdotool (tests/ui/test_xdotool_flows.py).
"""

from __future__ import annotations

import ctypes
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from imgui_bundle import imgui

if TYPE_CHECKING:
    from jackpy.ui.window import Window

te = imgui.test_engine
TestFunc = Callable[["imgui.test_engine.TestContext"], None]


@dataclass
class TestOutcome:
    """How a test ended: its engine status, the frames it took, and any Python error's traceback."""

    name: str
    status: "imgui.test_engine.TestStatus"
    frames: int
    errors: list[str] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return self.status == te.TestStatus.success and not self.errors

    def __str__(self) -> str:
        return f"{self.name}: {self.status.name} after {self.frames} frames" + "".join(
            "\n" + e for e in self.errors)


def _imgui_library() -> ctypes.CDLL:
    from imgui_bundle import _imgui_bundle  # type: ignore[attr-defined]

    return ctypes.CDLL(_imgui_bundle.__file__)


class GuiDriver:
    """The test engine bound to ``window``'s ImGui context; :meth:`run` runs one test to its end."""

    def __init__(self, window: "Window", fast: bool = True) -> None:
        lib = _imgui_library()
        self._new_frame, self._end_frame = lib._ZN5ImGui8NewFrameEv, lib._ZN5ImGui8EndFrameEv
        self._new_frame.restype = self._end_frame.restype = None
        self.window = window
        self.engine = te.create_context()
        io = te.get_io(self.engine)
        io.config_run_speed = te.TestRunSpeed.fast if fast else te.TestRunSpeed.normal
        io.config_no_throttle = True
        te.start(self.engine, window.imgui_ctx)
        self._saved = (window.new_frame, window.end_frame)
        window.new_frame, window.end_frame = self._new_frame, self._end_frame
        self._post_swap = lambda: te.post_swap(self.engine)
        window.after_swap.append(self._post_swap)
        self._stopped = False
        self.closed = False
        """Whether the window, asked before the last frame as :meth:`Window.run` does, would close."""

    def run(self, name: str, func: TestFunc, max_frames: int = 4000) -> TestOutcome:
        """Register ``func`` as test ``name``, run it while drawing the window's frames, and return
        its outcome (an exception in ``func`` is recorded with its traceback)."""
        errors: list[str] = []

        def guarded(ctx: "imgui.test_engine.TestContext") -> None:
            try:
                func(ctx)
            except BaseException:
                errors.append(traceback.format_exc())
                raise

        test = te.register_test(self.engine, "jackpy", name)
        test.test_func = guarded
        te.queue_test(self.engine, test)
        frames = 0
        while frames < max_frames:
            self.closed = self.window.should_close  # as Window.run asks before each frame
            self.window.frame()
            frames += 1
            if te.is_test_queue_empty(self.engine) and test.output.status not in (
                    te.TestStatus.queued, te.TestStatus.running):
                break
        else:
            errors.append(f"did not finish within {max_frames} frames")
            te.abort_current_test(self.engine)
            for _ in range(10):
                self.window.frame()
        if test.output.status != te.TestStatus.success:  # the engine's own account (item not found ...)
            log = test.output.log.get_text()
            errors.append("\n".join(line for line in log.splitlines() if line.strip())[-3000:])
        return TestOutcome(name, test.output.status, frames, errors)

    def stop(self) -> None:
        """Stop the engine's thread and give the window back its own frame calls (before
        :meth:`Window.close`)."""
        if self._stopped:
            return
        self._stopped = True
        te.stop(self.engine)
        self.window.new_frame, self.window.end_frame = self._saved
        if self._post_swap in self.window.after_swap:
            self.window.after_swap.remove(self._post_swap)

    def destroy(self) -> None:
        """Free the engine (after :meth:`Window.close`, as the engine asks)."""
        self.stop()
        te.destroy_context(self.engine)


__all__ = ["GuiDriver", "TestOutcome"]
