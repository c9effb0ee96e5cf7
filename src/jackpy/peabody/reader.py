"""Reader of Peabody text: ``.fig`` files (figures) and ``.env`` files (an environment).

The grammar, units and product rule are documented in docs/peabody-format.md. Values in files are
centimetres and degrees; the figures built here are in metres and radians with 4x4 column-vector
transforms. A syntax error raises :class:`ParseError` (``file:line:column: expected ...``); a
semantic one (unknown site, self-joint, cycle, displacement outside limits, wrong value count...)
raises :class:`FigureError` naming the figure and the segment, site, joint or group, prefixed with
the file and, where known, the line and column.

Relative ``psurf`` file names in the returned figures are relative to the directory of the file
that was read (for an environment: the ``.env`` file, so names from included figure files are
rewritten accordingly).
"""

from __future__ import annotations

import errno
import math
import os
import stat
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from jackpy.errors import FigureError, ImportCADError, ParseError
from jackpy.peabody.geometry import Mesh, Psurf
from jackpy.peabody.groups import JointGroup, LinearDriver
from jackpy.peabody.lexer import (
    EOF,
    IDENT,
    NUMBER,
    STRING,
    Token,
    TokenStream,
    tokenize,
)
from jackpy.peabody.model import (
    DEFAULT_ROTATION_LIMITS,
    DEFAULT_TRANSLATION_LIMITS,
    Dof,
    Environment,
    Figure,
    Joint,
    Segment,
)
from jackpy.peabody.notation import (
    ANGLE_UNITS,
    CM,
    DEG,
    LENGTH_UNITS,
    PRIM_ARGS,
    RIGID_PRIMS,
    Prim,
    compose,
)
from jackpy.peabody.psurf_io import load_mesh
from jackpy.peabody.transforms import AXES, is_rigid

#: a value as written: number, its unit token (or None) and the token where it starts
_Value = tuple[float, Token | None, Token]


@dataclass
class _JointSpec:
    name: Token
    connect: tuple[str, str, str, str] | None = None
    dofs: list[tuple[str, np.ndarray]] = field(default_factory=list)
    type_tok: Token | None = None
    values: dict[str, tuple[Token, list[_Value]]] = field(default_factory=dict)


@dataclass
class _GroupSpec:
    name: Token
    joints: list[Token] = field(default_factory=list)
    angles: list[Token] = field(default_factory=list)
    driver: tuple[Token, list[list[float]]] | None = None
    values: dict[str, tuple[Token, list[_Value]]] = field(default_factory=dict)
    limits: list[tuple[list[tuple[float, Token]], float]] = field(default_factory=list)


