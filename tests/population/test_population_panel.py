"""The Population panel's actions, headless: a family shown side by side (and removed), a small
sweep run in the background with its progress."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from jackpy.population.model import PopulationModel
from jackpy.scene.workplace import load_workplace
from jackpy.ui.panels import panels
from jackpy.ui.panels.population import TITLE, add_family, family_figures, remove_family, start_sweep, sweep_status

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace"


def test_panel_is_discovered() -> None:
    assert TITLE in [p.title for p in panels()]


@pytest.mark.timeout(900)
def test_family_side_by_side_and_removed() -> None:
    wp = load_workplace(EXAMPLE / "workplace.json")
    before = set(wp.env.figures)
    figures = family_figures(0.9, ["female"])
    assert len(figures) == 9 and figures[-1].name == "family_female_centre"
    xs = [f.location[0, 3] for f in figures]
    assert np.all(np.diff(xs) > 0.5)  # a row, no overlaps
    sm = PopulationModel.ansur2().sex("female")
    tallest = max(f.body_spec.stature for f in figures)
    assert tallest > sm.mean[0] + 1.5 * sm.sd[0]  # boundary cases, not all average
    add_family(wp.env, figures)
    assert set(wp.env.figures) == before | {f.name for f in figures}
    remove_family(wp.env)
    assert set(wp.env.figures) == before


@pytest.mark.timeout(900)
def test_small_sweep_in_the_background(tmp_path: Path) -> None:
    wp = load_workplace(EXAMPLE / "workplace.json")
    job = start_sweep(wp.env, str(EXAMPLE / "study.json"), 6, str(tmp_path / "out"), workers=1)
    assert "/6 bodies" in sweep_status(job) or job["finished"]
    job["thread"].join(timeout=600)
    assert job["error"] is None and sweep_status(job) == "done: 6 bodies"
    assert [a.criterion for a in job["table"]][-1] == "all"
    assert (tmp_path / "out" / "bodies.csv").exists() and (tmp_path / "out" / "report.html").exists()
