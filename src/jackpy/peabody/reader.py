"""Reader of Peabody text: ``.fig`` files (figures) and ``.env`` files (an environment).

The grammar, units and product rule are documented in docs/peabody-format.md. Values in files are
centimetres and degrees; the figures built here are in metres and radians with 4x4 column-vector
transforms. Every error in a user's file names the file, line and column: a syntax error raises
:class:`ParseError` (``file:line:column: expected ...``); a semantic one (unknown site, self-joint,
cycle, displacement outside limits, wrong value count...) raises :class:`FigureError`
``file:line:column: figure 'f' joint 'j': ...`` at the token of the part at fault (for graph errors
the joint's name, the segment's name or the root). Numbers are bounded
(:data:`~jackpy.peabody.lexer.MAX_MAGNITUDE`), so whatever the reader accepts the writer can write
and the reader reads back. Well-formed ``.fig`` text (and each included file) is first offered to
:mod:`jackpy.peabody.fastread`, which builds the same figures without listing tokens; what it
declines is read by the token parser here, the one place errors come from.

Relative ``psurf`` file names in the returned figures are relative to the directory of the file
that was read (for an environment: the ``.env`` file, so names from included figure files are
rewritten accordingly). Referenced files are contained (:mod:`jackpy.peabody.paths`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from jackpy.errors import FigureError, ImportCADError, ParseError
from jackpy.peabody.fastread import parse_fast
from jackpy.peabody.geometry import Mesh, Psurf, SourcePosition
from jackpy.peabody.groups import DRIVER_KINDS, DriverParam, JointGroup, LinearDriver, known_driver, make_driver
from jackpy.peabody.kinematics import MAX_JOINT_DOFS
from jackpy.peabody.lexer import EOF, IDENT, MAX_MAGNITUDE, NUMBER, STRING, TokenStream, string_value
from jackpy.peabody.model import (
    DEFAULT_ROTATION_LIMITS,
    DEFAULT_TRANSLATION_LIMITS,
    Dof,
    Environment,
    Figure,
    HumanMarker,
    Joint,
    Segment,
)
from jackpy.peabody.notation import (
    ANGLE_UNITS,
    CM,
    DEG,
    LENGTH_UNITS,
    PRIM_ARGS,
    Prim,
    bounded_compose,
    is_rigid_prim,
)
from jackpy.peabody.paths import MAX_MESH_BYTES, MAX_TEXT_BYTES, PathPolicy, read_limited
from jackpy.peabody.psurf_io import load_mesh
from jackpy.peabody.transforms import AXES

#: a value as written: number, its unit token index (or -1) and the index of its first token
_Value = tuple[float, int, int]
_UNITS = frozenset([*LENGTH_UNITS, *ANGLE_UNITS])
_ALL_UNITS = ", ".join([*LENGTH_UNITS, *ANGLE_UNITS])
_PRIMS = "a transform (trans, scale, rotx, roty, rotz, rot, matrix)"
#: the fast path of :meth:`_Parser.prim` takes values up to this; others go the checked way
_FAST_MAX = MAX_MAGNITUDE
_DIGITS = frozenset("0123456789")
_IDSTART = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_")
_JOINT_KEYS = {"connect": "connect", "type": "type", "displacement": "displacement", "lower": "lower",
               "upper": "upper", "lower_limits": "lower", "upper_limits": "upper"}
#: ``R(x)``-style DOFs: (kind, axis name) -> the unit axis (a fresh copy is made per DOF)
_NAMED_DOFS = {(kind, name): axis for kind in ("R", "T") for name, axis in AXES.items()}


@dataclass
class _JointSpec:
    name: int
    connect: tuple[str, str, str, str] | None = None
    connect_at: int = -1
    dofs: list[tuple[str, np.ndarray]] = field(default_factory=list)
    type_at: int = -1
    values: dict[str, tuple[int, list[_Value]]] = field(default_factory=dict)


@dataclass
class _GroupSpec:
    name: int
    joints: list[int] = field(default_factory=list)
    angles: list[int] = field(default_factory=list)
    driver: tuple[int, str, list[list[float]] | dict[str, DriverParam]] | None = None
    values: dict[str, tuple[int, list[_Value]]] = field(default_factory=dict)
    limits: list[tuple[list[tuple[float, int]], float]] = field(default_factory=list)


@dataclass
class _Positions:
    """Token indices of a figure's parts, for errors found once the figure is built."""

    figure: int
    segments: dict[str, int] = field(default_factory=dict)
    joints: dict[str, _JointSpec] = field(default_factory=dict)
    root: int = -1