class _Parser:
    """Recursive-descent parser over a token stream; builds figures as it goes."""

    def __init__(self, text: str, filename: str) -> None:
        self.file = filename
        self.ts = TokenStream(tokenize(text, filename), filename)

    # ----- small helpers ----------------------------------------------------------------------
    def fig_error(self, tok: Token, message: str) -> FigureError:
        return FigureError(f"{self.file}:{tok.line}:{tok.column}: {message}")

    def ident(self, what: str) -> Token:
        return self.ts.expect_kind(IDENT, what)

    def end(self) -> None:
        self.ts.expect(";")

    def number(self) -> float:
        """``["+"|"-"] NUMBER``."""
        sign = -1.0 if self.ts.accept("-") else 1.0
        if sign > 0:
            self.ts.accept("+")
        return sign * float(self.ts.expect_kind(NUMBER, "a number").value)  # type: ignore[arg-type]

    def quantity(self) -> _Value:
        """A number with an optional unit identifier (``5.00cm``, ``30 deg``)."""
        start = self.ts.peek()
        value = self.number()
        unit = self.ts.next() if self.ts.peek().kind == IDENT else None
        if unit is not None and unit.text not in LENGTH_UNITS and unit.text not in ANGLE_UNITS:
            raise self.ts.error("expected a unit (" + ", ".join([*LENGTH_UNITS, *ANGLE_UNITS]) + ")", unit)
        return value, unit, start

    def convert(self, v: _Value, units: dict[str, float], what: str) -> float:
        """A value in the file's default unit of ``units`` (cm or deg); a wrong unit is an error."""
        value, unit, start = v
        if unit is not None:
            if unit.text not in units:
                raise self.fig_error(unit, f"{what}: expected a unit among {', '.join(units)}, found {unit.text!r}")
            value *= units[unit.text]
        if not math.isfinite(value * CM):
            raise ParseError(f"{what}: value out of range", self.file, start.line, start.column)
        return value

    def value_list(self) -> list[_Value]:
        """``"(" quantity {"," quantity} ")" [unit]``; a trailing unit applies to bare numbers."""
        self.ts.expect("(")
        values = [self.quantity()]
        while self.ts.accept(","):
            values.append(self.quantity())
        self.ts.expect(")", "',' or ')'")
        if self.ts.peek().kind == IDENT:
            unit = self.ts.next()
            if unit.text not in LENGTH_UNITS and unit.text not in ANGLE_UNITS:
                raise self.ts.error("expected a unit or ';'", unit)
            values = [(v, u or unit, t) for v, u, t in values]
        return values

    def number_list(self) -> list[float]:
        """``"(" number {"," number} ")"``."""
        self.ts.expect("(")
        values = [self.number()]
        while self.ts.accept(","):
            values.append(self.number())
        self.ts.expect(")", "',' or ')'")
        return values

    def prim(self) -> tuple[Prim, Token]:
        tok = self.ident("a transform (trans, scale, rotx, roty, rotz, rot, matrix)")
        kinds = PRIM_ARGS.get(tok.text)
        if kinds is None:
            raise self.ts.error("expected a transform (trans, scale, rotx, roty, rotz, rot, matrix)", tok)
        self.ts.expect("(")
        args = []
        for k, kind in enumerate(kinds):
            if k:
                self.ts.expect(",")
            if kind == "N":
                args.append(self.number())
            else:
                args.append(self.convert(self.quantity(), LENGTH_UNITS if kind == "L" else ANGLE_UNITS,
                                         f"argument {k + 1} of {tok.text}"))
        self.ts.expect(")")
        if tok.text == "rot" and math.hypot(*args[:3]) < 1e-12:
            raise self.fig_error(tok, "rot(...) axis has no direction")
        return (tok.text, tuple(args)), tok

    def xform(self, rigid: bool) -> list[Prim]:
        """``prim {"*" prim}``; with ``rigid`` only rotations and translations are allowed."""
        prims = []
        while True:
            prim, tok = self.prim()
            if rigid and (prim[0] not in RIGID_PRIMS or not is_rigid(compose([prim]), 1e-6)):
                raise self.fig_error(tok, f"a location must be rigid (trans, rot...), not {tok.text}(...)")
            prims.append(prim)
            if not self.ts.accept("*"):
                return prims

    def siteref(self) -> tuple[str, str]:
        seg = self.ident("a site reference SEGMENT.SITE").text
        self.ts.expect(".", "'.' in SEGMENT.SITE")
        return seg, self.ident("a site name after '.'").text

    def name_list(self) -> list[Token]:
        names = [self.ident("a name")]
        while self.ts.accept(","):
            names.append(self.ident("a name"))
        return names

    # ----- files ------------------------------------------------------------------------------
    def figure_file(self) -> list[Figure]:
        """``{ figure }``."""
        figures = []
        while self.ts.peek().kind != EOF:
            figures.append(self.figure())
        return figures

    def figure(self) -> Figure:
        """``"figure" IDENT "{" { segment | joint | group | root | location } "}"``."""
        self.ts.expect("figure")
        name = self.ident("a figure name")
        fig = Figure(name.text)
        self.ts.expect("{")
        joints: list[_JointSpec] = []
        groups: list[_GroupSpec] = []
        seen: dict[str, Token] = {}
        while not self.ts.accept("}"):
            tok = self.ts.peek()
            if self.ts.accept("segment"):
                self.segment(fig)
            elif self.ts.accept("joint"):
                joints.append(self.joint(fig))
            elif self.ts.accept("group"):
                groups.append(self.group())
            elif tok.text in ("root", "location") and tok.kind == IDENT:
                self.ts.next()
                if tok.text in seen:
                    raise self.fig_error(tok, f"figure {fig.name!r}: {tok.text} given twice")
                seen[tok.text] = tok
                self.ts.expect("=")
                if tok.text == "root":
                    fig.root = self.siteref()
                else:
                    fig.location = compose(self.xform(rigid=True))
                self.end()
            else:
                raise self.ts.error("expected 'segment', 'joint', 'group', 'root', 'location' or '}'")
        for spec in joints:
            self.build_joint(fig, spec)
        for gspec in groups:
            self.build_group(fig, gspec)
        return fig

    def segment(self, fig: Figure) -> None:
        name = self.ident("a segment name")
        if name.text in fig.segments:
            raise self.fig_error(name, f"figure {fig.name!r}: duplicate segment {name.text!r}")
        seg = fig.add_segment(Segment(name.text))
        where = f"figure {fig.name!r} segment {seg.name!r}"
        self.ts.expect("{")
        seen: set[str] = set()
        while not self.ts.accept("}"):
            tok = self.ts.peek()
            if self.ts.accept("site"):
                site = self.ident("a site name")
                self.ts.expect("->", "'->location'")
                self.ts.expect("location", "'location' after '->'")
                self.ts.expect("=")
                if site.text in seg.sites:
                    raise self.fig_error(site, f"{where}: duplicate site {site.text!r}")
                seg.add_site(site.text, compose(self.xform(rigid=True)))
                self.end()
                continue
            if tok.kind != IDENT or tok.text not in ("psurf", "attribute", "mass", "com", "inertia"):
                raise self.ts.error("expected 'psurf', 'attribute', 'site', 'mass', 'com', 'inertia' or '}'")
            self.ts.next()
            if tok.text in seen:
                raise self.fig_error(tok, f"{where}: {tok.text} given twice")
            seen.add(tok.text)
            self.ts.expect("=")
            if tok.text == "psurf":
                source = self.ts.expect_kind(STRING, "a quoted geometry file name").value
                prims = self.xform(rigid=False) if self.ts.accept("*") else []
                seg.psurf = Psurf(str(source), compose(prims), scale_text=prims)
            elif tok.text == "attribute":
                attr = self.ts.next()
                if attr.kind not in (IDENT, STRING):
                    raise self.ts.error("expected an attribute name", attr)
                seg.attribute = str(attr.value)
            elif tok.text == "mass":
                start = self.ts.peek()
                seg.mass = self.number()
                if self.ts.peek().kind == IDENT:
                    self.ts.expect("kg", "'kg' or ';'")
                if seg.mass < 0:
                    raise self.fig_error(start, f"{where}: mass must not be negative")
            elif tok.text == "com":
                values = self.value_list()
                if len(values) != 3:
                    raise self.fig_error(tok, f"{where}: com needs 3 values, got {len(values)}")
                seg.com = np.array([self.convert(v, LENGTH_UNITS, "com") for v in values]) * CM
            else:
                values = self.number_list()
                if len(values) != 6:
                    raise self.fig_error(tok, f"{where}: inertia needs 6 values (ixx,iyy,izz,ixy,ixz,iyz), "
                                              f"got {len(values)}")
                ixx, iyy, izz, ixy, ixz, iyz = (v * CM * CM for v in values)
                seg.inertia = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
            self.end()

    def joint(self, fig: Figure) -> _JointSpec:
        spec = _JointSpec(self.ident("a joint name"))
        self.ts.expect("{")
        seen: set[str] = set()
        while not self.ts.accept("}"):
            tok = self.ts.peek()
            key = {"lower_limits": "lower", "upper_limits": "upper"}.get(tok.text, tok.text)
            if tok.kind != IDENT or key not in ("connect", "type", "displacement", "lower", "upper"):
                raise self.ts.error("expected 'connect', 'type', 'displacement', 'lower', 'upper' or '}'")
            self.ts.next()
            if key in seen:
                raise self.fig_error(tok, f"figure {fig.name!r} joint {spec.name.text!r}: {key} given twice")
            seen.add(key)
            if key == "connect":
                a = self.siteref()
                self.ts.expect("to", "'to'")
                spec.connect = (*a, *self.siteref())
            elif key == "type":
                self.ts.expect("=")
                spec.type_tok = tok
                spec.dofs.append(self.dof())
                while self.ts.accept("*"):
                    spec.dofs.append(self.dof())
            else:
                self.ts.expect("=")
                spec.values[key] = (tok, self.value_list())
            self.end()
        return spec

    def dof(self) -> tuple[str, np.ndarray]:
        """``("R" | "T") "(" ("x" | "y" | "z" | number "," number "," number) ")"``."""
        kind = self.ts.peek()
        if kind.kind != IDENT or kind.text not in ("R", "T"):
            raise self.ts.error("expected a DOF R(axis) or T(axis)")
        self.ts.next()
        self.ts.expect("(")
        if self.ts.peek().kind == IDENT and self.ts.peek().text in AXES:
            axis = AXES[self.ts.next().text].copy()
        else:
            start = self.ts.peek()
            xyz = [self.number()]
            for _ in range(2):
                self.ts.expect(",")
                xyz.append(self.number())
            axis = np.array(xyz)
            if np.linalg.norm(axis) < 1e-12:
                raise self.fig_error(start, "DOF axis has no direction")
        self.ts.expect(")")
        return kind.text, axis

    def group(self) -> _GroupSpec:
        spec = _GroupSpec(self.ident("a group name"))
        self.ts.expect("{")
        seen: set[str] = set()
        while not self.ts.accept("}"):
            tok = self.ts.peek()
            keys = ("joints", "angles", "driver", "offset", "lower", "upper", "displacement", "limit")
            if tok.kind != IDENT or tok.text not in keys:
                raise self.ts.error("expected " + ", ".join(f"'{k}'" for k in keys) + " or '}'")
            self.ts.next()
            if tok.text in seen and tok.text != "limit":
                raise self.fig_error(tok, f"group {spec.name.text!r}: {tok.text} given twice")
            seen.add(tok.text)
            if tok.text == "limit":
                spec.limits.append(self.linear_limit())
                continue
            self.ts.expect("=")
            if tok.text in ("joints", "angles"):
                setattr(spec, tok.text, self.name_list())
            elif tok.text == "driver":
                self.ts.expect("matrix", "'matrix'")
                self.ts.expect("(")
                rows = [self.number_list()]
                while self.ts.accept(","):
                    rows.append(self.number_list())
                self.ts.expect(")", "',' or ')'")
                spec.driver = (tok, rows)
            else:
                spec.values[tok.text] = (tok, self.value_list())
            self.end()
        return spec

    def linear_limit(self) -> tuple[list[tuple[float, Token]], float]:
        """``term {("+"|"-") term} ("<=" | ">=") number ";"`` with ``term := [number "*"] IDENT``."""
        terms = []
        sign = -1.0 if self.ts.accept("-") else 1.0
        while True:
            coef = 1.0
            if self.ts.peek().kind == NUMBER:
                coef = self.number()
                self.ts.expect("*")
            terms.append((sign * coef, self.ident("a group angle name")))
            if self.ts.accept("+"):
                sign = 1.0
            elif self.ts.accept("-"):
                sign = -1.0
            else:
                break
        if self.ts.accept(">="):
            flip = -1.0
        else:
            self.ts.expect("<=", "'+', '-', '<=' or '>='")
            flip = 1.0
        b = self.convert(self.quantity(), ANGLE_UNITS, "limit bound")
        self.end()
        return [(flip * c, t) for c, t in terms], flip * b

    # ----- building ---------------------------------------------------------------------------
    def joint_values(self, where: str, tok: Token, values: list[_Value], kinds: list[str]) -> np.ndarray:
        """Values for DOFs of ``kinds`` ('R' deg, 'T' cm) in SI, checking count and units."""
        if len(values) != len(kinds):
            raise self.fig_error(tok, f"{where}: {tok.text} has {len(values)} values for {len(kinds)} DOFs")
        out = []
        for k, (v, kind) in enumerate(zip(values, kinds)):
            if kind == "R":
                out.append(self.convert(v, ANGLE_UNITS, f"{where} DOF {k} (rotation)") * DEG)
            else:
                out.append(self.convert(v, LENGTH_UNITS, f"{where} DOF {k} (translation)") * CM)
        return np.array(out)

    def build_joint(self, fig: Figure, spec: _JointSpec) -> None:
        name = spec.name.text
        where = f"figure {fig.name!r} joint {name!r}"
        if name in fig.joints:
            raise self.fig_error(spec.name, f"figure {fig.name!r}: duplicate joint {name!r}")
        if spec.connect is None:
            raise self.fig_error(spec.name, f"{where}: no 'connect A.a to B.b;'")
        kinds = [k for k, _ in spec.dofs]
        limits = {key: self.joint_values(where, *spec.values[key], kinds)
                  for key in ("lower", "upper") if key in spec.values}
        dofs = []
        for k, (kind, axis) in enumerate(spec.dofs):
            lo, hi = DEFAULT_ROTATION_LIMITS if kind == "R" else DEFAULT_TRANSLATION_LIMITS
            dofs.append(Dof(kind, axis, float(limits["lower"][k]) if "lower" in limits else lo,
                            float(limits["upper"][k]) if "upper" in limits else hi))
        if "displacement" in spec.values:
            disp = self.joint_values(where, *spec.values["displacement"], kinds)
        else:
            disp = np.clip(np.zeros(len(dofs)), [d.lower for d in dofs], [d.upper for d in dofs])
        fig.add_joint(Joint(name, *spec.connect, dofs=dofs, displacement=disp))

    def build_group(self, fig: Figure, spec: _GroupSpec) -> None:
        name = spec.name.text
        where = f"figure {fig.name!r} group {name!r}"
        if name in fig.groups:
            raise self.fig_error(spec.name, f"figure {fig.name!r}: duplicate group {name!r}")
        if not spec.joints or not spec.angles or spec.driver is None:
            raise self.fig_error(spec.name, f"{where}: needs 'joints', 'angles' and 'driver'")
        member_kinds: list[str] = []
        for jt in spec.joints:
            if jt.text not in fig.joints:
                raise self.fig_error(jt, f"{where}: unknown joint {jt.text!r}")
            member_kinds += [d.kind for d in fig.joints[jt.text].dofs]
        angle_names = [t.text for t in spec.angles]
        n, m = len(angle_names), len(member_kinds)
        dtok, rows = spec.driver
        if len(rows) != m or any(len(r) != n for r in rows):
            raise self.fig_error(dtok, f"{where}: driver matrix must have {m} rows (member DOFs) of "
                                       f"{n} values (group angles)")
        per_unit = np.array([1.0 if k == "R" else CM / DEG for k in member_kinds])
        matrix = np.array(rows, dtype=float) * per_unit[:, None]
        offset = (self.joint_values(where, *spec.values["offset"], member_kinds)
                  if "offset" in spec.values else np.zeros(m))
        angle_values = {key: self.joint_values(where, *spec.values[key], ["R"] * n)
                        for key in ("lower", "upper", "displacement") if key in spec.values}
        lower = angle_values.get("lower", np.full(n, DEFAULT_ROTATION_LIMITS[0]))
        upper = angle_values.get("upper", np.full(n, DEFAULT_ROTATION_LIMITS[1]))
        a_rows, b = [], []
        for terms, bound in spec.limits:
            row = np.zeros(n)
            for coef, t in terms:
                if t.text not in angle_names:
                    raise self.fig_error(t, f"{where}: limit names unknown group angle {t.text!r}")
                row[angle_names.index(t.text)] += coef
            a_rows.append(row)
            b.append(bound * DEG)
        angles = angle_values.get("displacement", np.clip(np.zeros(n), lower, upper))
        group = JointGroup(name, [t.text for t in spec.joints], angle_names, LinearDriver(matrix, offset),
                           lower, upper, np.array(a_rows).reshape(-1, n), np.array(b), angles)
        if not group.is_feasible(group.angles):
            raise self.fig_error(spec.name, f"{where}: angles {np.degrees(angles).round(6).tolist()} deg "
                                            "violate the group's limits")
        try:
            fig.add_group(group)
        except FigureError as exc:
            raise self.fig_error(spec.name, str(exc)) from None

    # ----- environments -----------------------------------------------------------------------
    def environment_file(self, base_dir: Path) -> Environment:
        """``{ "include" STRING ";" | "place" IDENT "at" xform ";" | figure }``."""
        env = Environment()
        places: list[tuple[Token, np.ndarray]] = []
        while self.ts.peek().kind != EOF:
            tok = self.ts.peek()
            if self.ts.accept("include"):
                stok = self.ts.expect_kind(STRING, "a quoted figure file name")
                self.end()
                figures = self.include(base_dir, stok)
                env.includes.append(str(stok.value))
            elif self.ts.accept("place"):
                name = self.ident("a figure name")
                self.ts.expect("at", "'at'")
                places.append((name, compose(self.xform(rigid=True))))
                self.end()
                continue
            elif self.ts.at("figure"):
                figures = [self.figure()]
            else:
                raise self.ts.error("expected 'include', 'place' or 'figure'")
            for fig in figures:
                if fig.name in env.figures:
                    raise self.fig_error(tok, f"environment already has a figure named {fig.name!r}")
                env.add(fig)
        placed: set[str] = set()
        for name, location in places:
            if name.text not in env.figures:
                raise self.fig_error(name, f"place: environment has no figure {name.text!r}")
            if name.text in placed:
                raise self.fig_error(name, f"figure {name.text!r} placed twice")
            placed.add(name.text)
            env.figures[name.text].location = location
        return env

    def include(self, base_dir: Path, stok: Token) -> list[Figure]:
        path = base_dir / str(stok.value)
        try:
            text = _read_text(path)
        except OSError as exc:
            raise self.fig_error(stok, f"cannot read included file {str(stok.value)!r}: "
                                       f"{exc.strerror or exc}") from None
        figures = parse_figures(text, str(path))
        inc_dir = os.path.dirname(str(stok.value))
        for fig in figures:
            for seg in fig.segments.values():
                if seg.psurf is not None and inc_dir and not os.path.isabs(seg.psurf.source):
                    seg.psurf.source = Path(os.path.normpath(os.path.join(inc_dir, seg.psurf.source))).as_posix()
        return figures


