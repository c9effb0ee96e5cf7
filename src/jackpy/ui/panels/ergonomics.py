"""Ergonomics panel: the chosen assessments of the figure of interest, live while it is posed.

Per method its score in the action level's colour (green lowest level ... red highest), each body
part's sub-score, the worst contributor (named, and drawn on the figure in its level's colour through
``app.analysis.highlight_colours``) and the method's flags; the task parameters are editable;
during playback (or whenever the document's time moves) the scores are recorded and plotted over
time (implot). The imgui drawing (:func:`draw`) only calls the functions below, which tests drive
headless: :func:`task_of` (the task from the widget state), :func:`evaluate` (the assessments, or
the error a parameter gives), :func:`highlight` (the segment colours) and :func:`record` (the score
history).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.ergonomics import Assessment
    from jackpy.peabody.model import Figure
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Ergonomics"
#: body-part sub-scores shown per method (worksheet keys)
PARTS = {"rula": ("upper_arm", "lower_arm", "wrist", "wrist_twist", "neck", "trunk", "legs"),
         "reba": ("trunk", "neck", "legs", "upper_arm", "lower_arm", "wrist"),
         "owas": ("back", "arms", "legs", "load"),
         "lowback": ("flexion_moment_Nm", "compression_N", "shear_N"),
         "niosh": ("RWL_kg",), "capable": ()}
#: most points kept in the score history
HISTORY = 5000
SIDES = ["worst", "right", "left"]
COUPLINGS = ["good", "fair", "poor", "unacceptable"]


def defaults() -> dict[str, Any]:
    """The panel's widget state on first use."""
    return {"methods": {"rula": True, "reba": True, "lowback": True}, "highlight": True, "load_kg": 0.0, "static": False,
            "repeated": False, "shock": False, "side": "worst", "coupling": "good",
            "lift_d_cm": 40.0, "lift_frequency": 1.0, "lift_duration_h": 1.0,
            "history": [], "results": {}, "error": None}


def chosen(state: dict[str, Any]) -> list[str]:
    """The ticked methods, in the registry's order."""
    from jackpy.ergonomics import methods

    return [n for n in methods() if state["methods"].get(n)]


def task_of(state: dict[str, Any]):
    """The :class:`~jackpy.ergonomics.Task` the widgets describe (one NIOSH lift when NIOSH is on,
    its origin measured from the posture)."""
    from jackpy.ergonomics import Lift, Task

    lifts = []
    if state["methods"].get("niosh"):
        lifts = [Lift(d=state["lift_d_cm"], frequency=state["lift_frequency"], duration_h=state["lift_duration_h"],
                      load_kg=state["load_kg"])]
    return Task(load_kg=state["load_kg"], static=state["static"], repeated=state["repeated"], shock=state["shock"],
                side=state["side"], coupling=state["coupling"], lifts=lifts)


def evaluate(figure: Figure, state: dict[str, Any]) -> dict[str, Assessment]:
    """Run the chosen methods on ``figure``'s posture (one forward pass and one measurement for all);
    a method whose parameters are bad is left out and its message put in ``state["error"]``."""
    from jackpy.ergonomics import measure, method
    from jackpy.errors import JackpyError

    errors, results = [], {}
    try:
        task = task_of(state)
    except JackpyError as exc:
        state["error"] = str(exc)
        return state["results"]
    fk = figure.kinematics().forward(figure.q, figure.location)
    posture = measure(figure, fk)
    for name in chosen(state):
        try:
            results[name] = method(name).assess(figure, task, posture, fk)
        except JackpyError as exc:
            errors.append(f"{name}: {exc}")
    state["error"] = "; ".join(errors) or None
    state["results"] = results
    return results


def record(state: dict[str, Any], t: float, results: dict[str, Assessment]) -> None:
    """Append ``(t, {method: score})`` to the history when the time moved on; a time before the last
    one (playback restarted, the time scrubbed back) starts a new history."""
    hist: list = state["history"]
    if hist and t < hist[-1][0]:
        hist.clear()
    if hist and t == hist[-1][0]:
        return
    hist.append((t, {n: float(a.score) for n, a in results.items()}))
    del hist[:-HISTORY]


def highlight(results: dict[str, Assessment]) -> dict[str, tuple[float, float, float, float]]:
    """Segment -> RGBA for the figure: the worst body part of the method at the highest share of
    its action-level range, in that level's colour (nothing when every method is at its lowest)."""
    from jackpy.ergonomics import methods
    from jackpy.ergonomics.summary import level_colour, worst_segments

    def share(a: Assessment) -> float:
        lo, hi = methods()[a.method].levels
        return 0.0 if a.level is None else (a.level - lo) / max(hi - lo, 1)

    ranked = [a for a in results.values() if share(a) > 0]
    if not ranked:
        return {}
    top = max(ranked, key=share)
    colour = tuple(level_colour(top)) + (1.0,)
    return {seg: colour for seg in worst_segments(top)}