class _Parser:
    """Recursive-descent parser over a token stream; builds figures as it goes."""

    def __init__(self, text: str, filename: str) -> None:
        self.file = filename
        self.ts = TokenStream(text, filename)
        self.positions: dict[str, _Positions] = {}

    # ----- small helpers ----------------------------------------------------------------------
    def fig_error(self, index: int, message: str) -> FigureError:
        line, col = self.ts.position(index)
        return FigureError(f"{self.file}:{line}:{col}: {message}")

    def text(self, index: int) -> str:
        return self.ts.tokens[index]

    def ident(self, what: str) -> int:
        return self.ts.expect_kind(IDENT, what)

    def name(self, what: str) -> tuple[str, int]:
        k = self.ts.expect_kind(IDENT, what)
        return self.ts.tokens[k], k

    def end(self) -> None:
        self.ts.expect(";")

    def quantity(self) -> _Value:
        """A number with an optional unit identifier (``5.00cm``, ``30 deg``)."""
        start = self.ts.pos
        value = self.ts.number()
        unit = -1
        if self.ts.kind() == IDENT:
            unit = self.ts.next()
            if self.ts.tokens[unit] not in _UNITS:
                raise self.ts.error(f"expected a unit ({_ALL_UNITS})", unit)
        return value, unit, start

    def convert(self, v: _Value, units: dict[str, float], what: str) -> float:
        """A value in the file's default unit of ``units`` (cm or deg); a wrong unit is an error."""
        value, unit, start = v
        if unit >= 0:
            name = self.ts.tokens[unit]
            if name not in units:
                raise self.fig_error(unit, f"{what}: expected a unit among {', '.join(units)}, found {name!r}")
            value *= units[name]
        return self.ts.check_range(value, start, what)

    def value_list(self) -> list[_Value]:
        """``"(" quantity {"," quantity} ")" [unit]``; a trailing unit applies to bare numbers.
        Plain numbers with at most a trailing unit take a fast pass; the rest :meth:`value_list_checked`."""
        ts = self.ts
        toks, k = ts.tokens, ts.pos
        if toks[k] != "(":
            return self.value_list_checked()
        j = k + 1
        values: list[_Value] = []
        while True:
            start = j
            t = toks[j]
            sign = 1.0
            if t == "-":
                sign, j = -1.0, j + 1
                t = toks[j]
            if not t or t[0] not in _DIGITS:
                return self.value_list_checked()
            v = float(t) * sign
            if not -_FAST_MAX <= v <= _FAST_MAX:
                return self.value_list_checked()
            values.append((v, -1, start))
            j += 1
            t = toks[j]
            if t == ",":
                j += 1
                continue
            if t != ")":
                return self.value_list_checked()
            break
        j += 1
        t = toks[j]
        if t and t[0] in _IDSTART:
            if t not in _UNITS:
                return self.value_list_checked()
            values = [(v, j, i) for v, _, i in values]
            j += 1
        ts.pos = j
        return values

    def value_list_checked(self) -> list[_Value]:
        ts = self.ts
        ts.expect("(")
        values = [self.quantity()]
        while ts.accept(","):
            values.append(self.quantity())
        ts.expect(")", "',' or ')'")
        if ts.kind() == IDENT:
            unit = ts.next()
            if ts.tokens[unit] not in _UNITS:
                raise ts.error("expected a unit or ';'", unit)
            values = [(v, u if u >= 0 else unit, t) for v, u, t in values]
        return values

    def number_list(self) -> list[float]:
        """``"(" number {"," number} ")"``."""
        ts = self.ts
        ts.expect("(")
        values = [ts.number()]
        while ts.accept(","):
            values.append(ts.number())
        ts.expect(")", "',' or ')'")
        return values

    def prim(self) -> tuple[Prim, int]:
        """One transform primitive; the common, well-formed case in one pass over the tokens, the
        rest (and every error) by :meth:`prim_checked`."""
        ts = self.ts
        toks, k = ts.tokens, ts.pos
        name = toks[k]
        kinds = PRIM_ARGS.get(name)
        if kinds is None or toks[k + 1] != "(":
            return self.prim_checked()
        j = k + 2
        args = []
        for idx, kind in enumerate(kinds):
            if idx:
                if toks[j] != ",":
                    return self.prim_checked()
                j += 1
            t = toks[j]
            sign = 1.0
            if t == "-":
                sign, j = -1.0, j + 1
                t = toks[j]
            if not t or t[0] not in _DIGITS:
                return self.prim_checked()
            v = float(t) * sign
            j += 1
            if kind != "N":
                u = toks[j]
                if u and u[0] in _IDSTART:
                    factor = (LENGTH_UNITS if kind == "L" else ANGLE_UNITS).get(u)
                    if factor is None:
                        return self.prim_checked()
                    v *= factor
                    j += 1
            if not -_FAST_MAX <= v <= _FAST_MAX:  # (also false for NaN)
                return self.prim_checked()
            args.append(v)
        if toks[j] != ")" or (name == "rot" and max(abs(args[0]), abs(args[1]), abs(args[2])) < 1e-12):
            return self.prim_checked()
        ts.pos = j + 1
        return (name, tuple(args)), k

    def prim_checked(self) -> tuple[Prim, int]:
        ts = self.ts
        k = ts.pos
        name = ts.tokens[k]
        kinds = PRIM_ARGS.get(name)
        if kinds is None:
            raise ts.error(f"expected {_PRIMS}")
        ts.pos = k + 1
        ts.expect("(")
        args = []
        for j, kind in enumerate(kinds):
            if j:
                ts.expect(",")
            if kind == "N":
                args.append(ts.number())
            else:
                args.append(self.convert(self.quantity(), LENGTH_UNITS if kind == "L" else ANGLE_UNITS,
                                         f"argument {j + 1} of {name}"))
        ts.expect(")")
        if name == "rot" and max(abs(a) for a in args[:3]) < 1e-12:
            raise self.fig_error(k, "rot(...) axis has no direction")
        return (name, tuple(args)), k

    def xform(self, rigid: bool) -> tuple[list[Prim], np.ndarray]:
        """``prim {"*" prim}`` and its matrix; with ``rigid`` only rotations and translations are
        allowed. The product must stay within range (its writer form too)."""
        prims = []
        first = self.ts.pos
        while True:
            prim, k = self.prim()
            if rigid and not is_rigid_prim(prim):
                raise self.fig_error(k, f"a location must be rigid (trans, rot...), not {prim[0]}(...)")
            prims.append(prim)
            if not self.ts.accept("*"):
                break
        m = bounded_compose(prims)
        if m is None:
            raise ParseError("transform out of range (entries at most 5e11, translations at most 5e11 cm)",
                             self.file, *self.ts.position(first))
        return prims, m

    def siteref(self) -> tuple[str, str]:
        toks, k = self.ts.tokens, self.ts.pos
        if toks[k + 1] == "." and toks[k][:1] in _IDSTART and toks[k + 2][:1] in _IDSTART:
            self.ts.pos = k + 3  # (SEGMENT.SITE in one look)
            return toks[k], toks[k + 2]
        seg = self.text(self.ident("a site reference SEGMENT.SITE"))
        self.ts.expect(".", "'.' in SEGMENT.SITE")
        return seg, self.text(self.ident("a site name after '.'"))

    def name_list(self) -> list[int]:
        names = [self.ident("a name")]
        while self.ts.accept(","):
            names.append(self.ident("a name"))
        return names

    # ----- files ------------------------------------------------------------------------------
    def figure_file(self) -> list[Figure]:
        """``{ figure }``."""
        figures: list[Figure] = []
        names: set[str] = set()
        while self.ts.kind() != EOF:
            at = self.ts.pos + 1
            fig = self.figure()
            if fig.name in names:
                raise self.fig_error(at, f"duplicate figure {fig.name!r}")
            names.add(fig.name)
            figures.append(fig)
        return figures

    def figure(self) -> Figure:
        """``"figure" IDENT "{" { segment | joint | group | root | location | human } "}"``."""
        ts = self.ts
        ts.expect("figure")
        name, at = self.name("a figure name")
        fig = Figure(name)
        pos = _Positions(at)
        ts.expect("{")
        joints: list[_JointSpec] = []
        groups: list[_GroupSpec] = []
        seen: set[str] = set()
        while not ts.accept("}"):
            k = ts.pos
            word = ts.tokens[k]
            if word == "segment":
                ts.pos = k + 1
                self.segment(fig, pos)
            elif word == "joint":
                ts.pos = k + 1
                joints.append(self.joint(fig))
            elif word == "group":
                ts.pos = k + 1
                groups.append(self.group())
            elif word in ("root", "location", "human"):
                ts.pos = k + 1
                if word in seen:
                    raise self.fig_error(k, f"figure {fig.name!r}: {word} given twice")
                seen.add(word)
                if word == "human":
                    fig.human = self.human(fig)
                    continue
                ts.expect("=")
                if word == "root":
                    pos.root = ts.pos
                    fig.root = self.siteref()
                else:
                    fig.location = self.xform(rigid=True)[1]
                self.end()
            else:
                raise ts.error("expected 'segment', 'joint', 'group', 'root', 'location', 'human' or '}'")
        for spec in joints:
            self.build_joint(fig, spec)
            pos.joints[self.text(spec.name)] = spec
        for gspec in groups:
            self.build_group(fig, gspec)
        self.check_graph(fig, pos)
        self.positions[fig.name] = pos
        return fig

    def segment(self, fig: Figure, pos: _Positions) -> None:
        ts = self.ts
        name, at = self.name("a segment name")
        if name in fig.segments:
            raise self.fig_error(at, f"figure {fig.name!r}: duplicate segment {name!r}")
        seg = fig.add_segment(Segment(name))
        pos.segments[name] = at
        where = f"figure {fig.name!r} segment {seg.name!r}"
        ts.expect("{")
        seen: set[str] = set()
        while not ts.accept("}"):
            k = ts.pos
            word = ts.tokens[k]
            if word == "site":
                toks = ts.tokens
                site, sat = toks[k + 1], k + 1
                if toks[k + 2] == "->" and toks[k + 3] == "location" and toks[k + 4] == "=" and site[:1] in _IDSTART:
                    ts.pos = k + 5  # (the whole head in one look)
                else:
                    ts.pos = k + 1
                    site, sat = self.name("a site name")
                    ts.expect("->", "'->location'")
                    ts.expect("location", "'location' after '->'")
                    ts.expect("=")
                if site in seg.sites:
                    raise self.fig_error(sat, f"{where}: duplicate site {site!r}")
                seg.add_site(site, self.xform(rigid=True)[1])
                self.end()
                continue
            if word not in ("psurf", "attribute", "mass", "com", "inertia"):
                raise ts.error("expected 'psurf', 'attribute', 'site', 'mass', 'com', 'inertia' or '}'")
            ts.pos = k + 1
            if word in seen:
                raise self.fig_error(k, f"{where}: {word} given twice")
            seen.add(word)
            ts.expect("=")
            if word == "psurf":
                sk = ts.expect_kind(STRING, "a quoted geometry file name")
                prims, m = self.xform(rigid=False) if ts.accept("*") else ([], np.eye(4))
                seg.psurf = Psurf(string_value(ts.tokens[sk]), m, scale_text=prims,
                                  origin=SourcePosition(self.file, ts.text, sk))
            elif word == "attribute":
                kind = ts.kind()
                if kind not in (IDENT, STRING):
                    raise ts.error("expected an attribute name")
                a = ts.tokens[ts.next()]
                seg.attribute = string_value(a) if kind == STRING else a
            elif word == "mass":
                start = ts.pos
                seg.mass = ts.number()
                if ts.kind() == IDENT:
                    ts.expect("kg", "'kg' or ';'")
                if seg.mass < 0:
                    raise self.fig_error(start, f"{where}: mass must not be negative")
            elif word == "com":
                values = self.value_list()
                if len(values) != 3:
                    raise self.fig_error(k, f"{where}: com needs 3 values, got {len(values)}")
                bare = [v for v, u, _ in values if u < 0 and -MAX_MAGNITUDE <= v <= MAX_MAGNITUDE]
                seg.com = np.array(bare if len(bare) == 3 else
                                   [self.convert(v, LENGTH_UNITS, "com") for v in values]) * CM
            else:
                values = self.number_list()
                if len(values) != 6:
                    raise self.fig_error(k, f"{where}: inertia needs 6 values (ixx,iyy,izz,ixy,ixz,iyz), "
                                            f"got {len(values)}")
                ixx, iyy, izz, ixy, ixz, iyz = (v * CM * CM for v in values)
                seg.inertia = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
            self.end()

    def joint(self, fig: Figure) -> _JointSpec:
        ts = self.ts
        spec = _JointSpec(self.ident("a joint name"))
        jname = self.text(spec.name)
        ts.expect("{")
        seen: set[str] = set()
        while not ts.accept("}"):
            k = ts.pos
            word = ts.tokens[k]
            key = _JOINT_KEYS.get(word)
            if key is None:
                raise ts.error("expected 'connect', 'type', 'displacement', 'lower', 'upper' or '}'")
            ts.pos = k + 1
            if key in seen:
                raise self.fig_error(k, f"figure {fig.name!r} joint {jname!r}: {key} given twice")
            seen.add(key)
            if key == "connect":
                spec.connect_at = ts.pos
                a = self.siteref()
                ts.expect("to", "'to'")
                spec.connect = (*a, *self.siteref())
            elif key == "type":
                ts.expect("=")
                spec.type_at = k
                spec.dofs.append(self.dof())
                while ts.accept("*"):
                    spec.dofs.append(self.dof())
                if len(spec.dofs) > MAX_JOINT_DOFS:
                    raise self.fig_error(k, f"figure {fig.name!r} joint {jname!r}: {len(spec.dofs)} DOFs; at "
                                            f"most {MAX_JOINT_DOFS} per joint (chain joints for more)")
            else:
                ts.expect("=")
                spec.values[key] = (k, self.value_list())
            self.end()
        return spec

    def dof(self) -> tuple[str, np.ndarray]:
        """``("R" | "T") "(" ("x" | "y" | "z" | number "," number "," number) ")"``."""
        ts = self.ts
        toks, k = ts.tokens, ts.pos
        axis = _NAMED_DOFS.get((toks[k], toks[k + 2])) if toks[k + 1] == "(" and toks[k + 3] == ")" else None
        if axis is not None:  # (the common R(x) form in one look)
            ts.pos = k + 4
            return toks[k], axis.copy()
        kind = ts.peek()
        if kind not in ("R", "T"):
            raise ts.error("expected a DOF R(axis) or T(axis)")
        ts.next()
        ts.expect("(")
        if ts.peek() in AXES:
            axis = AXES[ts.peek()].copy()
            ts.next()
        else:
            start = ts.pos
            xyz = [ts.number()]
            for _ in range(2):
                ts.expect(",")
                xyz.append(ts.number())
            axis = np.array(xyz)
            if np.max(np.abs(axis)) < 1e-12:
                raise self.fig_error(start, "DOF axis has no direction")
        ts.expect(")")
        return kind, axis

    def group(self) -> _GroupSpec:
        ts = self.ts
        spec = _GroupSpec(self.ident("a group name"))
        gname = self.text(spec.name)
        ts.expect("{")
        seen: set[str] = set()
        keys = ("joints", "angles", "driver", "offset", "lower", "upper", "displacement", "limit")
        while not ts.accept("}"):
            k = ts.pos
            word = ts.tokens[k]
            if word not in keys:
                raise ts.error("expected " + ", ".join(f"'{x}'" for x in keys) + " or '}'")
            ts.pos = k + 1
            if word in seen and word != "limit":
                raise self.fig_error(k, f"group {gname!r}: {word} given twice")
            seen.add(word)
            if word == "limit":
                spec.limits.append(self.linear_limit())
                continue
            ts.expect("=")
            if word in ("joints", "angles"):
                setattr(spec, word, self.name_list())
            elif word == "driver":
                spec.driver = self.driver()
            else:
                spec.values[word] = (k, self.value_list())
            self.end()
        return spec

    def driver(self) -> tuple[int, str, list[list[float]] | dict[str, DriverParam]]:
        """``"matrix" "(" rows ")"`` or ``KIND "(" [IDENT "=" value {"," IDENT "=" value}] ")"``."""
        ts = self.ts
        k = self.ident("a driver ('matrix' or a driver kind)")
        kind = ts.tokens[k]
        ts.expect("(")
        if kind == "matrix":
            rows = [self.number_list()]
            while ts.accept(","):
                rows.append(self.number_list())
            ts.expect(")", "',' or ')'")
            return k, kind, rows
        if not known_driver(kind):
            known = ", ".join(["matrix", *sorted(DRIVER_KINDS)])
            raise self.fig_error(k, f"unknown driver kind {kind!r} (known here: {known}; the kinds of the "
                                    "standard human are registered by importing jackpy.body)")
        params: dict[str, DriverParam] = {}
        if not ts.at(")"):
            while True:
                key, kat = self.name("a driver parameter name")
                if key in params:
                    raise self.fig_error(kat, f"driver parameter {key!r} given twice")
                ts.expect("=")
                nk = ts.kind()
                if nk == STRING:
                    params[key] = string_value(ts.tokens[ts.next()])
                elif ts.peek() in ("true", "false"):
                    params[key] = ts.tokens[ts.next()] == "true"
                else:
                    params[key] = ts.number()
                if not ts.accept(","):
                    break
        ts.expect(")", "',' or ')'")
        return k, kind, params

    def linear_limit(self) -> tuple[list[tuple[float, int]], float]:
        """``term {("+"|"-") term} ("<=" | ">=") number ";"`` with ``term := [number "*"] IDENT``."""
        ts = self.ts
        terms = []
        sign = -1.0 if ts.accept("-") else 1.0
        while True:
            coef = 1.0
            if ts.kind() == NUMBER:
                coef = ts.number()
                ts.expect("*")
            terms.append((sign * coef, self.ident("a group angle name")))
            if ts.accept("+"):
                sign = 1.0
            elif ts.accept("-"):
                sign = -1.0
            else:
                break
        if ts.accept(">="):
            flip = -1.0
        else:
            ts.expect("<=", "'+', '-', '<=' or '>='")
            flip = 1.0
        b = self.convert(self.quantity(), ANGLE_UNITS, "limit bound")
        self.end()
        return [(flip * c, t) for c, t in terms], flip * b

    def human(self, fig: Figure) -> HumanMarker:
        """``"human" "{" { KEY "=" value ";" | ("dim" | "override") STRING "=" quantity ";" } "}"``."""
        ts = self.ts
        ts.expect("{")
        fields: dict[str, object] = {}
        dims: dict[str, float] = {}
        overrides: dict[str, float] = {}
        start = ts.pos
        while not ts.accept("}"):
            k = ts.pos
            word = ts.tokens[k]
            if word in ("dim", "override"):
                ts.pos = k + 1
                nk = ts.expect_kind(STRING, "a quoted dimension name")
                dim = string_value(ts.tokens[nk])
                ts.expect("=")
                target = dims if word == "dim" else overrides
                if dim in target:
                    raise self.fig_error(nk, f"figure {fig.name!r} human: {word} {dim!r} given twice")
                target[dim] = self.body_value(dim)
            elif word in ("population", "sex"):
                ts.pos = k + 1
                ts.expect("=")
                kind = ts.kind()
                if kind not in (IDENT, STRING):
                    raise ts.error(f"expected a {word} name")
                v = ts.tokens[ts.next()]
                fields[word] = string_value(v) if kind == STRING else v
            elif word in ("percentile", "mass", "eye_drop"):
                ts.pos = k + 1
                ts.expect("=")
                fields[word] = self.body_value("mass" if word == "mass" else ("" if word == "percentile" else word))
            else:
                raise ts.error("expected 'population', 'sex', 'percentile', 'mass', 'eye_drop', 'dim', "
                               "'override' or '}'")
            self.end()
        for need in ("population", "sex", "percentile"):
            if need not in fields:
                raise self.fig_error(start - 2, f"figure {fig.name!r} human: no {need}")
        return HumanMarker(str(fields["population"]), str(fields["sex"]), float(fields["percentile"]),  # type: ignore[arg-type]
                           float(fields.get("mass", 0.0)), float(fields.get("eye_drop", 0.0)),  # type: ignore[arg-type]
                           dims, overrides)

    def body_value(self, name: str) -> float:
        """A body value in SI: kilograms for ``mass`` (``kg`` or none), a bare number for the
        percentile (empty ``name``), metres for any other (lengths default to cm)."""
        ts = self.ts
        start = ts.pos
        value = ts.number()
        if name == "mass":
            if ts.kind() == IDENT:
                ts.expect("kg", "'kg' or ';'")
            return value
        if not name:
            return value
        unit = ts.next() if ts.kind() == IDENT else -1
        if unit >= 0 and ts.tokens[unit] == "m":  # metres as written, bit for bit
            ts.check_range(value * 100.0, start, name)
            return value
        return self.convert((value, unit, start), LENGTH_UNITS, name) * CM

    # ----- building ---------------------------------------------------------------------------
    def joint_values(self, where: str, tok: int, values: list[_Value], kinds: list[str]) -> np.ndarray:
        """Values for DOFs of ``kinds`` ('R' deg, 'T' cm) in SI, checking count and units."""
        return np.array(self.si_values(where, tok, values, kinds))

    def si_values(self, where: str, tok: int, values: list[_Value], kinds: list[str]) -> list[float]:
        """:meth:`joint_values` as a list of floats."""
        if len(values) != len(kinds):
            raise self.fig_error(tok, f"{where}: {self.text(tok)} has {len(values)} values for {len(kinds)} DOFs")
        bare = [v * (DEG if k == "R" else CM) for (v, u, _), k in zip(values, kinds)
                if u < 0 and -MAX_MAGNITUDE <= v <= MAX_MAGNITUDE]
        if len(bare) == len(values):  # bare numbers within range (the common case), the same bits as below
            return bare
        out = []
        for k, (v, kind) in enumerate(zip(values, kinds)):
            if kind == "R":
                out.append(self.convert(v, ANGLE_UNITS, f"{where} DOF {k} (rotation)") * DEG)
            else:
                out.append(self.convert(v, LENGTH_UNITS, f"{where} DOF {k} (translation)") * CM)
        return out

    def build_joint(self, fig: Figure, spec: _JointSpec) -> None:
        name = self.text(spec.name)
        where = f"figure {fig.name!r} joint {name!r}"
        if name in fig.joints:
            raise self.fig_error(spec.name, f"figure {fig.name!r}: duplicate joint {name!r}")
        if spec.connect is None:
            raise self.fig_error(spec.name, f"{where}: no 'connect A.a to B.b;'")
        kinds = [k for k, _ in spec.dofs]
        limits = {key: self.si_values(where, *spec.values[key], kinds)
                  for key in ("lower", "upper") if key in spec.values}
        dofs = []
        for k, (kind, axis) in enumerate(spec.dofs):
            lo, hi = DEFAULT_ROTATION_LIMITS if kind == "R" else DEFAULT_TRANSLATION_LIMITS
            dofs.append(Dof(kind, axis, limits["lower"][k] if "lower" in limits else lo,
                            limits["upper"][k] if "upper" in limits else hi))
            if dofs[-1].lower > dofs[-1].upper:
                at = spec.values["lower"][0] if "lower" in spec.values else spec.values["upper"][0]
                raise self.fig_error(at, f"{where} DOF {k}: lower limit above upper")
        if "displacement" in spec.values:
            at, values = spec.values["displacement"]
            disp = self.si_values(where, at, values, kinds)
            for k, (d, v) in enumerate(zip(dofs, disp)):
                if not (d.lower - 1e-9 <= v <= d.upper + 1e-9):
                    unit, f = ("deg", 180 / np.pi) if d.kind == "R" else ("cm", 100.0)
                    raise self.fig_error(values[k][2], f"{where} DOF {k}: displacement {v * f:.6g} {unit} outside "
                                                       f"limits [{d.lower * f:.6g}, {d.upper * f:.6g}] {unit}")
        else:
            disp = np.clip(np.zeros(len(dofs)), [d.lower for d in dofs], [d.upper for d in dofs])
        fig.add_joint(Joint(name, *spec.connect, dofs=dofs, displacement=disp))

    def check_graph(self, fig: Figure, pos: _Positions) -> None:
        """The checks of :meth:`Figure.validate`, each at the token of the part at fault."""
        for j in fig.joints.values():
            spec = pos.joints[j.name]
            where = f"figure {fig.name!r}: joint {j.name!r}"
            for seg, site in ((j.from_seg, j.from_site), (j.to_seg, j.to_site)):
                if seg not in fig.segments:
                    raise self.fig_error(spec.connect_at, f"{where} names unknown segment {seg!r}")
                if site not in fig.segments[seg].sites:
                    raise self.fig_error(spec.connect_at, f"{where} names unknown site {seg}.{site}")
            if j.from_seg == j.to_seg:
                raise self.fig_error(spec.connect_at, f"{where} connects segment {j.from_seg!r} to itself")
        if fig.root is not None:
            seg, site = fig.root
            if seg not in fig.segments or site not in fig.segments[seg].sites:
                raise self.fig_error(pos.root, f"figure {fig.name!r}: root names unknown site {seg}.{site}")
        if not fig.segments:
            return
        parent = {s: s for s in fig.segments}

        def find(s: str) -> str:
            while parent[s] != s:
                parent[s] = parent[parent[s]]
                s = parent[s]
            return s

        for j in fig.joints.values():
            a, b = find(j.from_seg), find(j.to_seg)
            if a == b:
                raise self.fig_error(pos.joints[j.name].name,
                                     f"figure {fig.name!r}: joint {j.name!r} closes a cycle between segments "
                                     f"{j.from_seg!r} and {j.to_seg!r} (Peabody figures are trees; close loops "
                                     "with IK constraints)")
            parent[a] = b
        start = find(fig.root_segment())
        for s in fig.segments:
            if find(s) != start:
                raise self.fig_error(pos.segments[s], f"figure {fig.name!r}: segment {s!r} is not joined to the "
                                                      f"root segment {fig.root_segment()!r}")

    def build_group(self, fig: Figure, spec: _GroupSpec) -> None:
        name = self.text(spec.name)
        where = f"figure {fig.name!r} group {name!r}"
        if name in fig.groups:
            raise self.fig_error(spec.name, f"figure {fig.name!r}: duplicate group {name!r}")
        if not spec.joints or not spec.angles or spec.driver is None:
            raise self.fig_error(spec.name, f"{where}: needs 'joints', 'angles' and 'driver'")
        member_kinds: list[str] = []
        for jt in spec.joints:
            jn = self.text(jt)
            if jn not in fig.joints:
                raise self.fig_error(jt, f"{where}: unknown joint {jn!r}")
            for other in fig.groups.values():
                if jn in other.joints:
                    raise self.fig_error(jt, f"figure {fig.name!r}: joint {jn!r} is in groups {other.name!r} "
                                             f"and {name!r}")
            if spec.joints.count(jt) > 1 or [self.text(t) for t in spec.joints].count(jn) > 1:
                raise self.fig_error(jt, f"{where}: joint {jn!r} named twice")
            member_kinds += [d.kind for d in fig.joints[jn].dofs]
        angle_names = [self.text(t) for t in spec.angles]
        for t in spec.angles:
            if angle_names.count(self.text(t)) > 1:
                raise self.fig_error(t, f"{where}: angle {self.text(t)!r} named twice")
        n, m = len(angle_names), len(member_kinds)
        dtok, kind, form = spec.driver
        offset = (self.joint_values(where, *spec.values["offset"], member_kinds)
                  if "offset" in spec.values else np.zeros(m))
        if isinstance(form, list):
            if len(form) != m or any(len(r) != n for r in form):
                raise self.fig_error(dtok, f"{where}: driver matrix must have {m} rows (member DOFs) of "
                                           f"{n} values (group angles)")
            per_unit = np.array([1.0 if k == "R" else CM / DEG for k in member_kinds])
            driver = LinearDriver(np.array(form, dtype=float).reshape(m, n) * per_unit[:, None], offset)
        else:
            try:
                driver = make_driver(kind, form)
            except (FigureError, ValueError, TypeError, KeyError) as exc:
                raise self.fig_error(dtok, f"{where}: bad {kind} driver: {exc}") from None
        angle_values = {key: self.joint_values(where, *spec.values[key], ["R"] * n)
                        for key in ("lower", "upper", "displacement") if key in spec.values}
        lower = angle_values.get("lower", np.full(n, DEFAULT_ROTATION_LIMITS[0]))
        upper = angle_values.get("upper", np.full(n, DEFAULT_ROTATION_LIMITS[1]))
        if np.any(lower > upper):
            raise self.fig_error(spec.values["lower"][0] if "lower" in spec.values else spec.name,
                                 f"{where}: lower limit above upper")
        a_rows, b = [], []
        for terms, bound in spec.limits:
            row = np.zeros(n)
            for coef, t in terms:
                if self.text(t) not in angle_names:
                    raise self.fig_error(t, f"{where}: limit names unknown group angle {self.text(t)!r}")
                row[angle_names.index(self.text(t))] += coef
            if not np.all(np.abs(row) <= MAX_MAGNITUDE):
                raise self.fig_error(terms[0][1], f"{where}: limit coefficients out of range")
            a_rows.append(row)
            b.append(bound * DEG)
        angles = angle_values.get("displacement", np.clip(np.zeros(n), lower, upper))
        group = JointGroup(name, [self.text(t) for t in spec.joints], angle_names, driver,
                           lower, upper, np.array(a_rows).reshape(-1, n), np.array(b), angles)
        if not group.is_feasible(group.angles):
            raise self.fig_error(spec.name, f"{where}: angles {np.degrees(angles).round(6).tolist()} deg "
                                            "violate the group's limits")
        with np.errstate(all="ignore"):
            values = np.asarray(driver(group.angles), dtype=float).reshape(-1)
        if values.size != m:
            raise self.fig_error(dtok, f"{where}: the {kind} driver gives {values.size} values for {m} member DOFs")
        if not np.all(np.isfinite(values)) or not np.all(np.abs(values) <= MAX_MAGNITUDE * CM):
            raise self.fig_error(dtok, f"{where}: the driver's member displacements are out of range")
        lo = np.concatenate([fig.joints[self.text(t)].lower for t in spec.joints])
        hi = np.concatenate([fig.joints[self.text(t)].upper for t in spec.joints])
        bad = np.flatnonzero((values < lo - 1e-9) | (values > hi + 1e-9))
        if bad.size:
            names = [f"{self.text(t)}[{k}]" for t in spec.joints for k in range(fig.joints[self.text(t)].ndof)]
            raise self.fig_error(spec.name, f"{where}: its angles drive {names[bad[0]]} outside that DOF's limits")
        fig.add_group(group)

    # ----- environments -----------------------------------------------------------------------
    def environment_file(self, base_dir: Path, policy: PathPolicy) -> Environment:
        """``{ "include" STRING ";" | "place" IDENT "at" xform ";" | figure }``."""
        ts = self.ts
        env = Environment()
        places: list[tuple[int, np.ndarray]] = []
        while ts.kind() != EOF:
            k = ts.pos
            if ts.accept("include"):
                sk = ts.expect_kind(STRING, "a quoted figure file name")
                self.end()
                figures = self.include(base_dir, sk, policy)
                env.includes.append(string_value(ts.tokens[sk]))
            elif ts.accept("place"):
                name = self.ident("a figure name")
                ts.expect("at", "'at'")
                places.append((name, self.xform(rigid=True)[1]))
                self.end()
                continue
            elif ts.at("figure"):
                figures = [self.figure()]
                k += 1
            else:
                raise ts.error("expected 'include', 'place' or 'figure'")
            for fig in figures:
                if fig.name in env.figures:
                    raise self.fig_error(k, f"environment already has a figure named {fig.name!r}")
                env.add(fig)
        placed: set[str] = set()
        for name, location in places:
            fn = self.text(name)
            if fn not in env.figures:
                raise self.fig_error(name, f"place: environment has no figure {fn!r}")
            if fn in placed:
                raise self.fig_error(name, f"figure {fn!r} placed twice")
            placed.add(fn)
            env.figures[fn].location = location
        return env

    def include(self, base_dir: Path, sk: int, policy: PathPolicy) -> list[Figure]:
        name = string_value(self.text(sk))
        path = base_dir / name
        refusal = policy.permit(path)
        if refusal is not None:
            raise self.fig_error(sk, f"include {name!r}: {refusal}")
        try:
            text = read_text(path)
        except OSError as exc:
            raise self.fig_error(sk, f"cannot read included file {name!r}: {exc.strerror or exc}") from None
        figures = parse_figures(text, str(path))
        inc_dir = os.path.dirname(name)
        for fig in figures:
            for seg in fig.segments.values():
                if seg.psurf is not None and inc_dir and not os.path.isabs(seg.psurf.source):
                    seg.psurf.source = Path(os.path.normpath(os.path.join(inc_dir, seg.psurf.source))).as_posix()
        return figures


