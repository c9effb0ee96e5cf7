"""``jackpy creature new`` and ``jackpy creature walk`` end to end."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from jackpy.cli import main
from jackpy.motion import motion_file
from jackpy.peabody.reader import load

EX = Path(__file__).resolve().parents[2] / "examples" / "creatures"


def test_new_then_walk_and_pronk(tmp_path, capsys):
    fig = tmp_path / "biped.fig"
    assert main(["creature", "new", str(EX / "biped.drawing.json"), "-o", str(fig)]) == 0
    assert (tmp_path / "creature_box.pss").exists()
    assert "2 legs" in capsys.readouterr().err
    out, ev = tmp_path / "w.motion.json", tmp_path / "ev.csv"
    assert main(["creature", "walk", str(fig), "--terrain", str(EX / "rolling_hills.terrain.json"), "--to", "0,1",
                 "--fps", "10", "--events", str(ev), "-o", str(out)]) == 0
    mf = motion_file.load(out)
    baked = mf.baked["biped"]
    assert mf.fps == 10 and baked.n_frames > 30
    f = load(fig).figures["biped"]
    posture = baked.posture(f, baked.n_frames - 1)
    assert np.hypot(*(posture.location[[0, 2], 3] - [0, 1])) < 0.2
    rows = list(csv.DictReader(ev.open()))
    assert {r["cause"] for r in rows} >= {"footstep", "liftoff"}
    assert [int(r["frame"]) for r in rows] == sorted(int(r["frame"]) for r in rows)
    assert main(["creature", "walk", str(fig), "--gait", "pronk", "--to", "0,0.5", "--fps", "10", "-o",
                 str(tmp_path / "p.motion.json")]) == 0


def test_bad_input_is_one_line_exit_2(tmp_path, capsys):
    (tmp_path / "d.json").write_text('{"nodes": [[0, 0]],\n "links": [[0, 5]]}')
    assert main(["creature", "new", str(tmp_path / "d.json"), "-o", str(tmp_path / "x.fig")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "links[0][1]" in err
    assert not (tmp_path / "x.fig").exists()
    (tmp_path / "t.json").write_text('{"cell": 0.1, "heights": [[0]]}')
    assert main(["creature", "walk", str(EX / "hexapod.fig"), "--terrain", str(tmp_path / "t.json"), "-o",
                 str(tmp_path / "o.json")]) == 2
    assert "t.json" in capsys.readouterr().err
