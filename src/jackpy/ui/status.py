"""What the workbench tells the user without a panel open: toasts and the status bar.

Toasts: every log line that starts with ``error`` or ``warning`` (the convention of
:meth:`Document.info`) also appears as a wrapped notification in the top-right corner of the 3-D
view for ``TOAST_S`` seconds (errors stay until closed or ``ERROR_TOAST_S``), at most
``MAX_TOASTS`` at once; the Log panel keeps them all.

Status bar (bottom of the window): frames per second (mean over the last second), the last solve's
time and iterations, the frame budget (:mod:`jackpy.ui.frame_budget`: quality rung, the solve's
time box, solves over their box; its menu switches the adaptation and picks the target frame
rate), and the selected goal's residual, e.g. ``right hand: 31 cm short``, in red when the goal is
not met (beyond ``MET_M`` or ``MET_RAD``).
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from imgui_bundle import imgui

from jackpy.ui.layout import Rect

if TYPE_CHECKING:
    from jackpy.ui.app import App

TOAST_S, ERROR_TOAST_S, MAX_TOASTS = 6.0, 15.0, 4
TOAST_WIDTH = 360.0
"""Toast width in pixels (text wraps inside)."""
STATUS_BAR_HEIGHT = 24.0
MET_M, MET_RAD = 0.01, np.radians(2.0)
"""A goal counts as met within 1 cm and 2°."""
RED, YELLOW, GREY = (1.0, 0.35, 0.3, 1.0), (1.0, 0.8, 0.3, 1.0), (0.75, 0.75, 0.75, 1.0)


@dataclass
class Toast:
    text: str
    level: str  # "error" or "warning"
    until: float  # time.monotonic() when it goes


def level_of(line: str) -> str | None:
    """``"error"`` / ``"warning"`` for a log line that deserves a toast, else None."""
    head = line.lstrip().lower()
    for level in ("error", "warning"):
        if head.startswith(level):
            return level
    return None


@dataclass
class Notifications:
    """The toasts on screen; :meth:`push` is the app's ``on_log`` hook."""

    toasts: list[Toast] = field(default_factory=list)

    def push(self, line: str) -> None:
        level = level_of(line)
        if level is None:
            return
        life = ERROR_TOAST_S if level == "error" else TOAST_S
        self.toasts.append(Toast(line, level, time.monotonic() + life))
        del self.toasts[:-MAX_TOASTS]

    def draw(self, view: Rect) -> None:
        """Draw the live toasts in the top-right corner of ``view`` (the 3-D view's rect)."""
        now = time.monotonic()
        self.toasts = [t for t in self.toasts if t.until > now]
        y = view.y + 8.0
        flags = (imgui.WindowFlags_.no_decoration | imgui.WindowFlags_.always_auto_resize
                 | imgui.WindowFlags_.no_saved_settings | imgui.WindowFlags_.no_focus_on_appearing
                 | imgui.WindowFlags_.no_nav | imgui.WindowFlags_.no_docking)
        for k, toast in enumerate(list(self.toasts)):
            imgui.set_next_window_pos((view.x + view.w - 8.0, y), imgui.Cond_.always, (1.0, 0.0))
            imgui.set_next_window_size_constraints((TOAST_WIDTH, 0.0), (TOAST_WIDTH, 400.0))
            imgui.set_next_window_bg_alpha(0.92)
            imgui.begin(f"##toast{k}", None, flags)
            imgui.push_text_wrap_pos(TOAST_WIDTH - 30.0)
            imgui.text_colored(RED if toast.level == "error" else YELLOW, toast.text)
            imgui.pop_text_wrap_pos()
            if imgui.small_button(f"close##toast{k}"):
                self.toasts.remove(toast)
            y += imgui.get_window_height() + 6.0
            imgui.end()


class FrameRate:
    """Frames per second over the last second of frame times."""

    def __init__(self) -> None:
        self._times: deque[float] = deque(maxlen=240)

    def tick(self, t: float | None = None) -> None:
        self._times.append(time.monotonic() if t is None else t)

    @property
    def fps(self) -> float:
        if len(self._times) < 2:
            return 0.0
        last = self._times[-1]
        recent = [t for t in self._times if last - t <= 1.0]
        span = recent[-1] - recent[0]
        return (len(recent) - 1) / span if span > 0 else 0.0



