"""Fuzzing ``.env`` environments (includes, place, inline figures) and ``.pss`` psurf files read
from disk: mutated input only ever raises the project's errors, with ``file:line:column``."""

from __future__ import annotations

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
from hypothesis import strategies as st

from jackpy.errors import FigureError, ParseError
from jackpy.peabody.psurf_io import load_mesh, parse_psurf, read_psurf
from jackpy.peabody.reader import parse_environment, read_environment

FIGURES = Path(__file__).resolve().parents[2] / "figures"
ENV_TEXT = (FIGURES / "workplace.env").read_text()
PSS_TEXT = "# a unit cube corner\nv 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 0 10\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
ENV_WORDS = ["include", "place", "at", "figure", "segment", "site", "psurf", '"cube.pss"', '"chair.fig"',
             '"nosuch.fig"', '"/dev/null"', '""', "trans(", "roty(", "scale(", "crate", "chair", "arm7", "->",
             "location", "root", "mass", "kg", "cm", "deg"]


@pytest.fixture(scope="module")
def figdir(tmp_path_factory) -> Path:
    d = tmp_path_factory.mktemp("envfuzz")
    for name in ("worktable.fig", "chair.fig", "arm7.fig", "worktable.pss", "chair.pss", "cube.pss", "link.pss",
                 "leg.pss"):
        if (FIGURES / name).exists():
            shutil.copy(FIGURES / name, d / name)
    (d / "small.pss").write_text(PSS_TEXT)
    (d / "latin1.fig").write_bytes("figure caf\xe9 { }\n".encode("latin-1"))
    (d / "sub").mkdir()
    return d


def test_seed_reads(figdir: Path) -> None:
    (figdir / "seed.env").write_text(ENV_TEXT)
    env = read_environment(figdir / "seed.env")
    assert {"worktable", "chair", "arm7", "crate"} <= set(env.figures)


@pytest.mark.timeout(60)
@FUZZ
@given(mutations(ENV_TEXT, ENV_WORDS))
def test_mutated_env_raises_only_project_errors(figdir: Path, ops) -> None:
    path = figdir / "fuzz.env"
    path.write_text(mutate(ENV_TEXT, ops), encoding="utf-8", newline="")
    expect_only_project_errors(lambda: read_environment(path), str(figdir), position=True)


@pytest.mark.timeout(60)
@FUZZ
@given(byte_mutations(ENV_TEXT.encode()))
def test_byte_mutated_env(figdir: Path, ops) -> None:
    path = figdir / "bytes.env"
    path.write_bytes(mutate_bytes(ENV_TEXT.encode(), ops))
    expect_only_project_errors(lambda: read_environment(path, require_geometry=False), str(figdir), position=True)


@pytest.mark.timeout(30)
@pytest.mark.parametrize("name", ["", ".", "sub", "/", "nosuch.fig", "a\x00b.fig", "small.pss", "latin1.fig",
                                  "/dev/null", "/dev/zero", "/proc/self/fd/0", "../" * 40 + "x.fig", "x" * 5000])
def test_include_of_anything(figdir: Path, name: str) -> None:
    """An include naming no readable figure file -- a folder, a device, a missing or binary file,
    a name with a NUL byte -- is a one-line error at the include, never a hang."""
    text = f'include "{name}";\n'
    with pytest.raises((ParseError, FigureError)) as info:
        parse_environment(text, "inc.env", figdir)
    check_error(info.value, "inc.env" if name not in ("small.pss", "latin1.fig") else str(figdir))


@pytest.mark.timeout(30)
@pytest.mark.parametrize("name", ["a\x00b.pss", "sub", "/dev/zero", "latin1.fig", "x" * 5000])
def test_psurf_name_of_anything(figdir: Path, name: str) -> None:
    """A segment's psurf naming a folder, a device or an unreadable file is a one-line error."""
    (figdir / "ps.env").write_text(f'figure f {{ segment s {{ psurf = "{name}"; }} }}\n')
    expect_only_project_errors(lambda: read_environment(figdir / "ps.env"), str(figdir / "ps.env"))


def test_deeply_nested_and_long_input(figdir: Path) -> None:
    for text in ["(" * 100000, "figure f { segment s { site a->location = " + "trans(1,2,3) * " * 2000 + "trans(0,0,0); } }",
                 "place crate at " + "rotx(1)*" * 3000, "/*" * 10000, '"' + "a" * 100000]:
        (figdir / "deep.env").write_text(text)
        expect_only_project_errors(lambda: read_environment(figdir / "deep.env"), str(figdir), position=True)


# ------------------------------------------------------------------------------------ .pss
PSS_WORDS = ["v", "f", "1", "2", "3", "4", "5", "0", "-1", "1e999", "nan", "1_0", "٣", "0x10", "+1"]


@pytest.mark.timeout(60)
@FUZZ
@given(mutations(PSS_TEXT, PSS_WORDS))
def test_mutated_psurf(figdir: Path, ops) -> None:
    path = figdir / "fuzz.pss"
    path.write_text(mutate(PSS_TEXT, ops), encoding="utf-8", newline="")
    mesh = expect_only_project_errors(lambda: load_mesh(path), str(path), position=True)
    if mesh is not None:
        assert mesh.faces.size == 0 or mesh.faces.max() < len(mesh.vertices)


@pytest.mark.timeout(60)
@FUZZ
@given(byte_mutations(PSS_TEXT.encode()))
def test_byte_mutated_psurf(figdir: Path, ops) -> None:
    path = figdir / "bytes.pss"
    path.write_bytes(mutate_bytes(PSS_TEXT.encode(), ops))
    expect_only_project_errors(lambda: read_psurf(path), str(path), position=True)


def test_psurf_positions_count_newlines_only() -> None:
    """Line numbers are what an editor shows: only ``\\n`` ends a line (not form feeds, U+2028...)."""
    with pytest.raises(ParseError) as info:
        parse_psurf("v 0 0 0 \x0c\nv 1 1 1\u2028\nq\n", "sep.pss")
    assert (info.value.line, info.value.column) == (3, 1)
    with pytest.raises(ParseError) as info:
        parse_psurf("v 0 0 0\nf 1 1 " + "9" * 5000 + "\n", "big.pss")
    assert (info.value.line, info.value.column) == (2, 7)


def test_psurf_not_utf8(tmp_path: Path) -> None:
    path = tmp_path / "bin.pss"
    path.write_bytes(b"v 0 0 0\nv 1 \xff 0\n")
    with pytest.raises(ParseError) as info:
        read_psurf(path)
    assert (info.value.line, info.value.column) == (2, 5)


@pytest.mark.timeout(30)
@given(st.text(max_size=200))
@FUZZ
def test_psurf_random_text(text: str) -> None:
    expect_only_project_errors(lambda: parse_psurf(text, "rand.pss"), "rand.pss", position=True)
