"""Fuzzing the Peabody reader: mutated table files only ever raise ParseError or FigureError."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from jackpy.errors import FigureError, ParseError
from jackpy.peabody.reader import parse_figures
from jackpy.peabody.writer import figures_to_text

TABLE = (Path(__file__).resolve().parents[2] / "figures" / "table.fig").read_text()
PIECES = re.findall(r"\s+|[A-Za-z_][A-Za-z0-9_]*|[0-9.]+|->|\S", TABLE)
SNIPPETS = ["figure", "segment", "joint", "group", "site", "->", "location", "trans(", "rotx(", "rot(", "R(",
            "T(", "matrix(", "scale(", "limit", "<=", ">=", "connect", "to", "type", "displacement", "lower",
            "upper", "root", "psurf", "angles", "joints", "driver", "1e308", "1e999", "-", "/*", "*/", '"', "//",
            "#", "\n", ",", ";", "{", "}", "(", ")", "=", "*", ".", "0", "-0", "inf", "nan", "cm", "deg", "rad",
            "mm", "x", "y", "z", "top", "leg", "leg0", "base", "٣", "é", "\x00", "\\"]

mutation = st.tuples(st.sampled_from(["insert", "delete", "replace", "dup"]), st.integers(0, len(PIECES) - 1),
                     st.one_of(st.sampled_from(SNIPPETS), st.text(max_size=3)))


def mutate(ops: list[tuple[str, int, str]]) -> str:
    pieces = list(PIECES)
    for op, k, payload in ops:
        k = min(k, len(pieces) - 1)
        if op == "insert":
            pieces.insert(k, payload)
        elif op == "delete" and pieces:
            del pieces[k]
        elif op == "replace":
            pieces[k] = payload
        else:
            pieces.insert(k, pieces[k])
        if not pieces:
            pieces = [""]
    return "".join(pieces)


@pytest.mark.timeout(60)
@settings(max_examples=400, deadline=1000, suppress_health_check=[HealthCheck.too_slow], database=None)
@given(st.lists(mutation, min_size=1, max_size=6))
def test_mutated_table_raises_only_format_errors(ops: list[tuple[str, int, str]]) -> None:
    text = mutate(ops)
    try:
        figures = parse_figures(text, "fuzz.fig")
    except (ParseError, FigureError) as exc:
        assert str(exc)
        return
    again = parse_figures(figures_to_text(figures), "again.fig")  # whatever reads also writes back
    assert [f.name for f in again] == [f.name for f in figures]


@settings(max_examples=200, deadline=1000, database=None)
@given(st.lists(st.sampled_from(SNIPPETS + [" ", "a", "1"]), max_size=60))
def test_random_token_soup(tokens: list[str]) -> None:
    try:
        parse_figures(" ".join(tokens), "soup.fig")
    except (ParseError, FigureError):
        pass