def _exists(path: Path) -> bool:
    """``path.exists()`` that is False, not an error, for a name the system refuses."""
    try:
        return path.exists()
    except (OSError, ValueError):
        return False


def read_text(path: str | os.PathLike[str], limit: int | None = None) -> str:
    """The UTF-8 text of a regular file of at most ``limit`` bytes (default
    :data:`~jackpy.peabody.paths.MAX_TEXT_BYTES`); OSError for anything else (a folder, a FIFO or
    device that would never end, a file too large, a name with a NUL byte); ParseError at the first
    byte that is not UTF-8."""
    data = read_limited(path, MAX_TEXT_BYTES if limit is None else limit)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        before = data[:exc.start]
        line = before.count(b"\n") + 1
        column = exc.start - (before.rfind(b"\n") + 1) + 1
        raise ParseError("expected UTF-8 text", str(path), line, column) from None


def _validate(parser: _Parser, figures: Iterable[Figure]) -> None:
    """A last check of each figure (the parser has already checked everything at its token)."""
    for fig in figures:
        try:
            fig.validate()
        except FigureError as exc:
            pos = parser.positions.get(fig.name)
            raise parser.fig_error(pos.figure if pos else 0, str(exc)) from None


def parse_figures(text: str, filename: str = "<string>", *, fast: bool = True) -> list[Figure]:
    """Parse ``.fig`` text into validated figures (no geometry is loaded).

    Well-formed text takes :func:`~jackpy.peabody.fastread.parse_fast`; anything it declines (and
    everything with ``fast=False``) the token parser, which reports every error."""
    with np.errstate(all="ignore"):  # (overflow is checked where it matters, without warnings)
        figures = parse_fast(text, filename) if fast else None
        if figures is not None:
            return figures
        parser = _Parser(text, filename)
        figures = parser.figure_file()
    _validate(parser, figures)
    return figures


