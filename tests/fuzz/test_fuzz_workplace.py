"""Fuzzing workplace scene JSON (``load_workplace``): mutated scenes raise only SessionError, with
``file:line:column`` for JSON syntax and the key path for a value of the wrong shape."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from fuzz_helpers import (
    FUZZ,
    byte_mutations,
    check_error,
    expect_only_project_errors,
    mutate,
    mutate_bytes,
    mutations,
)
from hypothesis import given

from jackpy.errors import SessionError
from jackpy.scene.workplace import load_workplace, save_workplace

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "workplace"
SCENE = {
    "jackpy_scene": 1,
    "objects": [
        {"name": "panel", "source": "panel.obj", "units": "cm", "up": "y", "position": [0.0, 1.0, 0.75],
         "colour": [0.3, 0.35, 0.4], "sites": {"switch": {"position": [-0.1, 0.14, 0.0]}}},
        {"name": "desk", "source": "desk.obj", "units": "mm", "up": "z",
         "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0.3], [0, 0, 0, 1]],
         "sites": {"button": {"rotation_deg": [0, 90, 0], "position": [-0.2, 1.02, 0.1]}}},
    ],
    "figure": {"position": [0.0, 0.0], "heading_deg": 0},
    "analysis": {"reach": ["desk.button", "panel.switch"], "view": ["panel"], "load_kg": 5, "hand": "right"},
}
SCENE_TEXT = json.dumps(SCENE, indent=1)
WORDS = ['"objects"', '"source"', '"units"', '"up"', '"matrix"', '"position"', '"rotation_deg"', '"sites"',
         '"colour"', '"figure"', '"analysis"', '"hand"', '"load_kg"', '"reach"', '"km"', '"w"', '"left"',
         '"panel.obj"', '"desk.obj"', '"nosuch.obj"', '"/dev/zero"', '""', '"a.b"', '"base"', "[0,0,0]",
         "[[1]]", '{"x": 1}', "1e400"]


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    d = tmp_path_factory.mktemp("wpfuzz")
    for name in ("panel.obj", "desk.obj"):
        shutil.copy(EXAMPLES / name, d / name)
    (d / "seed.json").write_text(SCENE_TEXT)
    return d


def test_seed_loads_and_round_trips(folder: Path) -> None:
    wp = load_workplace(folder / "seed.json")
    assert set(wp.objects) == {"panel", "desk"} and wp.plan.load_kg == 5
    save_workplace(wp, folder / "again.json")
    again = load_workplace(folder / "again.json")
    assert set(again.objects) == {"panel", "desk"} and again.plan.reach == wp.plan.reach


@pytest.mark.timeout(60)
@FUZZ
@given(mutations(SCENE_TEXT, WORDS))
def test_mutated_scene(folder: Path, ops) -> None:
    path = folder / "fuzz.json"
    path.write_text(mutate(SCENE_TEXT, ops), encoding="utf-8", newline="")
    expect_only_project_errors(lambda: load_workplace(path), str(path))


@pytest.mark.timeout(60)
@FUZZ
@given(byte_mutations(SCENE_TEXT.encode()))
def test_byte_mutated_scene(folder: Path, ops) -> None:
    path = folder / "bytes.json"
    path.write_bytes(mutate_bytes(SCENE_TEXT.encode(), ops))
    expect_only_project_errors(lambda: load_workplace(path), str(path))


def _with(change) -> str:
    data = json.loads(SCENE_TEXT)
    change(data)
    return json.dumps(data)


@pytest.mark.parametrize("change, message", [
    (lambda d: d["objects"][1].update(units="km"), "objects[1].units: expected one of m, cm, mm, in, found 'km'"),
    (lambda d: d["objects"][0].update(up="w"), "objects[0].up: expected one of y, z, x"),
    (lambda d: d["objects"][0].pop("source"), "objects[0].source: missing"),
    (lambda d: d["objects"][0].update(source=3), "objects[0].source: expected a string, found 3"),
    (lambda d: d["objects"][0].update(position=[1, 2]), "objects[0].position: expected 3 numbers"),
    (lambda d: d["objects"][1].update(matrix=[[1, 0, 0]]), "objects[1].matrix: expected 4 rows"),
    (lambda d: d["objects"][1]["matrix"][2].__setitem__(1, "x"), "objects[1].matrix[2][1]: expected a number"),
    (lambda d: d["objects"][0]["sites"].update(knob=[1]), "objects[0].sites.knob: expected an object"),
    (lambda d: d["objects"][0].update(colour=[1, 1, 1e400]), "objects[0].colour[2]: expected a finite number"),
    (lambda d: d.update(objects={"a": 1}), "objects: expected a list"),
    (lambda d: d.update(objects=[3]), "objects[0]: expected an object"),
    (lambda d: d.update(figure=[]), "figure: expected an object"),
    (lambda d: d["figure"].update(heading_deg="north"), "figure.heading_deg: expected a number"),
    (lambda d: d["analysis"].update(hand="both"), "analysis.hand: expected one of right, left, found 'both'"),
    (lambda d: d["analysis"].update(load_kg=-1), "analysis.load_kg: expected a number in 0.., found -1"),
    (lambda d: d["analysis"].update(reach="desk.button"), "analysis.reach: expected a list"),
    (lambda d: d["analysis"]["view"].append(None), "analysis.view[1]: expected a string, found null"),
    (lambda d: d["objects"][1].update(name="panel"), "objects[1]: environment already has a figure named 'panel'"),
    (lambda d: d["objects"][0].update(source="nosuch.obj"), "objects[0]: "),
    (lambda d: d["objects"][0].update(source="/dev/zero"), "objects[0]: "),
    (lambda d: d["objects"][0]["sites"].update({"a.b": {}}), "objects[0]: "),
])
def test_schema_errors_name_the_key_path(folder: Path, change, message: str) -> None:
    path = folder / "schema.json"
    path.write_text(_with(change))
    with pytest.raises(SessionError) as info:
        load_workplace(path)
    check_error(info.value, str(path))
    assert f"{path}: {message}" in str(info.value)


def test_json_errors_have_line_and_column(folder: Path) -> None:
    path = folder / "syntax.json"
    path.write_text('{\n "jackpy_scene": 1,\n "objects": [}\n')
    with pytest.raises(SessionError, match=r"syntax\.json:3:14: expected JSON"):
        load_workplace(path)
    for data in (b'{"jackpy_scene": 1, "objects": ["\xff"]}', b"[" * 100000, b"1" * 5000, b""):
        path.write_bytes(data)
        with pytest.raises(SessionError) as info:
            load_workplace(path)
        check_error(info.value, str(path))
    path.write_bytes(b'{\n"jackpy_scene": 1, "objects": ["\xff"]}')
    with pytest.raises(SessionError, match=r"syntax\.json:2:33: expected UTF-8"):
        load_workplace(path)
    for bad in (folder / "nosuch.json", folder, str(folder / "a\x00b.json")):
        with pytest.raises(SessionError):
            load_workplace(bad)