def goal_label(app: "App", key: str) -> str:
    """A goal's name for people: its role (``right hand``) or its site."""
    goal = app.goal(key)
    if goal is None:
        return key
    role = app.role_of(goal) or goal.role
    if role:
        return role.replace("_", " ")
    return goal.site.replace("_", " ").replace(".", " ")


def goal_residual(app: "App", key: str) -> tuple[float, float] | None:
    """(distance m, angle rad) between a goal's target and its site's actual frame, or None."""
    goal = app.goal(key)
    if goal is None:
        return None
    fig = app.env.figures.get(goal.figure)
    if fig is None:
        return None
    try:
        actual = fig.site_world(*goal.site.split(".", 1))
    except (KeyError, ValueError):
        return None
    target = goal.target
    distance = float(np.linalg.norm(target[:3, 3] - actual[:3, 3]))
    angle = 0.0
    if "orient" in goal.kind or goal.kind in ("frame", "pose"):
        c = (np.trace(target[:3, :3].T @ actual[:3, :3]) - 1.0) / 2.0
        angle = float(np.arccos(np.clip(c, -1.0, 1.0)))
    return distance, angle


def residual_text(app: "App", key: str) -> tuple[str, bool] | None:
    """(``"right hand: 31 cm short"`` or ``"right hand: met"``, met) for a goal, or None."""
    r = goal_residual(app, key)
    if r is None:
        return None
    distance, angle = r
    name = goal_label(app, key)
    if distance <= MET_M and angle <= MET_RAD:
        return f"{name}: met", True
    parts = []
    if distance > MET_M:
        parts.append(f"{distance * 100:.0f} cm short")
    if angle > MET_RAD:
        parts.append(f"{np.degrees(angle):.0f}\u00b0 off")
    return f"{name}: {', '.join(parts)}", False


TARGET_RATES = (20.0, 30.0, 60.0)
"""Target frame rates the frame budget's menu offers."""


def _budget_menu(app: "App") -> None:
    """The frame budget's line, a menu: adaptive quality on/off and the target frame rate."""
    fb = app.frame_budget
    if imgui.begin_menu(f"{fb.describe()}###frame_budget"):
        changed, on = imgui.menu_item("Adaptive quality", "", fb.adaptive)
        if changed:
            fb.adaptive = on
        for fps in TARGET_RATES:
            if imgui.menu_item(f"Target {fps:.0f} frames/s", "", fb.fps == fps)[0]:
                fb.fps = fps
        imgui.end_menu()


def draw_status_bar(app: "App", rate: FrameRate) -> None:
    """The status bar along the bottom of the main viewport (call before the dockspace)."""
    from jackpy.ui.scene_view import GoalPick

    flags = (imgui.WindowFlags_.no_scrollbar | imgui.WindowFlags_.no_saved_settings
             | imgui.WindowFlags_.menu_bar)
    if imgui.internal.begin_viewport_side_bar("##status", imgui.get_main_viewport(), imgui.Dir.down,
                                              STATUS_BAR_HEIGHT, flags):
        if imgui.begin_menu_bar():
            s = app.stats
            imgui.text_colored(GREY, f"{rate.fps:5.1f} frames/s   solve {s.solve_s * 1e3:5.1f} ms, "
                                     f"{s.iterations} it   draw {s.draw_s * 1e3:4.1f} ms")
            imgui.separator()
            _budget_menu(app)
            key = None
            if isinstance(app.selection, GoalPick):
                key = app.selection.key
            elif app.manipulator.active:
                target = app.manipulator.target
                key = getattr(getattr(target, "goal", None), "key", None)
            text = residual_text(app, key) if key is not None else None
            if text is not None:
                imgui.separator()
                imgui.text_colored(GREY if text[1] else RED, text[0])
            imgui.end_menu_bar()
    imgui.end()