def parse_environment(text: str, filename: str = "<string>", base_dir: str | os.PathLike[str] = ".",
                      policy: PathPolicy | None = None) -> Environment:
    """Parse ``.env`` text; ``include`` files are read relative to ``base_dir`` and must lie
    inside it or the library path unless ``policy`` allows more (no geometry loaded)."""
    policy = policy or PathPolicy.for_folder(base_dir)
    parser = _Parser(text, filename)
    with np.errstate(all="ignore"):
        env = parser.environment_file(Path(base_dir), policy)
    for fig in env.figures.values():  # (included figures were checked by their own parser)
        if fig.name in parser.positions:
            _validate(parser, [fig])
    env.outside = policy.outside
    return env


def load_geometry(figures: Iterable[Figure], base_dir: str | os.PathLike[str], *, require: bool = True,
                  filename: str = "<string>", policy: PathPolicy | None = None) -> None:
    """Load every segment's psurf mesh, resolving relative names against ``base_dir``.

    A missing, unreadable or refused file (outside the folders ``policy`` allows: by default
    ``base_dir`` and the library path) raises FigureError at the psurf's position naming the
    figure and segment, unless ``require`` is false (the psurf then keeps ``mesh = None``). A
    malformed file raises ParseError (at its own line) or ImportCADError. Each file is read once.
    """
    policy = policy or PathPolicy.for_folder(base_dir)
    cache: dict[Path, Mesh] = {}
    for fig in figures:
        for seg in fig.segments.values():
            if seg.psurf is None:
                continue
            ps = seg.psurf
            at = ps.origin.text() if ps.origin is not None else f"{filename}:1:1"
            where = f"{at}: figure {fig.name!r} segment {seg.name!r}"
            path = Path(base_dir) / ps.source
            if path not in cache:
                if not require and not _exists(path):
                    continue
                refusal = policy.permit(path)
                if refusal is not None:
                    if not require:
                        continue
                    raise FigureError(f"{where}: geometry file {ps.source!r}: {refusal}")
                if not _exists(path):
                    raise FigureError(f"{where}: geometry file {ps.source!r} not found (looked for {path})")
                try:
                    cache[path] = load_mesh(path, limit=MAX_MESH_BYTES)
                except ImportCADError as exc:
                    raise ImportCADError(f"{where}: {exc}") from None
                except OSError as exc:
                    if not require:
                        continue
                    raise FigureError(f"{where}: cannot read geometry file {ps.source!r}: "
                                      f"{exc.strerror or exc}") from None
            mesh = cache[path]
            ps.mesh = Mesh(mesh.vertices.copy(), mesh.faces.copy())