def _read_text(path: str | os.PathLike[str]) -> str:
    """The UTF-8 text of a regular file; OSError for anything else (a folder, a device such as
    ``/dev/zero`` that would never end, a name with a NUL byte); ParseError at the first byte that
    is not UTF-8."""
    try:
        info = os.stat(path)
    except ValueError:  # an embedded NUL byte
        raise OSError(errno.EINVAL, "not a valid file name") from None
    if stat.S_ISDIR(info.st_mode):
        raise IsADirectoryError(errno.EISDIR, "a folder, not a file", str(path))
    if not stat.S_ISREG(info.st_mode):
        raise OSError(errno.EINVAL, "not a regular file", str(path))
    data = Path(path).read_bytes()
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        before = data[:exc.start]
        line = before.count(b"\n") + 1
        column = exc.start - (before.rfind(b"\n") + 1) + 1
        raise ParseError("expected UTF-8 text", str(path), line, column) from None


def _is_file(path: Path) -> bool:
    """``path.is_file()`` that is False, not an error, for any name the system refuses (too long...)."""
    try:
        return stat.S_ISREG(os.stat(path).st_mode)
    except (OSError, ValueError):
        return False


def _validate(figures: list[Figure], filename: str) -> None:
    for fig in figures:
        try:
            fig.validate()
        except FigureError as exc:
            raise FigureError(f"{filename}: {exc}") from None


