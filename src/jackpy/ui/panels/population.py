"""Population panel: show a manikin family in the scene side by side, and run a small sweep of the
scene with a progress bar (docs/population.md).

*Show family*: the boundary and centre cases of the chosen share of stature x weight for the chosen
sexes, full figures placed in a row along +x behind the scene's origin (one undo step; *Remove
family* takes them out again). *Run sweep*: a study file and N Monte Carlo bodies on a local pool in
a background thread; the panel shows the rows done, the rate and, when done, the accommodation
table; the output folder keeps everything as ``jackpy sweep`` writes it. The imgui drawing only
calls :func:`family_figures`, :func:`add_family`, :func:`remove_family`, :func:`start_sweep` and
:func:`sweep_status`, which tests drive headless.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.peabody.model import Environment, Figure
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Population"
PREFIX = "family_"
#: spacing of the family's figures along +x (m) and their distance behind the origin (-z)
SPACING, BEHIND = 0.75, 1.5


def defaults() -> dict[str, Any]:
    return {"share": 90.0, "female": True, "male": True, "study": "", "n": 100, "workers": 2,
            "out": "population_sweep", "job": None, "error": None}


def family_figures(share: float, sexes: list[str]) -> list[Figure]:
    """The family's full figures (``family_<sex>_<k>``), standing in a row along +x."""
    from jackpy.peabody.transforms import translation
    from jackpy.population.families import family
    from jackpy.population.generate import make_figure
    from jackpy.population.model import PopulationModel

    bodies = family(PopulationModel.ansur2(), share, ("stature", "weight"), sexes)
    figures = []
    for k, b in enumerate(bodies):
        fig = make_figure(b, surfaces=True, name=f"{PREFIX}{b.sex}_{b.label.replace(' ', '_')}")
        x = (k - (len(bodies) - 1) / 2) * SPACING
        fig.location = translation(x, 0.0, -BEHIND) @ fig.location
        figures.append(fig)
    return figures


def add_family(env: Environment, figures: list[Figure]) -> None:
    """Replace any shown family in ``env`` by ``figures``."""
    remove_family(env)
    for f in figures:
        env.add(f)


def remove_family(env: Environment) -> None:
    for name in [n for n in env.figures if n.startswith(PREFIX)]:
        del env.figures[name]


def start_sweep(env: Environment, study_path: str, n: int, out: str, workers: int = 2) -> dict[str, Any]:
    """Start a sweep of the scene's CAD objects (figures standing at the origin facing +z) in a
    background thread; returns the job (poll it with :func:`sweep_status`)."""
    from jackpy.population.evaluate import SweepContext
    from jackpy.population.study import check_against_scene, load_study
    from jackpy.scene.cad import CADObject
    from jackpy.scene.workplace import Workplace

    study = load_study(study_path)
    wp = Workplace()
    for name, f in env.figures.items():
        if isinstance(f, CADObject):
            wp.env.add(f)
    check_against_scene(study, wp.env)
    job: dict[str, Any] = {"done": 0, "total": n, "started": time.perf_counter(), "table": None, "error": None,
                           "finished": False}

    def work() -> None:
        from jackpy.population.report import write_report
        from jackpy.population.run import population_bodies
        from jackpy.population.sweep import run_sweep

        try:
            bodies = population_bodies(n)
            ctx = SweepContext(wp, study).prepare()
            job["started"] = time.perf_counter()
            result = run_sweep(ctx, bodies, out, workers=workers, progress=False,
                               on_rows=lambda rows: job.__setitem__("done", job["done"] + len(rows)))
            job["table"] = write_report(out, study, result.rows, "Population sweep (workbench)", result.complete)
        except Exception as exc:  # shown in the panel; the thread must not die silently
            job["error"] = f"{type(exc).__name__}: {exc}"
        job["finished"] = True

    job["thread"] = threading.Thread(target=work, name="population-sweep", daemon=True)
    job["thread"].start()
    return job


def sweep_status(job: dict[str, Any]) -> str:
    """One line: rows done, rate and ETA, or the outcome."""
    if job["error"]:
        return f"error: {job['error']}"
    if job["finished"]:
        return f"done: {job['done']} bodies"
    elapsed = time.perf_counter() - job["started"]
    rate = job["done"] / elapsed if elapsed > 0 and job["done"] else 0.0
    eta = f"{(job['total'] - job['done']) / rate:.0f} s" if rate else "-"
    return f"{job['done']}/{job['total']} bodies, {rate:.1f}/s, ETA {eta}"


def draw(app: App, ui: UiState) -> None:
    from imgui_bundle import imgui

    st = ui.panel_state(TITLE, defaults())
    imgui.set_next_window_size((330, 330), imgui.Cond_.first_use_ever)
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels[TITLE])
    if visible:
        imgui.set_next_item_width(120)
        st["share"] = float(np.clip(imgui.input_float("share %", st["share"], 1.0, 5.0, "%.0f")[1], 50.0, 99.0))
        st["female"] = imgui.checkbox("women", st["female"])[1]
        imgui.same_line()
        st["male"] = imgui.checkbox("men", st["male"])[1]
        sexes = [s for s in ("female", "male") if st[s]]
        if imgui.button("Show family") and sexes:
            figures = family_figures(st["share"] / 100.0, sexes)
            app.doc.command(f"show {st['share']:.0f} % family", lambda: add_family(app.env, figures), structural=True)
        imgui.same_line()
        if imgui.button("Remove family"):
            app.doc.command("remove family", lambda: remove_family(app.env), structural=True)
        imgui.separator()
        st["study"] = imgui.input_text("study", st["study"])[1]
        imgui.set_next_item_width(120)
        st["n"] = max(1, imgui.input_int("bodies", st["n"])[1])
        imgui.set_next_item_width(120)
        st["workers"] = max(1, imgui.input_int("workers", st["workers"])[1])
        st["out"] = imgui.input_text("output", st["out"])[1]
        job = st["job"]
        running = job is not None and not job["finished"]
        if imgui.button("Run sweep") and not running:
            try:
                st["job"] = start_sweep(app.env, st["study"], st["n"], str(Path(st["out"])), st["workers"])
                st["error"] = None
            except Exception as exc:  # a bad study path or target: shown, nothing started
                st["error"] = str(exc)
        if st["error"]:
            imgui.text_colored((1.0, 0.4, 0.4, 1.0), st["error"])
        if job is not None:
            imgui.progress_bar(job["done"] / max(job["total"], 1), (-1, 0), sweep_status(job))
            for a in job["table"] or []:
                imgui.text(f"{a.criterion}: {100 * a.share:.1f} %")
    imgui.end()


PANEL = Panel(TITLE, draw, order=80)
