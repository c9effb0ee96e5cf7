"""Every command that reads a user's file answers a malformed or missing file with exactly one
line on stderr starting ``jackpy: error:`` and a non-zero exit (2 for a parse error), never a
traceback."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from jackpy.cli import main

BAD_FIG = "figure f {\n  segment s { site a->location = trans(1cm, 2cm; }\n}\n"


def _one_line_error(capsys, code: int, expected_code: int | None = None, contains: str = "") -> str:
    out = capsys.readouterr()
    lines = out.err.splitlines()
    assert len(lines) == 1, out.err
    assert lines[0].startswith("jackpy: error: "), out.err
    assert "Traceback" not in out.err + out.out
    assert code != 0
    if expected_code is not None:
        assert code == expected_code, out.err
    assert contains in lines[0], lines[0]
    return lines[0]


@pytest.fixture
def files(tmp_path: Path) -> Path:
    (tmp_path / "bad.fig").write_text(BAD_FIG)
    (tmp_path / "bad.env").write_text('include "bad.fig";\n')
    (tmp_path / "nul.env").write_text('include "a\x00b.fig";\n')
    (tmp_path / "binary.fig").write_bytes(b"figure f {\xff}\n")
    (tmp_path / "scene.json").write_text('{"jackpy_scene": 1, "objects": [{"source": "x.obj", "units": "km"}]}')
    (tmp_path / "syntax.json").write_text('{"jackpy_scene": 1,\n "objects": [}')
    (tmp_path / "bad.jsonl").write_text('{"jackpy": "flock-recording", "version": 1}\n[0,1,0,"Y",36,[1,2],null,null]\n')
    (tmp_path / "notrec.jsonl").write_text("hello\n")
    return tmp_path


@pytest.mark.parametrize("argv, code, contains", [
    (["info", "{d}/bad.fig"], 2, "bad.fig:2:"),
    (["info", "{d}/bad.env"], 2, "bad.fig:2:"),
    (["info", "{d}/binary.fig"], 2, "binary.fig:1:11: expected UTF-8 text"),
    (["info", "{d}/nul.env"], 2, "nul.env:1:9: cannot read included file"),
    (["info", "{d}/missing.fig"], None, "missing.fig"),
    (["info", "{d}"], None, ""),
    (["info", "{d}/scene.json"], None, "scene.json"),
    (["convert", "{d}/bad.fig", "{d}/out.glb"], 2, "bad.fig:2:"),
    (["convert", "{d}/missing.env", "{d}/out.fig"], None, "missing.env"),
])
def test_peabody_commands(files: Path, capsys, argv, code, contains) -> None:
    rc = main([a.format(d=files) for a in argv])
    _one_line_error(capsys, rc, code, contains)
    assert not (files / "out.glb").exists() and not (files / "out.fig").exists()


@pytest.mark.parametrize("override", ["stature", "stature=tall", "nosuch=10cm", "mass=10cm", "stature=p1e999x"])
def test_human_set(tmp_path: Path, capsys, override: str) -> None:
    rc = main(["human", "--sex", "male", "--set", override, "-o", str(tmp_path / "h.fig")])
    _one_line_error(capsys, rc, None, "")
    assert not (tmp_path / "h.fig").exists()


@pytest.mark.parametrize("scene, contains", [
    ("scene.json", "scene.json: objects[0].units: expected one of m, cm, mm, in, found 'km'"),
    ("syntax.json", "syntax.json:2:14: expected JSON"),
    ("missing.json", "missing.json: no such scene file"),
    ("bad.fig", "bad.fig:1:1: expected JSON"),
])
def test_analyze(files: Path, capsys, scene: str, contains: str) -> None:
    rc = main(["analyze", str(files / scene), "--no-pictures", "-o", str(files / "report")])
    _one_line_error(capsys, rc, 2, contains)
    assert not (files / "report").exists()


@pytest.mark.parametrize("scene, code, contains", [
    ("bad.fig", 2, "bad.fig:2:"), ("bad.env", 2, "bad.fig:2:"), ("missing.env", 2, "no such scene file")])
def test_screenshot_bad_scene(files: Path, capsys, scene: str, code: int, contains: str) -> None:
    rc = main(["screenshot", str(files / scene), "-o", str(files / "shot.png")])
    _one_line_error(capsys, rc, code, contains)
    assert not (files / "shot.png").exists()


def test_screenshot_bad_sidecar(files: Path, capsys) -> None:
    (files / "ok.env").write_text("figure box { segment b { site base->location = trans(0,0,0); } }\n")
    (files / "ok.jackpy.json").write_text('{"format": "jackpy-session", "figures": {"box": {"q": "x"}}}')
    rc = main(["screenshot", str(files / "ok.env"), "-o", str(files / "shot.png")])
    _one_line_error(capsys, rc, 2, "ok.jackpy.json: figures.box.q: expected a list")


@pytest.mark.parametrize("argv, code, contains", [
    (["flock-replay", "{d}/bad.jsonl", "--speed", "0"], 2, "bad.jsonl:2:1: bad sample line"),
    (["flock-replay", "{d}/notrec.jsonl"], 2, "notrec.jsonl:1:1: not a jackpy Flock recording"),
    (["flock-replay", "{d}/missing.jsonl"], None, "missing.jsonl"),
    (["flock-replay", "{d}"], None, ""),
])
def test_flock_replay(files: Path, capsys, argv, code, contains) -> None:
    rc = main([a.format(d=files) for a in argv])
    _one_line_error(capsys, rc, code, contains)


def test_flock_replay_bad_sensor_config(files: Path, capsys) -> None:
    rec = Path(__file__).resolve().parents[2] / "examples" / "flock" / "reach.jsonl"
    (files / "sensors.json").write_text(json.dumps({"sensors": [{"bird": 300, "part": "pelvis"}]}))
    rc = main(["flock-replay", str(rec), "--figure", "--speed", "0", "--sensors", str(files / "sensors.json")])
    _one_line_error(capsys, rc, 2, "sensors.json: sensors[0].bird: expected an integer in 0..126, found 300")


# ---------------------------------------------------------------- real processes
def _run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "jackpy", *args], check=False, capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, PYTHONWARNINGS="ignore"))


def test_subprocess_info_and_replay(files: Path) -> None:
    for args, code, contains in ((["info", str(files / "bad.fig")], 2, "bad.fig:2:"),
                                 (["flock-replay", str(files / "bad.jsonl")], 2, "bad.jsonl:2:1:"),
                                 (["analyze", str(files / "syntax.json"), "-o", str(files / "r")], 2, "syntax.json:2:14:")):
        done = _run(*args)
        assert done.returncode == code, done.stderr
        lines = done.stderr.splitlines()
        assert len(lines) == 1 and lines[0].startswith("jackpy: error: ") and contains in lines[0], done.stderr


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="the workbench window needs an X display")
def test_subprocess_open_bad_scene(files: Path) -> None:
    done = _run("open", str(files / "bad.env"), "--frames", "1")
    assert done.returncode == 2, done.stderr
    lines = done.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("jackpy: error: ") and "bad.fig:2:" in lines[0], done.stderr
