"""Per-body evaluation with the criteria that need the full figure: clearance, strength and an
ergonomics score, each in a reach target's posture."""

from __future__ import annotations

from pathlib import Path

import pytest

from jackpy.population.evaluate import SweepContext, columns, evaluate_body
from jackpy.population.generate import make_body
from jackpy.population.study import check_against_scene, parse_study
from jackpy.scene.workplace import load_workplace

SCENE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


@pytest.mark.timeout(900)
def test_full_figure_criteria() -> None:
    study = parse_study({"jackpy_study": 1, "reach": ["desk.button"],
                         "clearance": [{"object": "desk", "min_m": 0.0, "posture": "desk.button"},
                                       {"object": "shelf", "min_m": 0.02}],
                         "strength": {"load_kg": 5, "max_utilisation": 1.0},
                         "ergonomics": [{"method": "rula", "posture": "desk.button", "max_score": 7}]})
    wp = load_workplace(SCENE)
    check_against_scene(study, wp.env)
    ctx = SweepContext(wp, study).prepare(("male",))
    small = evaluate_body(ctx, make_body(0, "male", {"stature": 1.62}))
    tall = evaluate_body(ctx, make_body(1, "male", {"stature": 1.95}))
    assert list(small) == columns(study)
    for row in (small, tall):
        assert row["reach:desk.button"] == 1
        assert 0.0 < row["strength:joints:max_utilisation"] < 1.0 and row["strength:joints"] == 1
        assert 1.0 <= row["ergonomics:rula:score"] <= 7.0
        assert row["clearance:shelf:distance_m"] > 0.0
    # the tall body's head is nearer the shelf above the desk than the short body's
    assert tall["clearance:shelf:distance_m"] < small["clearance:shelf:distance_m"]
