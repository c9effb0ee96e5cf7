"""Fuzzing the Peabody reader and writer against the rule of issue 22 item 5:

- whatever the reader accepts, the writer writes and the reader reads back as the same figure;
- a value that would overflow is an error at its ``file:line:column``;
- every error of a user's file carries ``file:line:column`` (graph errors at the joint or site);
- no numpy warning reaches the user; ``info --json`` is always valid JSON;
- a 4-DOF joint is refused alike by the reader, ``info`` and ``convert``.

Inputs: mutations of the shipped figures (structure-aware pieces), and figures generated from
scratch with numbers up to the format's bounds (1e12 cm / deg). The regression cases are the
findings of the issue, verbatim.
"""

from __future__ import annotations

import json
import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from fuzz_helpers import FUZZ, mutate, mutations
from hypothesis import event, given, settings
from hypothesis import strategies as st

from jackpy.bench.cases_files import chain_fig_text
from jackpy.cli import main
from jackpy.commands.info import figure_summary
from jackpy.errors import FigureError, JackpyError, ParseError
from jackpy.peabody.compare import figure_differences
from jackpy.peabody.fastread import parse_fast
from jackpy.peabody.reader import parse_figures
from jackpy.peabody.writer import figures_to_text

FIGURES = Path(__file__).resolve().parents[2] / "figures"
SEEDS = {name: (FIGURES / name).read_text() for name in ("table.fig", "finger.fig", "arm7.fig", "planar_arm.fig")}
WORDS = ["1e308", "1e12", "999999999999", "1.7976931348623157e308", "1e-320", "R(x)", "R(1e308,1e308,0)",
         "* R(z)", "* R(x) * R(y)", "trans(1e308,0,0)", "* trans(1e11,0,0)", "scale(1e12,1e12,1e12)",
         "matrix(1e12,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1)", "root = nosuch.base;", "connect a.s to a.s;", "group",
         "limit", "<=", "displacement = (1e12);", "lower = (-1e12);", "upper = (1e12);", "human",
         'psurf = "../../../etc/passwd";', "driver = spine();", "driver = nosuch(a = 1);", "mass = 1e12kg;"]
POSITION = re.compile(r"^fuzz\.fig:\d+:\d+: ")


