"""Figure properties: name, placement, DOFs and mass of the selected (or first) figure; for a
standard human also sex, population and percentile, applied by rescaling it in place
(:meth:`App.rescale_figure`: posture kept, goals re-solved, one undo step)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from imgui_bundle import imgui

from jackpy.ui.panels import Panel
from jackpy.ui.scene_view import SegmentPick

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState


def draw(app: "App", ui: "UiState") -> None:
    imgui.set_next_window_pos((8, 370), imgui.Cond_.first_use_ever)
    imgui.set_next_window_size((270, 300), imgui.Cond_.first_use_ever)
    visible, ui.open_panels["Figure"] = imgui.begin("Figure", ui.open_panels["Figure"])
    if visible:
        sel = app.selection
        fig = app.env.figures.get(sel.figure) if isinstance(sel, SegmentPick) else app.figure_of_interest()
        if fig is None:
            imgui.text_disabled("No figure.")
        else:
            imgui.text(fig.name)
            x, y, z = fig.location[:3, 3] * 100.0
            imgui.text(f"at ({x:.1f}, {y:.1f}, {z:.1f}) cm")
            imgui.text(f"{len(fig.segments)} segments, {fig.ndof} DOFs")
            if fig.total_mass > 0:
                com = fig.centre_of_mass() * 100.0
                imgui.text(f"mass {fig.total_mass:.1f} kg, COM y {com[1]:.1f} cm")
            inside = np.all((fig.q >= fig.lower - 1e-9) & (fig.q <= fig.upper + 1e-9))
            imgui.text("all joints within limits" if inside else "some joints outside limits")
            _body(app, fig, ui.panel_state("Figure"))
    imgui.end()


def _body(app: "App", fig, pending: dict) -> None:
    """The body's rows; ``pending`` (the panel's state) holds per figure the sex / population /
    percentile chosen but not applied yet."""
    from jackpy.body.anthropometry import SEXES, available_populations

    spec = getattr(fig, "body_spec", None)
    if spec is None:
        return
    imgui.separator()
    imgui.text(f"{spec.sex}, P{spec.percentile:g} of {spec.population}")
    imgui.text(f"stature {spec.stature * 100:.1f} cm, mass {spec.mass:.1f} kg")
    pend = pending.setdefault(fig.name, {"sex": spec.sex, "population": spec.population,
                                          "percentile": float(spec.percentile)})
    sexes = list(SEXES)
    pops = available_populations() or [spec.population]
    imgui.set_next_item_width(120)
    pend["sex"] = sexes[imgui.combo("sex", sexes.index(pend["sex"]) if pend["sex"] in sexes else 0, sexes)[1]]
    imgui.set_next_item_width(120)
    i = pops.index(pend["population"]) if pend["population"] in pops else 0
    pend["population"] = pops[imgui.combo("population", i, pops)[1]]
    imgui.set_next_item_width(120)
    pend["percentile"] = float(imgui.slider_float("percentile", pend["percentile"], 1.0, 99.0, "%.0f")[1])
    same = (pend["sex"], pend["population"], pend["percentile"]) == (spec.sex, spec.population, float(spec.percentile))
    imgui.begin_disabled(same)
    if imgui.button("Rescale in place"):
        app.rescale_figure(fig.name, pend["sex"], round(pend["percentile"]), pend["population"])
        pending.pop(fig.name, None)
    imgui.end_disabled()


PANEL = Panel("Figure", draw, order=40)
