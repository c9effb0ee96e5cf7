"""The reader's fast path (jackpy.peabody.fastread) against the token parser it stands in for."""

from __future__ import annotations

from pathlib import Path

import pytest

import jackpy.body  # noqa: F401  (registers the standard human's group drivers)
from jackpy.bench.cases_files import chain_fig_text
from jackpy.errors import FigureError, ParseError
from jackpy.peabody.compare import figure_differences
from jackpy.peabody.fastread import parse_fast
from jackpy.peabody.reader import parse_figures, read_text
from jackpy.peabody.writer import figures_to_text

FIGURES = Path(__file__).resolve().parents[2] / "figures"


def assert_identical(fast: list, slow: list) -> None:
    """The same figures, every number bit for bit, the same orders, psurf texts and positions."""
    assert [f.name for f in fast] == [f.name for f in slow]
    for a, b in zip(fast, slow):
        assert figure_differences(a, b, tol=0.0) == []
        assert list(a.segments) == list(b.segments) and list(a.joints) == list(b.joints)
        for name, seg in a.segments.items():
            other = b.segments[name]
            assert list(seg.sites) == list(other.sites)
            if seg.psurf is not None:
                assert seg.psurf.scale_text == other.psurf.scale_text
                assert seg.psurf.origin.text() == other.psurf.origin.text()


def _both(text: str, filename: str = "t.fig") -> tuple[list | None, list]:
    return parse_fast(text, filename), parse_figures(text, filename, fast=False)


@pytest.mark.parametrize("name", ["arm7.fig", "chair.fig", "hexapod.fig", "planar_arm.fig", "table.fig",
                                  "worktable.fig"])
def test_shipped_figures_and_their_written_text_read_fast_and_identically(name: str) -> None:
    text = read_text(FIGURES / name)
    fast, slow = _both(text, name)
    assert fast is not None
    assert_identical(fast, slow)
    written = figures_to_text(slow)
    fast, again = _both(written, name)
    assert fast is not None
    assert_identical(fast, again)


def test_the_bench_chain_reads_fast_and_identically() -> None:
    fast, slow = _both(chain_fig_text(40))
    assert fast is not None and len(fast[0].segments) == 40
    assert_identical(fast, slow)


def test_comments_spacing_units_and_general_forms_read_fast() -> None:
    text = """# a comment line
    figure f { // another
      segment a /* inline */ { psurf = "geo/a.pss" * scale(2,2,2) * trans(1mm, 0, 0); attribute = "red x";
        mass = 2 kg ; com = (1cm, 2 mm, 3)in; inertia = (1, 2, 3, 0.1, 0.2, 0.3);  # kg cm^2
        site base->location = trans(0,0,0);
        site tip ->location = roty(0.5 rad) * trans(1 m, - 2cm, 3);
        site m->location = matrix(1,0,0,0, 0,1,0,0, 0,0,1,0, 5,6,7,1) * rotz(10deg);
      }
      segment b { site base->location = rot(0, 0, 2, 45) * trans(1cm, 2cm, 3cm); }
      joint j { connect a.tip to b.base; type = R(1, 1, 0) * T(z); lower = (-10deg, -5)mm; upper = (10deg, 5);
                displacement = (0.1rad, 0); }
      root = a.base; location = rotx(-30) * trans(0, 100, 0);
    }
    figure g { segment only { } }
    """
    fast, slow = _both(text)
    assert fast is not None
    assert_identical(fast, slow)
    assert fast[0].segments["a"].psurf.origin.text() == "t.fig:3:40"


@pytest.mark.parametrize("name", ["human/male_p50.fig", "finger.fig"])
def test_groups_and_human_markers_go_to_the_token_parser(name: str) -> None:
    text = read_text(FIGURES / name)
    assert parse_fast(text, name) is None
    assert parse_figures(text, name)  # (and read there)


@pytest.mark.parametrize("body, where, message", [
    ("segment a { site s->location = trans(1,2,3); site s->location = trans(0,0,0); }", "1:62",
     "duplicate site 's'"),
    ("segment a { mass = -1kg; }", "1:31", "mass must not be negative"),
    ("segment a { site s->location = trans(1e12in,0,0); }", "1:49", "out of range"),
    ("segment a { site s->location = scale(1,1,1); }", "1:43", "must be rigid"),
    ("segment a { site s->location = trans(1,2,3) }", "1:56", "expected ';'"),
    ("segment a { site s->location = trans(1,2,3); } joint j { connect a.s to a.s; type = R(x); }", "1:77",
     "to itself"),
    ("segment a { site s; }", "1:30", "expected '->location'"),
    ("segment a { site s->location = trans(1,2,3); /* never closed }", "1:57", "unterminated comment"),
])
def test_errors_are_the_token_parsers_at_their_position(body: str, where: str, message: str) -> None:
    text = f"figure f {{ {body} }}"
    assert parse_fast(text, "bad.fig") is None
    with pytest.raises((ParseError, FigureError)) as err:
        parse_figures(text, "bad.fig")
    assert str(err.value).startswith(f"bad.fig:{where}: ") and message in str(err.value), str(err.value)
