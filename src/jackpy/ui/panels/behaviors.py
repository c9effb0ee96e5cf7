"""Behaviors panel: the switch between behaviors and plain IK, the drag settings, and per human
each behavior with its enable checkbox and its parameters drawn from their descriptions
(:func:`jackpy.behaviors.describe`: description, unit and range).

The value conversions are plain functions (:func:`to_display`, :func:`set_param`) so they are
tested without a window.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from imgui_bundle import imgui

from jackpy.behaviors import describe
from jackpy.behaviors.base import ParamSpec, validate
from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

DISPLAY_SCALE = {"deg": float(np.degrees(1.0)), "cm": 100.0, "mm": 1000.0}
"""Internal (m, rad) → shown units for a parameter's ``unit``; anything else is shown as is."""

HEAD_DRAG = ["head", "eyes"]


def to_display(spec: ParamSpec, value: Any) -> Any:
    """A parameter value in the units the panel shows."""
    k = DISPLAY_SCALE.get(spec.unit)
    return value * k if k is not None and isinstance(value, (int, float)) and not isinstance(value, bool) else value


def from_display(spec: ParamSpec, value: Any) -> Any:
    """A shown value back in internal units."""
    k = DISPLAY_SCALE.get(spec.unit)
    return value / k if k is not None and isinstance(value, (int, float)) and not isinstance(value, bool) else value


def set_param(app: "App", behavior: Any, name: str, value: Any) -> bool:
    """Set one parameter (internal units), keep it only if it validates; re-solve. True when set."""
    params = behavior.params
    old = getattr(params, name)
    setattr(params, name, type(old)(value) if isinstance(old, (bool, int, float)) and not isinstance(old, np.ndarray) else value)
    try:
        validate(params)
    except (ValueError, TypeError) as exc:
        setattr(params, name, old)
        app.info(f"error: {behavior.name}.{name}: {exc}")
        return False
    app.goals_changed()
    return True


def set_enabled(app: "App", behavior: Any, on: bool) -> None:
    """Switch a behavior on or off (one undo step); re-solve."""
    def act() -> None:
        behavior.enabled = bool(on)
        app.goals_changed()

    app.command(f"behavior {behavior.name} {'on' if on else 'off'}", act)


def change_param(app: "App", behavior: Any, name: str, value: Any) -> bool:
    """Set one parameter as one undo step (a checkbox, a choice); nothing is recorded when the value
    is refused. True when set."""
    before = app.capture()
    if not set_param(app, behavior, name, value):
        return False
    app.undo_stack.push(f"{behavior.name}.{name}", before)
    app.info(f"{behavior.name}.{name} = {getattr(behavior.params, name)}")
    return True


def begin_param_drag(app: "App") -> None:
    """A slider drag on a parameter starts (the state before it is the undo step's)."""
    app.begin_edit()


def end_param_drag(app: "App", behavior: Any, name: str) -> None:
    """The slider drag ended: one undo step for the whole drag."""
    app.end_edit(f"{behavior.name}.{name}")


def draw(app: "App", ui: "UiState") -> None:
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((vp.size.x - 620, 30), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((320, 480), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Behaviors"] = imgui.begin("Behaviors", ui.open_panels["Behaviors"])
    if visible:
        _settings(app)
        if not app.loops:
            imgui.text_disabled("No standard human in the scene: plain IK only.")
        for name, loop in app.loops.items():
            imgui.separator()
            imgui.text(name)
            rep = app.last_report
            if rep is not None:
                imgui.text_disabled(f"root {rep.root}, balance x {rep.balance[0]:.2f} z {rep.balance[1]:.2f}, "
                                    f"COM off {rep.com_error * 1000:.1f} mm")
            for b in loop.behaviors:
                imgui.push_id(f"{name}/{b.name}")
                changed, on = imgui.checkbox("##on", b.enabled)
                if changed:
                    set_enabled(app, b, on)
                imgui.same_line()
                if imgui.tree_node(b.name):
                    for spec in describe(b.params):
                        _param_row(app, b, spec)
                    imgui.tree_pop()
                imgui.pop_id()
    imgui.end()


def _settings(app: "App") -> None:
    s = app.settings
    changed, on = imgui.checkbox("Behaviors (off: plain IK)", s.behaviors)
    if changed:
        app.set_behaviors_enabled(on)
    if imgui.is_item_hovered():
        imgui.set_tooltip("Drags of hands, feet, pelvis and head keep balance, planted feet and step, as in Jack.")
    changed, v = imgui.checkbox("Hands lean when out of reach", s.hand_lean)
    if changed:
        s.hand_lean = v
        _resync(app)
    changed, v = imgui.checkbox("Planted feet hold orientation", s.feet_hold)
    if changed:
        s.feet_hold = v
        _resync(app)
    imgui.set_next_item_width(90)
    changed, k = imgui.combo("head drag moves", HEAD_DRAG.index(s.head_drag) if s.head_drag in HEAD_DRAG else 0,
                             HEAD_DRAG)
    if changed:
        s.head_drag = HEAD_DRAG[k]
    imgui.set_next_item_width(90)
    changed, ms = imgui.slider_float("max time box (ms)", s.ik_time_budget_s * 1e3, 5.0, 200.0, "%.0f")
    if changed:
        s.ik_time_budget_s = ms / 1e3


def _resync(app: "App") -> None:
    for name in app.loops:
        app.sync_behaviors(name)
    app.goals_changed()


def _param_row(app: "App", b: Any, spec: ParamSpec) -> None:
    label = spec.name + (f" ({spec.unit})" if spec.unit else "")
    v = spec.value
    imgui.set_next_item_width(110)
    instant = True  # checkboxes and choices are one step each; sliders one step per drag
    if isinstance(v, bool):
        changed, new = imgui.checkbox(label, v)
    elif spec.choices:
        i = spec.choices.index(v) if v in spec.choices else 0
        changed, i = imgui.combo(label, i, list(spec.choices))
        new = spec.choices[i]
    elif isinstance(v, int):
        lo, hi = (int(spec.range[0]), int(spec.range[1])) if spec.range else (0, 100)
        changed, new = imgui.slider_int(label, v, lo, hi)
        instant = False
    elif isinstance(v, float):
        shown = to_display(spec, v)
        if spec.range is not None and np.isfinite(spec.range[1]) and spec.range[1] < 1e3:
            lo, hi = to_display(spec, spec.range[0]), to_display(spec, spec.range[1])
            changed, shown = imgui.slider_float(label, shown, lo, hi, "%.3g")
        else:
            changed, shown = imgui.drag_float(label, shown, 0.01 * max(abs(shown), 0.1), 0.0, 0.0, "%.3g")
        new = from_display(spec, shown)
        instant = False
    else:
        imgui.text(f"{label}: {v}")
        changed, new = False, v
    if imgui.is_item_hovered() and spec.doc:
        rng = ""
        if spec.range is not None:
            rng = f"  [{to_display(spec, spec.range[0]):.3g} .. {to_display(spec, spec.range[1]):.3g}]"
        imgui.set_tooltip(spec.doc + rng)
    if instant:
        if changed:
            change_param(app, b, spec.name, new)
        return
    if imgui.is_item_activated():
        begin_param_drag(app)
    if changed:
        set_param(app, b, spec.name, new)
    if imgui.is_item_deactivated_after_edit():
        end_param_drag(app, b, spec.name)


PANEL = Panel("Behaviors", draw, order=50)
