"""``jackpy info`` and ``jackpy convert``, in process and once as a real subprocess."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import trimesh

from jackpy.cli import main
from jackpy.peabody.compare import figure_differences
from jackpy.peabody.reader import read_environment, read_figures

FIGURES = Path(__file__).resolve().parents[2] / "figures"
TABLE = str(FIGURES / "table.fig")


def test_info_prints_the_table_summary(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", TABLE]) == 0
    out = capsys.readouterr().out
    assert "figure table: 5 segments, 4 joints, 4 DOFs, 13 sites, root top.base" in out
    assert "joint leg4: top.leg0 -> leg.top, R(z)" in out
    assert "bounds (world, cm, from geometry): min (0, 0, 0) max (100, 85, 200)" in out


def test_info_json_and_site_bounds_without_geometry(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", str(FIGURES / "finger.fig"), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    (fig,) = data["figures"]
    assert fig["dofs"] == 3 and fig["groups"] == [{"name": "curl", "joints": ["mcp", "pip", "dip"],
                                                   "angles": ["curl"]}]
    assert fig["bounds_cm"]["from"] == "geometry"
    bare = tmp_path / "bare.fig"
    bare.write_text('figure bare { segment s { psurf = "gone.pss"; site a->location = trans(0cm,0cm,0cm);'
                    " site b->location = trans(10cm,20cm,30cm); } }")
    assert main(["info", str(bare), "--json", "--no-geometry"]) == 0
    b = json.loads(capsys.readouterr().out)["figures"][0]["bounds_cm"]
    assert b == {"min": [0.0, 0.0, 0.0], "max": [10.0, 20.0, 30.0], "from": "sites"}


def test_info_environment(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["info", str(FIGURES / "workplace.env")]) == 0
    out = capsys.readouterr().out
    assert "4 figures, includes worktable.fig, chair.fig, arm7.fig" in out
    assert "figure arm7: 5 segments, 4 joints, 7 DOFs" in out


def test_malformed_file_prints_position_and_exits_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.fig"
    bad.write_text("figure f {\n  segment a {\n    attribute = red\n  }\n}\n")
    assert main(["info", str(bad)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == f"jackpy: error: {bad}:4:3: expected ';', found '}}'"


def test_semantic_error_and_missing_geometry_exit_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "loop.fig"
    bad.write_text("figure f { segment a { site s->location = trans(0cm,0cm,0cm); }\n"
                   "joint j { connect a.s to a.s; type = R(z); } }")
    assert main(["info", str(bad)]) == 2
    assert "joint 'j' connects segment 'a' to itself" in capsys.readouterr().err
    gone = tmp_path / "gone.fig"
    gone.write_text('figure g { segment body { psurf = "nowhere.pss"; } }')
    assert main(["info", str(gone)]) == 2
    assert "segment 'body': geometry file 'nowhere.pss' not found" in capsys.readouterr().err


def test_real_subprocess_reports_parse_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.fig"
    bad.write_text("figure f { segment a { site s->location = trans(1cm 2cm 3cm); } }")
    proc = subprocess.run([sys.executable, "-m", "jackpy", "info", str(bad)], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.strip() == f"jackpy: error: {bad}:1:53: expected ',', found '2'"
    assert "Traceback" not in proc.stderr


def test_convert_to_glb_loads_back_in_world_metres(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "table.glb"
    assert main(["convert", TABLE, str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    scene = trimesh.load(out)
    assert len(scene.geometry) == 5 and "table.top" in scene.geometry
    np.testing.assert_allclose(scene.bounds, [[0, 0, 0], [1.0, 0.85, 2.0]], atol=1e-6)


def test_convert_environment_to_obj_and_text(tmp_path: Path) -> None:
    env_in = FIGURES / "workplace.env"
    assert main(["convert", str(env_in), str(tmp_path / "w.obj")]) == 0
    mesh = trimesh.load(tmp_path / "w.obj", force="mesh")
    assert len(mesh.faces) > 100
    assert main(["convert", str(env_in), str(tmp_path / "w.env")]) == 0
    assert main(["convert", str(env_in), str(tmp_path / "w.fig")]) == 0
    original = read_environment(env_in)
    back_env = read_environment(tmp_path / "w.env", allow_outside=True)  # (includes stay in figures/)
    back_fig = read_figures(tmp_path / "w.fig", allow_outside=True)  # (psurfs stay in figures/)
    for back in (back_env.figures, {f.name: f for f in back_fig}):
        for name, fig in original.figures.items():
            assert figure_differences(fig, back[name], dirs=(FIGURES, tmp_path)) == []


def test_convert_refuses_unknown_output(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["convert", TABLE, str(tmp_path / "t.xyz")]) == 1
    assert "cannot convert to '.xyz'" in capsys.readouterr().err
    assert not (tmp_path / "t.xyz").exists()