def parse_figures(text: str, filename: str = "<string>") -> list[Figure]:
    """Parse ``.fig`` text into validated figures (no geometry is loaded)."""
    figures = _Parser(text, filename).figure_file()
    names = set()
    for fig in figures:
        if fig.name in names:
            raise FigureError(f"{filename}: duplicate figure {fig.name!r}")
        names.add(fig.name)
    _validate(figures, filename)
    return figures


def parse_environment(text: str, filename: str = "<string>",
                      base_dir: str | os.PathLike[str] = ".") -> Environment:
    """Parse ``.env`` text; ``include`` files are read relative to ``base_dir`` (no geometry loaded)."""
    env = _Parser(text, filename).environment_file(Path(base_dir))
    _validate(list(env.figures.values()), filename)
    return env


def load_geometry(figures: list[Figure], base_dir: str | os.PathLike[str], *, require: bool = True,
                  filename: str = "<string>") -> None:
    """Load every segment's psurf mesh, resolving relative names against ``base_dir``.

    A missing file raises FigureError naming the file, figure and segment, unless ``require`` is
    false (the psurf then keeps ``mesh = None``). Each file is read once.
    """
    cache: dict[Path, Mesh] = {}
    for fig in figures:
        for seg in fig.segments.values():
            if seg.psurf is None:
                continue
            path = Path(base_dir) / seg.psurf.source
            if path not in cache:
                if not _is_file(path):
                    if not require:
                        continue
                    raise FigureError(f"{filename}: figure {fig.name!r} segment {seg.name!r}: geometry file "
                                      f"{seg.psurf.source!r} not found (looked for {path})")
                try:
                    cache[path] = load_mesh(path)
                except ImportCADError as exc:  # (a malformed .pss raises ParseError at its own line)
                    raise ImportCADError(f"{filename}: figure {fig.name!r} segment {seg.name!r}: {exc}") from None
                except OSError as exc:
                    raise FigureError(f"{filename}: figure {fig.name!r} segment {seg.name!r}: cannot read "
                                      f"geometry file {seg.psurf.source!r}: {exc.strerror or exc}") from None
            mesh = cache[path]
            seg.psurf.mesh = Mesh(mesh.vertices.copy(), mesh.faces.copy())


