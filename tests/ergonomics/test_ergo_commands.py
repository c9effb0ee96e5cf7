"""``jackpy ergo`` (one posture, every baked frame of a motion) and ``jackpy analyze --ergonomics``."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from jackpy.body import make_human
from jackpy.cli import main
from jackpy.peabody.model import Environment

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


@pytest.fixture(scope="module")
def session(tmp_path_factory) -> Path:
    """A saved session with one standard human, right arm raised 100° forward."""
    from jackpy.document import Document

    env = Environment()
    f = make_human("male", 50, name="worker")
    env.add(f)
    f.groups["right_shoulder_complex"].set_angles(f, np.radians([100.0, 90.0, 0.0]))
    return Document(env).save(tmp_path_factory.mktemp("s") / "work.env")


def test_ergo_scores_the_posed_figure_of_a_session(session, capsys):
    assert main(["ergo", str(session), "--method", "rula,reba,lowback", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["figure"] == "worker"
    rula = d["methods"]["rula"]
    assert rula["posture"]["upper_arm_flexion"] == pytest.approx(100.0, abs=1e-6)
    assert rula["worksheet"]["side"] == "right" and rula["worksheet"]["upper_arm"] == 4
    assert set(d["methods"]) == {"rula", "reba", "lowback"}


def test_ergo_text_and_workplace_scene(capsys):
    assert main(["ergo", str(EXAMPLE), "--method", "rula", "--human", "female:5"]) == 0
    out = capsys.readouterr().out
    assert "rula 2 (level 1)" in out and "upper_arm: 1" in out and "frame" not in out.splitlines()[0]


@pytest.mark.parametrize("argv,message", [
    (["--method", "rola"], "unknown ergonomic method 'rola'"),
    (["--load", "-2"], "load_kg: must be a number >= 0"),
    (["--figure", "nobody"], "no figure 'nobody'"),
])
def test_ergo_bad_input_is_one_line(session, capsys, argv, message):
    assert main(["ergo", str(session)] + argv) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and len(err.splitlines()) == 1


def test_ergo_bad_task_file(session, tmp_path, capsys):
    bad = tmp_path / "task.json"
    bad.write_text('{"lifts": [{"d": 40, "frequency": 30}],\n "load_kg": 5}\n')
    assert main(["ergo", str(session), "--method", "niosh", "--task", str(bad)]) == 2
    assert "off the NIOSH frequency table" in capsys.readouterr().err
    bad.write_text('{"load_kg": 5,\n  oops}\n')
    assert main(["ergo", str(session), "--task", str(bad)]) == 2
    assert f"{bad}:2:" in capsys.readouterr().err


def test_ergo_every_frame_of_a_motion(session, tmp_path, capsys):
    from jackpy.ergonomics.inputs import figure_from_scene
    from jackpy.motion import motion_file
    from jackpy.motion.bake import Posture

    f = figure_from_scene(str(session), "worker")
    arm = f.groups["right_shoulder_complex"]
    postures = []
    for deg in (10.0, 30.0, 60.0, 100.0):
        arm.set_angles(f, np.radians([deg, 90.0, 0.0]))
        postures.append(Posture.of(f))
    mf = motion_file.MotionFile(fps=2.0, baked={"worker": motion_file.BakedFigure.from_postures(f, postures,
                                                                                                human="male:50")})
    path = tmp_path / "raise.motion.json"
    motion_file.save(mf, path)
    out = tmp_path / "frames"
    assert main(["ergo", str(session), "--motion", str(path), "--method", "rula,reba", "-o", str(out)]) == 0
    assert capsys.readouterr().out.startswith("wrote ")
    rows = list(csv.DictReader((out / "frames.csv").open()))
    assert [int(r["frame"]) for r in rows] == [0, 1, 2, 3]
    assert [float(r["time"]) for r in rows] == [0.0, 0.5, 1.0, 1.5]
    scores = [json.loads(r["rula"]) for r in rows]
    assert scores == sorted(scores) and scores[0] < scores[-1]  # the arm rises through 20, 45, 90°
    assert (out / "rula.svg").read_text().startswith("<svg") and (out / "reba.svg").exists()
    assert main(["ergo", str(session), "--motion", str(path), "--method", "rula"]) == 0
    table = capsys.readouterr().out.splitlines()
    assert table[0].split()[:3] == ["frame", "time_s", "rula"] and len(table) == 5
    # on an empty floor: the motion's one figure, made at the motion's size, gives the same scores
    assert main(["ergo", "-", "--motion", str(path), "--method", "rula", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["figure"] == "worker" and [r["rula"] for r in d["frames"]] == scores


def test_ergo_motion_without_the_figure(session, tmp_path, capsys):
    from jackpy.motion import motion_file

    path = tmp_path / "empty.motion.json"
    motion_file.save(motion_file.MotionFile(), path)
    assert main(["ergo", str(session), "--motion", str(path)]) == 2
    assert "no baked frames for figure 'worker'" in capsys.readouterr().err


def test_analyze_with_ergonomics_report_json_csv(tmp_path, capsys):
    task = tmp_path / "task.json"
    task.write_text(json.dumps({"load_kg": 5, "lifts": [{"d": 40, "frequency": 1, "duration_h": 1}]}))
    out = tmp_path / "report"
    rc = main(["analyze", str(EXAMPLE), "--figures", "male:50", "--reach", "desk.button", "--view", "panel",
               "--resolution", "6", "--ergonomics", "all", "--ergo-task", str(task), "-o", str(out)])
    if rc != 0 and "offscreen rendering is unavailable" in capsys.readouterr().err:
        pytest.skip("no EGL here")
    assert rc == 0
    res = json.loads((out / "results.json").read_text())
    ergo = res["figures"][0]["ergonomics"]
    assert ergo["posture"] == "desk.button"
    assert set(ergo["methods"]) == {"rula", "reba", "owas", "niosh", "lowback", "capable"}
    # RULA scores the worse arm (Table A, then the sum of its parts); the reaching right arm was
    # assessed in its reach posture (not hanging: its part scores differ from the free left arm's)
    ws = ergo["methods"]["rula"]["worksheet"]
    arms = ws["arms"]
    key = {s: (a["table_a"], a["upper_arm"] + a["lower_arm"] + a["wrist"] + a["wrist_twist"]) for s, a in arms.items()}
    assert key[ws["side"]] == max(key.values())
    parts = ("upper_arm", "lower_arm", "wrist", "wrist_twist")
    assert [arms["right"][k] for k in parts] != [arms["left"][k] for k in parts]
    rows = [r for r in csv.DictReader((out / "results.csv").open()) if r["analysis"] == "ergonomics"]
    scores = {r["target"]: r["value"] for r in rows if r["metric"] == "score"}
    assert float(scores["rula"]) == ergo["methods"]["rula"]["score"]
    html = (out / "report.html").read_text()
    for m in ergo["methods"]:
        assert f"male50-ergo-{m}.png" in html and (out / f"male50-ergo-{m}.png").stat().st_size > 1000
    assert "grand_score" in html and "compression_N" in html


@pytest.mark.parametrize("task,message", [
    ({"lifts": [{"d": 40, "frequency": 20}], "load_kg": 5}, "off the NIOSH frequency table"),
    ({"load_kg": -5}, "load_kg"),
    ({}, "needs a lifting task"),
])
def test_analyze_bad_ergonomic_task_writes_nothing(tmp_path, capsys, task, message):
    path = tmp_path / "task.json"
    path.write_text(json.dumps(task))
    out = tmp_path / "report"
    rc = main(["analyze", str(EXAMPLE), "--ergonomics", "rula,niosh", "--ergo-task", str(path), "--no-pictures",
               "-o", str(out)])
    assert rc != 0
    assert message in capsys.readouterr().err
    assert not out.exists()


def test_example_task_file(capsys):
    task = EXAMPLE.parents[1] / "ergonomics" / "lift_task.json"
    assert main(["ergo", str(EXAMPLE), "--method", "niosh,lowback", "--task", str(task), "--json"]) == 0
    niosh = json.loads(capsys.readouterr().out)["methods"]["niosh"]
    assert len(niosh["worksheet"]["lifts"]) == 2 and niosh["worksheet"]["CLI"] == niosh["score"]
    assert niosh["score"] > max(x["LI"] for x in niosh["worksheet"]["lifts"])
