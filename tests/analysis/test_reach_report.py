"""``jackpy analyze --reach-mode``: the mode reaches results.json, the CSV's reach_mode column and the
report; a bad mode is one clear error."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from jackpy.cli import main

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"

import jackpy.body.human  # noqa: E402,F401  (a broken import fails, never skips)


def test_analyze_with_body_reach_mode(tmp_path, capsys):
    out = tmp_path / "r"
    rc = main(["analyze", str(EXAMPLE), "--figures", "female:5", "--reach", "desk.button",
               "--reach-mode", "body", "--no-pictures", "--resolution", "8", "-o", str(out)])
    assert rc == 0, capsys.readouterr().err
    res = json.loads((out / "results.json").read_text())
    assert res["reach_mode"] == "body"
    v = res["figures"][0]["reach"]["desk.button"]
    assert v["mode"] == "body" and v["reached"] and v["steps"] == 0 and not v["stepped"]
    assert v["balanced"] is True and v["com_margin_m"] < 0
    rows = list(csv.DictReader((out / "results.csv").open()))
    reach = [r for r in rows if r["analysis"] == "reach"]
    assert {r["metric"] for r in reach} == {"shortfall", "steps"} and {r["reach_mode"] for r in reach} == {"body"}
    assert all(r["reach_mode"] == "" for r in rows if r["analysis"] != "reach")
    html = (out / "report.html").read_text()
    assert "feet planted" in html


def test_bad_reach_mode_is_rejected(tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        main(["analyze", str(EXAMPLE), "--reach-mode", "walk", "-o", str(tmp_path)])
    assert e.value.code != 0 and "reach-mode" in capsys.readouterr().err