def read_figures(path: str | os.PathLike[str], *, require_geometry: bool = True) -> list[Figure]:
    """Read a ``.fig`` file: its figures, validated, with geometry loaded relative to the file."""
    figures = parse_figures(_read_text(path), str(path))
    load_geometry(figures, Path(path).parent, require=require_geometry, filename=str(path))
    return figures


def read_environment(path: str | os.PathLike[str], *, require_geometry: bool = True) -> Environment:
    """Read a ``.env`` file: included and inline figures, placed, with geometry loaded."""
    base = Path(path).parent
    env = parse_environment(_read_text(path), str(path), base)
    load_geometry(list(env.figures.values()), base, require=require_geometry, filename=str(path))
    return env


def load(path: str | os.PathLike[str], *, require_geometry: bool = True) -> Environment:
    """Read a ``.fig`` or ``.env`` file by extension; a ``.fig`` file's figures come as an Environment."""
    ext = Path(path).suffix.lower()
    if ext == ".env":
        return read_environment(path, require_geometry=require_geometry)
    if ext == ".fig":
        env = Environment()
        for fig in read_figures(path, require_geometry=require_geometry):
            env.add(fig)
        return env
    raise FigureError(f"{path}: unknown Peabody file type {ext!r} (expected .fig or .env)")
