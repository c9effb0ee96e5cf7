"""The shipped ANSUR II tables: derived from the public subject files, and the loader reads them."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from jackpy.body import ansur2
from jackpy.body.anthropometry import AnthropometryError

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT.parent / "shared" / "data" / "anthropometry"


@pytest.mark.skipif(not (DATA / "ansur2_male.csv").exists(), reason="ANSUR II subject files not present")
def test_shipped_tables_are_what_the_tool_derives(tmp_path: Path) -> None:
    subprocess.run([sys.executable, str(ROOT / "tools" / "derive_ansur2.py"), "--data", str(DATA),
                    "--out", str(tmp_path)], check=True)
    shipped = ROOT / "src" / "jackpy" / "body" / "data"
    for name in ("ansur2_summary.csv", "ansur2_correlations.csv"):
        assert (tmp_path / name).read_text() == (shipped / name).read_text()


def test_summary_matches_the_survey_sanity_figures() -> None:
    # data README (unweighted sample statistics of the public files)
    male, female = ansur2.summary("male"), ansur2.summary("female")
    assert male["stature"].n == 4082 and female["stature"].n == 1986
    assert male["stature"].mean == pytest.approx(1.7562, abs=1e-4)
    assert male["stature"].sd == pytest.approx(0.0686, abs=1e-4)
    assert female["weight"].mean == pytest.approx(67.76, abs=0.01) and female["weight"].unit == "kg"
    assert male["span"].measurement == "span" and ansur2.stats("male", "bideltoidbreadth").key == "bideltoid_breadth"
    arm = male["arm_length"]
    assert arm.measurement == "acromionradialelength + radialestylionlength"
    assert arm.mean == pytest.approx(male["upper_arm_length"].mean + male["forearm_length"].mean, abs=1e-5)


def test_correlations_are_symmetric_positive_definite_and_match_the_data() -> None:
    dims = ansur2.key_dimensions()
    for sex, r_sw, r_ss in (("male", 0.469, 0.823), ("female", 0.533, 0.819)):
        c = ansur2.correlations(sex, dims)
        assert np.allclose(c, c.T) and np.allclose(np.diag(c), 1.0)
        assert np.linalg.eigvalsh(c).min() > 0
        sub = ansur2.correlations(sex, ["stature", "weight", "span"])
        assert sub[0, 1] == pytest.approx(r_sw, abs=1e-3) and sub[0, 2] == pytest.approx(r_ss, abs=1e-3)


def test_quantile_interpolates_the_table_and_rejects_bad_input() -> None:
    s = ansur2.stats("female", "stature")
    assert ansur2.quantile("female", "stature", 5) == pytest.approx(s.percentiles[5.0])
    assert s.percentiles[5.0] < ansur2.quantile("female", "stature", 25) < s.percentiles[50.0]
    with pytest.raises(AnthropometryError):
        ansur2.quantile("female", "stature", 0.5)
    with pytest.raises(AnthropometryError):
        ansur2.correlations("male", ["stature", "shoe_size"])
    with pytest.raises(AnthropometryError):
        ansur2.summary("robot")
