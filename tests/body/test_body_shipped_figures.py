"""The ready-made humans in figures/human are what the current generator makes (`jackpy human`):
read back, each equals make_human at its sex and percentile (segments, masses, sites, joints,
limits, groups with their drivers and limits, the human marker), carries the shoulder's non-convex
limit, and runs the behaviors. A change to the generator fails here until the files are regenerated
(`jackpy human --sex S --percentile P -o figures/human/S_pP.fig`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from jackpy.behaviors import BehaviorLoop
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.body.human import make_human, peabody_copy
from jackpy.body.saved import is_standard_human, restore_human
from jackpy.peabody.compare import figure_differences
from jackpy.peabody.reader import read_figures

HUMANS = Path(__file__).resolve().parents[2] / "figures" / "human"
CASES = [(sex, p) for sex in ("female", "male") for p in (5, 50, 95)]


def test_all_six_ship():
    assert {f"{s}_p{p}" for s, p in CASES} <= {path.stem for path in HUMANS.glob("*.fig")}


@pytest.mark.parametrize("sex,p", CASES)
def test_shipped_human_equals_the_generator(sex: str, p: int) -> None:
    path = HUMANS / f"{sex}_p{p}.fig"
    back = read_figures(path)[0]
    assert restore_human(back) and is_standard_human(back)
    fig = make_human(sex, p)
    assert figure_differences(peabody_copy(fig, f"{path.stem}_psurf"), back, tol=1e-7) == []
    assert all(s.psurf.mesh is not None for s in back.segments.values() if s.psurf)
    for side in ("left", "right"):
        g = back.groups[f"{side}_shoulder_complex"]
        assert len(g.pieces) == 2
        assert g.is_feasible(np.radians([60.0, -90.0, 0.0])) and not g.is_feasible(np.radians([120.0, -45.0, 0.0]))
    lp = BehaviorLoop(back, human_anatomy(back))
    lp.step()
