"""``jackpy motion bake|import-bvh|export`` end to end, and their one-line errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from jackpy.cli import main
from jackpy.motion import motion_file

MOCAP = Path("/work/shared/data/mocap")
SCENE_MOTION = {"jackpy_motion": 1, "timeline": {
    "figures": {"jack": {"human": "male:50", "position": [0.0, 0.0], "heading_deg": 0}},
    "motions": [{"kind": "com", "figure": "jack", "t0": 0.0, "t1": 0.4, "x": 0.3},
                {"kind": "foot", "figure": "jack", "side": "right", "t0": 0.4, "t1": 0.8,
                 "displacement": [0, 0, 0.2], "height": 0.1}],
    "timed": [{"figure": "jack", "control": "torso", "value": "hold", "t0": 0.2, "t1": 0.6}],
    "duration": 1.0}}


def test_bake_then_export(tmp_path, capsys):
    src = tmp_path / "step.motion.json"
    src.write_text(json.dumps(SCENE_MOTION))
    out = tmp_path / "baked.motion.json"
    assert main(["motion", "bake", "-", str(src), "-o", str(out), "--fps", "10"]) == 0
    mf = motion_file.load(out)
    assert mf.fps == 10 and mf.n_frames == 11 and list(mf.baked) == ["jack"]
    assert "11 frames" in capsys.readouterr().out
    for ext in ("bvh", "glb", "csv"):
        dst = tmp_path / f"step.{ext}"
        assert main(["motion", "export", str(out), "-o", str(dst)]) == 0
        assert dst.stat().st_size > 0
    # an unbaked file is baked on the way
    assert main(["motion", "export", str(src), "--fps", "5", "-o", str(tmp_path / "direct.csv")]) == 0
    assert len((tmp_path / "direct.csv").read_text().splitlines()) == 1 + 6


def test_import_bvh(tmp_path):
    out = tmp_path / "walk.motion.json"
    assert main(["motion", "import-bvh", str(MOCAP / "bandai2_walk-turn-left_normal_001.bvh"), "--figure",
                 "female:5", "--fps", "5", "-o", str(out)]) == 0
    mf = motion_file.load(out)
    baked = next(iter(mf.baked.values()))
    assert baked.human == "female:5" and baked.n_frames == 17


@pytest.mark.parametrize("argv,needle", [
    (["motion", "bake", "-", "missing.motion.json", "-o", "x.motion.json"], "no such motion file"),
    (["motion", "import-bvh", "missing.bvh", "-o", "x.motion.json"], "no such BVH file"),
    (["motion", "import-bvh", str(MOCAP / "cmu_02_01_walk.bvh"), "--figure", "robot:5", "-o", "x.json"],
     "standard human"),
])
def test_bad_input_is_one_line_exit_2(tmp_path, capsys, argv, needle, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0]


def test_bad_export_suffix_and_fps(tmp_path, capsys):
    src = tmp_path / "m.motion.json"
    src.write_text(json.dumps(SCENE_MOTION))
    assert main(["motion", "export", str(src), "--fps", "2", "-o", str(tmp_path / "out.fbx")]) == 2
    assert "export as .bvh, .glb or .csv" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exc:
        main(["motion", "bake", "-", str(src), "-o", "x", "--fps", "0"])
    assert exc.value.code == 2


def test_progress_bar_for_long_jobs():
    import io

    from jackpy.commands.motion import Progress

    quick = io.StringIO()
    p = Progress("baking", stream=quick)
    p(10, 10)
    assert quick.getvalue() == ""  # done within a second: nothing shown
    slow = io.StringIO()
    p = Progress("baking", after_s=0.0, stream=slow)
    p(5, 10)
    p(10, 10)
    assert "5/10 frames" in slow.getvalue() and slow.getvalue().endswith("\n")
