"""``jackpy flock-replay FILE --figure``: the standard human driven from the shipped reach recording."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from jackpy.body.human import attach_groups
from jackpy.cli import main
from jackpy.peabody.reader import read_figures

REACH = Path(__file__).resolve().parents[2] / "examples" / "flock" / "reach.jsonl"


def test_replay_drives_the_figure_and_writes_the_final_posture(tmp_path, capsys):
    out = tmp_path / "posture.fig"
    assert main(["flock-replay", str(REACH), "--figure", "--speed", "0", "--every", "25", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "frame    275" in text and "frame    299" in text and "error cm:" in text
    assert "drove 13 of 300 frames" in text and f"wrote {out}" in text
    fig = read_figures(out)[0]
    if "spine" not in fig.groups:  # files written before groups were saved with the figure
        attach_groups(fig)
    final = json.loads((REACH.parent / "reach-final.json").read_text())
    for part, site in (("right_palm", ("right_palm", "palm_centre")), ("left_palm", ("left_palm", "palm_centre"))):
        assert np.linalg.norm(fig.site_world(*site)[:3, 3] - np.array(final[part])[:3, 3]) < 0.02


def test_replay_json_and_bad_options(capsys):
    assert main(["flock-replay", str(REACH), "--figure", "--speed", "0", "--every", "100", "--json"]) == 0
    cap = capsys.readouterr()
    rows = [json.loads(line) for line in cap.out.splitlines()]
    assert [r["frame"] for r in rows] == [0, 100, 200, 299]
    assert np.allclose(rows[-1]["spine_deg"], [10.0, 0.0, 8.0], atol=0.3)
    assert max(rows[-1]["errors_m"]["right_palm"], rows[-1]["errors_m"]["left_palm"]) < 0.02
    assert "drove 4 of 300 frames" in cap.err
    assert main(["flock-replay", str(REACH), "--figure", "--every", "0"]) == 1
    assert main(["flock-replay", str(REACH), "--figure", "--calibrate-frame", "999"]) == 1
    err = capsys.readouterr().err
    assert err.count("jackpy: error:") == 2 and "Traceback" not in err