def series(state: dict[str, Any], name: str) -> tuple[list[float], list[float]]:
    """The history of method ``name`` as (times, scores), finite scores only."""
    import math

    ts, vs = [], []
    for t, scores in state["history"]:
        v = scores.get(name)
        if v is not None and math.isfinite(v):
            ts.append(t)
            vs.append(v)
    return ts, vs


def _task_widgets(state: dict[str, Any]) -> None:
    from imgui_bundle import imgui

    imgui.set_next_item_width(110)
    state["load_kg"] = max(0.0, imgui.input_float("load kg", state["load_kg"], 0.5, 5.0, "%.1f")[1])
    state["static"] = imgui.checkbox("static", state["static"])[1]
    imgui.same_line()
    state["repeated"] = imgui.checkbox("repeated", state["repeated"])[1]
    imgui.same_line()
    state["shock"] = imgui.checkbox("shock", state["shock"])[1]
    imgui.set_next_item_width(90)
    state["side"] = SIDES[imgui.combo("arm", SIDES.index(state["side"]), SIDES)[1]]
    imgui.same_line()
    imgui.set_next_item_width(110)
    state["coupling"] = COUPLINGS[imgui.combo("coupling", COUPLINGS.index(state["coupling"]), COUPLINGS)[1]]
    if state["methods"].get("niosh"):
        imgui.set_next_item_width(90)
        state["lift_d_cm"] = max(0.0, imgui.input_float("lift travel cm", state["lift_d_cm"], 5.0, 25.0, "%.0f")[1])
        imgui.set_next_item_width(90)
        state["lift_frequency"] = imgui.input_float("lifts/min", state["lift_frequency"], 0.5, 2.0, "%.1f")[1]
        imgui.set_next_item_width(90)
        state["lift_duration_h"] = imgui.input_float("hours", state["lift_duration_h"], 1.0, 2.0, "%.1f")[1]


def _result_lines(a: Assessment) -> None:
    from imgui_bundle import imgui

    from jackpy.ergonomics.summary import headline, level_colour, value_text

    imgui.text_colored(tuple(level_colour(a)) + (1.0,), headline(a))
    parts = [f"{k} {value_text(a.worksheet[k])}" for k in PARTS.get(a.method, ()) if k in a.worksheet]
    if parts:
        imgui.text_wrapped("  " + ", ".join(parts))
    if a.worst:
        imgui.text_disabled(f"  worst: {a.worst}")
    for f in a.flags:
        imgui.text_colored((1.0, 0.6, 0.2, 1.0), f"  ! {f}")


def _plot(state: dict[str, Any]) -> None:
    from imgui_bundle import imgui, implot

    if len(state["history"]) < 2:
        imgui.text_disabled("play the timeline to plot the scores over time")
        return
    import numpy as np

    if implot.begin_plot("scores over time", (-1, 180)):
        implot.setup_axes("time s", "score")
        for name in state["results"]:
            ts, vs = series(state, name)
            if ts:
                implot.plot_line(name, np.array(ts), np.array(vs))
        implot.end_plot()


def draw(app: App, ui: UiState) -> None:
    from imgui_bundle import imgui

    from jackpy.ergonomics import methods
    from jackpy.ergonomics.inputs import is_human

    state = ui.panel_state(TITLE, defaults())
    if not ui.open_panels.get(TITLE):  # drawn every frame (always=True) only to clear the highlight
        if app.analysis.highlight_colours:
            app.analysis.highlight_colours = {}
        return
    vp = imgui.get_main_viewport()
    imgui.set_next_window_pos((vp.size.x - 920, 30), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((310, 560), imgui.Cond_.first_use_ever)
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels[TITLE])
    if visible:
        fig = app.figure_of_interest()
        if fig is None or not is_human(fig):
            imgui.text_disabled("No standard human in the scene.")
        else:
            imgui.text(f"figure: {fig.name}")
            for k, name in enumerate(methods()):
                if k:
                    imgui.same_line()
                state["methods"][name] = imgui.checkbox(name, bool(state["methods"].get(name)))[1]
            _task_widgets(state)
            imgui.separator()
            results = evaluate(fig, state)
            if state["error"]:
                imgui.text_colored((1.0, 0.4, 0.3, 1.0), state["error"])
            state["highlight"] = imgui.checkbox("highlight the worst part", state["highlight"])[1]
            for a in results.values():
                _result_lines(a)
            app.analysis.highlight_colours = highlight(results) if state["highlight"] else {}
            record(state, float(app.doc.time), results)
            imgui.separator()
            _plot(state)
    imgui.end()


PANEL = Panel(TITLE, draw, order=62, always=True)
