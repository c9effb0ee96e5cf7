"""STUDY.json: the criteria it holds, and one clear error (file:line:column or key path) for bad
input; fuzzed with hypothesis."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from jackpy import jsonfile
from jackpy.population.study import StudyError, check_against_scene, load_study, parse_study
from jackpy.scene.workplace import load_workplace

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "examples" / "workplace" / "workplace.json"


def test_example_study_parses_and_fits_the_scene() -> None:
    study = load_study(ROOT / "examples" / "workplace" / "study.json")
    assert [c.id for c in study.criteria] == ["reach:desk.button", "reach:shelf.box_handle", "view:panel",
                                              "view:panel.switch"]
    assert not study.needs_surfaces
    assert study.criteria[3].params["cone"] == "maximum eye rotation"
    check_against_scene(study, load_workplace(SCENE).env)
    again = parse_study(study.to_dict())
    assert again.criteria == study.criteria


def test_full_study_needs_surfaces() -> None:
    study = parse_study({"jackpy_study": 1, "reach": [{"target": "desk.button", "hand": "left"}],
                         "clearance": [{"object": "shelf", "min_m": 0.05, "posture": "desk.button"}],
                         "strength": {"load_kg": 5}})
    assert study.needs_surfaces and study.criteria[0].params["hand"] == "left"
    check_against_scene(study, load_workplace(SCENE).env)


def test_bad_json_names_line_and_column(tmp_path: Path) -> None:
    p = tmp_path / "s.json"
    p.write_text('{"jackpy_study": 1,\n "reach": ["desk.button",]\n}')
    with pytest.raises(StudyError, match=r"s\.json:2:\d+"):
        load_study(p)


@pytest.mark.parametrize("data, where", [
    ({"jackpy_study": 2, "reach": ["a.b"]}, "jackpy_study"),
    ({"jackpy_study": 1, "reach": "a.b"}, "reach"),
    ({"jackpy_study": 1, "view": [{"target": "gauge", "cone": "tunnel"}]}, "view[0].cone"),
    ({"jackpy_study": 1, "reach": [{"target": "a.b", "tolerance": 1}]}, "reach[0].tolerance"),
    ({"jackpy_study": 1, "strength": {"load_kg": -1}}, "strength.load_kg"),
    ({"jackpy_study": 1, "colour": 1, "reach": ["a.b"]}, "colour"),
    ({"jackpy_study": 1}, "no criteria"),
    ({"jackpy_study": 1, "reach": ["a.b", "a.b"]}, "twice"),
])
def test_bad_values_name_the_key(tmp_path: Path, data: dict, where: str) -> None:
    p = tmp_path / "s.json"
    p.write_text(json.dumps(data))
    with pytest.raises(StudyError, match=where.replace("[", r"\[").replace("]", r"\]")):
        load_study(p)


def test_targets_must_exist_in_the_scene() -> None:
    env = load_workplace(SCENE).env
    with pytest.raises(StudyError, match="no object named 'crane'"):
        check_against_scene(parse_study({"jackpy_study": 1, "reach": ["crane.hook"]}, "s.json"), env)
    with pytest.raises(StudyError, match="posture 'desk.far_corner'"):
        check_against_scene(parse_study({"jackpy_study": 1, "reach": ["desk.button"],
                                         "strength": {"posture": "desk.far_corner"}}, "s.json"), env)


def test_cli_prints_one_line_and_exits_2(tmp_path: Path) -> None:
    p = tmp_path / "s.json"
    p.write_text('{"jackpy_study": 1, "reach": ["desk.nothing"]}')
    run = subprocess.run([sys.executable, "-m", "jackpy", "sweep", str(SCENE), "--study", str(p), "--n", "4",
                          "-o", str(tmp_path / "out")], capture_output=True, text=True)
    assert run.returncode == 2
    assert run.stderr.count("\n") == 1 and "desk.nothing" in run.stderr


json_values = st.recursive(st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=8),
                           lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=4),
                           max_leaves=20)
study_like = st.fixed_dictionaries({"jackpy_study": st.just(1)}, optional={
    "hand": json_values, "reach": json_values, "view": json_values, "clearance": json_values,
    "strength": json_values, "ergonomics": json_values})


@settings(max_examples=300, deadline=None)
@given(study_like)
def test_fuzzed_studies_parse_or_raise_invalid(data: dict) -> None:
    try:
        parse_study(data)
    except jsonfile.Invalid:
        pass


def test_cli_unreachable_scheduler_is_one_line_exit_2(tmp_path: Path) -> None:
    run = subprocess.run([sys.executable, "-m", "jackpy", "sweep", str(SCENE), "--study",
                          str(ROOT / "examples" / "workplace" / "study.json"), "--n", "4", "--scheduler",
                          "tcp://127.0.0.1:1", "-o", str(tmp_path / "out")], capture_output=True, text=True)
    assert run.returncode == 2
    assert run.stderr.count("\n") == 1 and "cannot reach the Dask scheduler" in run.stderr
