"""Fuzzing session sidecars (``NAME.jackpy.json`` beside ``NAME.env``) as ``load_session`` reads
them: mutated sidecars raise only the project's errors, naming the sidecar and the key path."""

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
from jackpy.peabody.reader import read_environment
from jackpy.ui.session import load_session

FIGURES = Path(__file__).resolve().parents[2] / "figures"
ENV_TEXT = 'include "chair.fig";\nplace chair at trans(10cm,0cm,0cm);\n'
WORDS = ['"figures"', '"chair"', '"q"', '"location"', '"root"', '"cad"', '"human"', '"goals"', '"camera"',
         '"settings"', '"format"', '"jackpy-session"', "[]", "{}", "[1,2]", '"x"', "1e400"]


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    d = tmp_path_factory.mktemp("sidefuzz")
    for name in ("chair.fig", "chair.pss"):
        shutil.copy(FIGURES / name, d / name)
    (d / "s.env").write_text(ENV_TEXT)
    return d


@pytest.fixture(scope="module")
def sidecar(folder: Path) -> str:
    chair = read_environment(folder / "s.env").figures["chair"]
    data = {"format": "jackpy-session", "version": 1, "settings": {},
            "camera": {"target": [0, 1, 0], "distance": 3.0, "yaw": 0.5, "pitch": 0.2, "orthographic": False},
            "figures": {"chair": {"q": chair.q.tolist(), "location": chair.location.reshape(-1).tolist(),
                                  "root": list(chair.root) if chair.root else None}},
            "behaviors": {},
            "goals": [{"key": "g1", "figure": "chair", "site": "seat", "kind": "position",
                       "target": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], "enabled": True, "weight": 1.0,
                       "priority": 0, "chain": None, "manip": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1],
                       "offset": [1, 0, 0, 0, 1, 0, 0, 0, 1]}]}
    text = json.dumps(data, indent=1)
    (folder / "s.jackpy.json").write_text(text)
    env, read = load_session(folder / "s.env")
    assert "chair" in env.figures and read["figures"]["chair"]["q"] == data["figures"]["chair"]["q"]
    return text


@pytest.mark.timeout(60)
@FUZZ
@given(ops=mutations('{"format": "jackpy-session", "figures": {"chair": {"q": [], "location": []}}}', WORDS))
def test_mutated_sidecar_small(folder: Path, sidecar: str, ops) -> None:
    seed = json.dumps({"format": "jackpy-session", "figures": json.loads(sidecar)["figures"]})
    (folder / "s.jackpy.json").write_text(mutate(seed, ops), encoding="utf-8", newline="")
    expect_only_project_errors(lambda: load_session(folder / "s.env"), str(folder))


@pytest.mark.timeout(60)
@FUZZ
@given(ops=mutations("x" * 400, WORDS))
def test_mutated_sidecar(folder: Path, sidecar: str, ops) -> None:
    (folder / "s.jackpy.json").write_text(mutate(sidecar, ops), encoding="utf-8", newline="")
    expect_only_project_errors(lambda: load_session(folder / "s.env"), str(folder))


@pytest.mark.timeout(60)
@FUZZ
@given(ops=byte_mutations(b"x" * 800))
def test_byte_mutated_sidecar(folder: Path, sidecar: str, ops) -> None:
    (folder / "s.jackpy.json").write_bytes(mutate_bytes(sidecar.encode(), ops))
    expect_only_project_errors(lambda: load_session(folder / "s.env"), str(folder))


@pytest.mark.parametrize("change, message", [
    (lambda d: d.update(figures=[]), "figures: expected an object"),
    (lambda d: d["figures"]["chair"].update(q="x"), "figures.chair.q: expected a list"),
    (lambda d: d["figures"]["chair"].update(location=[1, 2]), "figures.chair.location: expected 16 numbers"),
    (lambda d: d["figures"]["chair"].update(root=["a"]), "figures.chair.root: expected [SEGMENT, SITE]"),
    (lambda d: d["figures"]["chair"].update(cad={"source": 1}), "figures.chair.cad.source: expected a string"),
    (lambda d: d["figures"]["chair"].update(human={"sex": "x", "percentile": 5}), "figures.chair.human.sex"),
    (lambda d: d["goals"][0].update(target=[1]), "goals[0].target: expected 16 numbers"),
    (lambda d: d["goals"][0].pop("figure"), "goals[0].figure: missing"),
    (lambda d: d["camera"].update(distance="far"), "camera.distance: expected a number"),
])
def test_sidecar_errors_name_the_key_path(folder: Path, sidecar: str, change, message: str) -> None:
    data = json.loads(sidecar)
    change(data)
    (folder / "s.jackpy.json").write_text(json.dumps(data))
    with pytest.raises(SessionError) as info:
        load_session(folder / "s.env")
    check_error(info.value, "s.jackpy.json")
    assert message in str(info.value)


def test_sidecar_syntax_error_has_line_and_column(folder: Path, sidecar: str) -> None:
    (folder / "s.jackpy.json").write_text('{\n "format": "jackpy-session",\n "figures": {,}\n}\n')
    with pytest.raises(SessionError, match=r"s\.jackpy\.json:3:14: expected JSON"):
        load_session(folder / "s.env")
    (folder / "s.jackpy.json").write_bytes(b'{"format": "jackpy-session", "x": "\xfe"}')
    with pytest.raises(SessionError, match=r"s\.jackpy\.json:1:36: expected UTF-8"):
        load_session(folder / "s.env")
    (folder / "s.jackpy.json").write_text(sidecar)