def _strict_parse(text: str):
    """Parse with every warning an error (numpy RuntimeWarnings must not reach the user)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return parse_figures(text, "fuzz.fig")


def _assert_round_trip(figures) -> None:
    """write -> read gives the same figures; the summary of each is valid JSON."""
    text = figures_to_text(figures)
    again = _strict_parse(text)
    assert [f.name for f in again] == [f.name for f in figures]
    for a, b in zip(figures, again):
        assert figure_differences(a, b, tol=1e-9, rtol=1e-12) == []
        json.dumps(figure_summary(b), allow_nan=False)
    assert figures_to_text(again) == text or all(  # the text is a fixed point up to float noise
        figure_differences(x, y, tol=1e-9, rtol=1e-12) == [] for x, y in zip(again, _strict_parse(figures_to_text(again))))


def _check(text: str) -> None:
    try:
        figures = _strict_parse(text)
    except (ParseError, FigureError) as exc:
        message = str(exc)
        assert "\n" not in message and POSITION.match(message), message
        assert "np.float64" not in message and "array(" not in message, message
        event("refused at a position")
        return
    event("accepted: written and read back")
    _assert_round_trip(figures)


@settings(FUZZ, max_examples=300)
@given(st.sampled_from(sorted(SEEDS)), st.data())
def test_mutated_figures_round_trip_or_fail_at_a_position(seed: str, data) -> None:
    _check(mutate(SEEDS[seed], data.draw(mutations(SEEDS[seed], WORDS))))


# ----- figures generated from scratch, with numbers up to the format's bounds -------------------------
BIG = st.one_of(st.floats(-1e12, 1e12, allow_nan=False, allow_infinity=False),
                st.sampled_from([0.0, -0.0, 1e-300, 5e-324, 5e11, -5e11, 1e12, 0.1, 1 / 3, 123456789.123456789]))
ANGLE = st.floats(-720, 720, allow_nan=False)
#: translations: a product of transforms may reach 5e11 cm (the writer's bound); 1 in 8 beyond it
SHIFT = st.integers(0, 7).flatmap(lambda k: BIG if k == 0 else st.floats(-2.5e11, 2.5e11, allow_nan=False))


def _num(v: float) -> str:
    return repr(float(v))


@st.composite
def generated_figure(draw) -> str:
    """A random tree figure as text: chain or branching joints of 1-3 DOFs, big numbers, psurf
    transforms with scale, a linear group, a root and a location."""
    nseg = draw(st.integers(1, 6))
    lines = ["figure g {"]
    for i in range(nseg):
        t = [draw(SHIFT) for _ in range(3)]
        ax = [draw(st.floats(-1e12, 1e12, allow_nan=False)) for _ in range(3)]
        if max(abs(a) for a in ax) < 1e-6:
            ax = [0.0, 0.0, 1.0]
        site = f"rot({','.join(map(_num, ax))},{_num(draw(ANGLE))}) * trans({','.join(map(_num, t))})"
        scale = [draw(st.floats(1e-3, 1e3)) for _ in range(3)]
        lines.append(f"segment s{i} {{ site a->location = {site}; site b->location = rotx({_num(draw(ANGLE))});"
                     f' psurf = "p.pss" * scale({",".join(map(_num, scale))}) * trans({_num(draw(SHIFT))},0,0);'
                     f" mass = {_num(abs(draw(BIG)))}kg; com = ({_num(draw(BIG))},0,0)cm; }}")
    ndofs = {}
    for i in range(1, nseg):
        parent = draw(st.integers(0, i - 1))
        ndof = ndofs[i] = draw(st.integers(1, 3))
        kinds = [draw(st.sampled_from(["R", "T"])) for _ in range(ndof)]
        axes = [draw(st.sampled_from(["x", "y", "z", "1,2,3", "1e12,-1e12,5"])) for _ in range(ndof)]
        lo = [-abs(draw(BIG)) for _ in range(ndof)]
        hi = [abs(draw(BIG)) for _ in range(ndof)]
        disp = [draw(st.floats(lo[k], hi[k], allow_nan=False)) if lo[k] < hi[k] else lo[k] for k in range(ndof)]
        lines.append(f"joint j{i} {{ connect s{parent}.b to s{i}.a; type = "
                     + " * ".join(f"{k}({a})" for k, a in zip(kinds, axes))
                     + f"; lower = ({','.join(map(_num, lo))}); upper = ({','.join(map(_num, hi))});"
                     + f" displacement = ({','.join(map(_num, disp))}); }}")
    if nseg > 1 and draw(st.booleans()):
        lines.append("group grp { joints = j1; angles = u; driver = matrix(" + ",".join(["(0.5)"] * ndofs[1])
                     + "); lower = (-10); upper = (10); limit 2*u <= 15; displacement = (3); }")
    lines.append(f"root = s0.a; location = roty({_num(draw(ANGLE))}) * trans({_num(draw(SHIFT))},0,0);")
    lines.append("}")
    return "\n".join(lines) + "\n"


@settings(FUZZ, max_examples=250)
@given(generated_figure())
def test_generated_figures_with_big_numbers_round_trip(text: str) -> None:
    _check(text)


# ----- the reader's fast path reads exactly what the token parser reads ------------------------------
def _written(text: str) -> str:
    return figures_to_text(parse_figures(text, "seed.fig", fast=False))


#: texts the fast path reads: shipped figures (their text and the writer's) and the bench's chain
FAST_SEEDS = {name: text for name, text in {**SEEDS, **{f"written {n}": _written(t) for n, t in SEEDS.items()},
                                            "chain": chain_fig_text(6)}.items()
              if parse_fast(text, name) is not None}
FAST_WORDS = WORDS + ["# c\n", "/* c */", "// c\n", "5cm", "2mm", "1in", "0.5rad", "10deg", "kg", "- 1", "+1", ".5",
                      "1e3", "1.e2", "* rotx(1)", "* R(y)", "trans(1,2,3)", "rot(0,0,1,5)", "site q->location = "
                      "trans(1,2,3);", "mass = 1;", "com = (1,2,3);", "segment z { }", "lower = (1);", "}"]


def _fast_agrees(text: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fast = parse_fast(text, "fuzz.fig")
    if fast is None:
        event("declined: the token parser reads it")
        return
    event("read by the fast path")
    slow = parse_figures(text, "fuzz.fig", fast=False)  # (it must accept what the fast path accepted)
    assert [f.name for f in fast] == [f.name for f in slow]
    for a, b in zip(fast, slow):
        assert figure_differences(a, b, tol=0.0) == []  # (every number bit for bit)
        assert list(a.segments) == list(b.segments) and list(a.joints) == list(b.joints)
        for name, seg in a.segments.items():
            assert list(seg.sites) == list(b.segments[name].sites)
            if seg.psurf is not None:
                assert seg.psurf.scale_text == b.segments[name].psurf.scale_text
                assert seg.psurf.origin.text() == b.segments[name].psurf.origin.text()


@settings(FUZZ, max_examples=300)
@given(st.sampled_from(sorted(FAST_SEEDS)), st.data())
def test_the_fast_path_reads_mutated_figures_as_the_token_parser_does(seed: str, data) -> None:
    _fast_agrees(mutate(FAST_SEEDS[seed], data.draw(mutations(FAST_SEEDS[seed], FAST_WORDS))))


@settings(FUZZ, max_examples=100)
@given(generated_figure())
def test_the_fast_path_reads_generated_figures_as_the_token_parser_does(text: str) -> None:
    _fast_agrees(text)


# ----- the findings of issue 22, item 5, as regression cases ------------------------------------------
TWO = ("figure f {\n segment a { site s->location = trans(0,0,0); }\n"
       " segment b { site s->location = trans(0,0,0); }\n")


@pytest.mark.parametrize("body, where, message", [
    (" segment c { site s->location = trans(1.79769313486232e308,0,0); }\n", "4:39", "out of range"),
    (" segment c { site s->location = trans(1e308,0,0)*trans(1e308,0,0); }\n", "4:39", "out of range"),
    (" segment c { site s->location = trans(9e11,0,0)*trans(9e11,0,0); }\n", "4:33", "transform out of range"),
    (" joint j { connect a.s to b.s; type = R(1e308,1e308,0); }\n", "4:41", "out of range"),
    (" joint j { connect a.s to b.s; type = R(x)*R(y)*R(z)*R(x); }\n", "4:32", "at most 3 per joint"),
    (" joint j { connect a.s to b.s; type = R(0,0,0); }\n", "4:41", "DOF axis has no direction"),
    (" joint j { connect a.s to b.nope; type = R(z); }\n", "4:20", "unknown site b.nope"),
    (" joint j { connect a.s to b.s; } joint k { connect b.s to a.s; }\n", "4:40", "closes a cycle"),
    (" root = a.nope;\n", "4:9", "root names unknown site a.nope"),
    (" segment c { }\n", "3:10", "segment 'b' is not joined"),
])
def test_issue_22_findings_are_errors_at_their_position(body: str, where: str, message: str) -> None:
    with pytest.raises(JackpyError) as info:
        _strict_parse(TWO + body + "}\n")
    text = str(info.value)
    assert text.startswith(f"fuzz.fig:{where}: ") and message in text, text
    assert "np.float64" not in text


def test_the_largest_accepted_numbers_write_and_read_back_exactly() -> None:
    text = TWO + (" segment c { site s->location = trans(5e11,-5e11,499999999999.9999); mass = 1e12kg; }\n"
                  " joint j { connect a.s to b.s; type = R(1e12,1e12,0) * T(z); lower = (-1e12, -1e12);"
                  " upper = (1e12, 1e12); displacement = (1e12, 0.1); }\n"
                  " joint k { connect b.s to c.s; type = R(x); }\n}\n")
    figures = _strict_parse(text)
    _assert_round_trip(figures)
    again = _strict_parse(figures_to_text(figures))[0]
    assert again.segment("c").mass == 1e12
    assert math.isclose(again.segment("c").site("s").location[0, 3], 5e9, rel_tol=1e-15)


def test_info_and_convert_agree_with_the_reader_on_4_dof_joints(tmp_path: Path, capsys) -> None:
    bad = tmp_path / "four.fig"
    bad.write_text(TWO + " joint j { connect a.s to b.s; type = R(x)*R(y)*R(z)*R(x); }\n}\n")
    expected = f"{bad}:4:32: figure 'f' joint 'j': 4 DOFs; at most 3 per joint"
    for argv in (["info", str(bad)], ["info", "--json", str(bad)], ["convert", str(bad), str(tmp_path / "o.fig")]):
        assert main(argv) == 2
        captured = capsys.readouterr()
        assert expected in captured.err and captured.out == ""
    assert not (tmp_path / "o.fig").exists()


def test_info_json_is_valid_for_figures_at_the_bounds(tmp_path: Path, capsys) -> None:
    far = tmp_path / "far.fig"
    chain = "".join(f" segment s{i} {{ site a->location = trans(0,0,0); site b->location = trans(5e11,5e11,5e11); }}\n"
                    for i in range(30))
    joints = "".join(f" joint j{i} {{ connect s{i}.b to s{i + 1}.a; type = T(x); }}\n" for i in range(29))
    far.write_text("figure far {\n" + chain + joints + "}\n")
    assert main(["info", "--json", "--no-geometry", str(far)]) == 0
    out = capsys.readouterr()
    doc = json.loads(out.out)  # (json.loads accepts NaN; the strict check follows)
    json.dumps(doc, allow_nan=False)
    assert out.err == "" and doc["figures"][0]["bounds_cm"]["max"][0] == pytest.approx(30 * 5e11, rel=1e-9)
    assert np.isfinite(doc["figures"][0]["mass_kg"])