def read_figures(path: str | os.PathLike[str], *, require_geometry: bool = True, allow_outside: bool | None = None,
                 library: Iterable[str | os.PathLike[str]] | None = None) -> list[Figure]:
    """Read a ``.fig`` file: its figures, validated, with geometry loaded relative to the file
    (contained as :class:`~jackpy.peabody.paths.PathPolicy` says)."""
    policy = PathPolicy.for_file(path, allow_outside=allow_outside, library=library)
    figures = parse_figures(read_text(path), str(path))
    load_geometry(figures, Path(path).parent, require=require_geometry, filename=str(path), policy=policy)
    return figures


def read_environment(path: str | os.PathLike[str], *, require_geometry: bool = True,
                     allow_outside: bool | None = None,
                     library: Iterable[str | os.PathLike[str]] | None = None) -> Environment:
    """Read a ``.env`` file: included and inline figures, placed, with geometry loaded."""
    base = Path(path).parent
    policy = PathPolicy.for_file(path, allow_outside=allow_outside, library=library)
    env = parse_environment(read_text(path), str(path), base, policy)
    load_geometry(list(env.figures.values()), base, require=require_geometry, filename=str(path), policy=policy)
    env.outside = policy.outside
    return env


def load(path: str | os.PathLike[str], *, require_geometry: bool = True, allow_outside: bool | None = None,
         library: Iterable[str | os.PathLike[str]] | None = None) -> Environment:
    """Read a ``.fig`` or ``.env`` file by extension; a ``.fig`` file's figures come as an Environment
    (files read from outside the allowed folders are listed in ``env.outside``)."""
    ext = Path(path).suffix.lower()
    if ext == ".env":
        return read_environment(path, require_geometry=require_geometry, allow_outside=allow_outside,
                                library=library)
    if ext == ".fig":
        policy = PathPolicy.for_file(path, allow_outside=allow_outside, library=library)
        figures = parse_figures(read_text(path), str(path))
        load_geometry(figures, Path(path).parent, require=require_geometry, filename=str(path), policy=policy)
        env = Environment()
        for fig in figures:
            env.add(fig)
        env.outside = policy.outside
        return env
    raise FigureError(f"{path}: unknown Peabody file type {ext!r} (expected .fig or .env)")
