"""Goals list: every goal with enable, weight, priority and chain; add one on a site, remove one.

On a behavior-driven human the goals on sites other than the dragged effectors are the behavior
loop's user goals (:meth:`App.sync_user_goals`): solved with balance, below the planted feet; the
row says which pass solves each."""

from __future__ import annotations

from typing import TYPE_CHECKING

from imgui_bundle import imgui

from jackpy.document.goals import placeable_kinds
from jackpy.ui.panels import Panel
from jackpy.ui.scene_view import GoalPick, SegmentPick, is_object

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

ADD_DEFAULTS = {"site": 0, "kind": 0}
"""The add row's chosen site and kind indices (the panel's state in the UI state)."""


def kinds() -> list[str]:
    """The kinds the add row offers: every registered goal kind a site can take
    (:func:`jackpy.document.goals.placeable_kinds`: built-in ones and any module's own)."""
    return placeable_kinds()


def draw(app: "App", ui: "UiState") -> None:
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((vp.size.x - 290, 400), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((280, 300), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Goals"] = imgui.begin("Goals", ui.open_panels["Goals"])
    if visible:
        _add_row(app, ui.panel_state("Goals", ADD_DEFAULTS))
        imgui.separator()
        for g in list(app.goals):
            imgui.push_id(g.key)
            chosen = isinstance(app.selection, GoalPick) and app.selection.key == g.key
            if imgui.selectable(f"{g.site} ({g.kind})", chosen)[0]:
                app.select(GoalPick(g.key))
            if g.figure in app.behavior_figures() and app.is_user_goal(g):
                part = app.user_goal_part(g.key)
                imgui.text_disabled(f"with behaviors: {'body pass' if part == 'body' else f'{part} (limbs pass)'}"
                                    if part else "with behaviors: next frame")
            changed, enabled = imgui.checkbox("enabled", g.enabled)
            if changed:
                app.command(f"{'enable' if enabled else 'disable'} {g.key}", lambda g=g, e=enabled: _set(g, "enabled", e))
            imgui.same_line()
            if imgui.small_button("remove"):
                app.remove_goal(g.key)
            imgui.set_next_item_width(90)
            changed, w = imgui.drag_float("weight", g.weight, 0.01, 0.0, 100.0, "%.2f")
            if imgui.is_item_activated():
                app.begin_edit()
            if changed:
                g.weight = w
                app.goals_changed()
            if imgui.is_item_deactivated_after_edit():
                app.end_edit(f"weight of {g.key}")
            imgui.same_line()
            imgui.set_next_item_width(70)
            changed, p = imgui.input_int("priority", g.priority)
            if changed:
                app.command(f"priority of {g.key}", lambda g=g, p=p: _set(g, "priority", p))
            changed, chain = imgui.input_text("chain (joint)", g.chain or "",
                                              imgui.InputTextFlags_.enter_returns_true)
            if changed:
                app.command(f"chain of {g.key}", lambda g=g, c=chain.strip() or None: _set(g, "chain", c))
            imgui.separator()
            imgui.pop_id()
    imgui.end()


def _set(goal: object, name: str, value: object) -> None:
    setattr(goal, name, value)


def _add_row(app: "App", state: dict) -> None:
    sel = app.selection
    fig = app.env.figures.get(sel.figure) if isinstance(sel, SegmentPick) else None
    if fig is None or is_object(fig):
        imgui.text_disabled("Select a segment to add a goal on its site.")
        return
    sites = [f"{sel.segment}.{s}" for s in fig.segments[sel.segment].sites]
    names = kinds()
    state["site"] = min(state["site"], len(sites) - 1)
    state["kind"] = min(state["kind"], len(names) - 1)
    imgui.set_next_item_width(150)
    state["site"] = imgui.combo("site", state["site"], sites)[1]
    imgui.set_next_item_width(150)
    state["kind"] = imgui.combo("kind", state["kind"], names)[1]
    if imgui.button("Add goal") and sites:
        site, kind = sites[state["site"]], names[state["kind"]]
        app.command(f"add {kind} goal {fig.name}:{site}", lambda: app.add_goal(fig, site, kind))


PANEL = Panel("Goals", draw, open=True, order=30)
