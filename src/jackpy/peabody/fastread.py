"""The Peabody reader's fast path: well-formed ``.fig`` text read a statement (or a whole segment or
joint in the writer's form) per regular-expression match.

Each match is anchored where the last one ended (a scanner over the whole text), so the tokens are
never listed one by one; numbers are read by ``float`` from the matched groups, a segment's sites
are found by one ``findall`` and all site matrices of a figure are made in one array. The figures
built are the same, bit for bit, as :mod:`jackpy.peabody.reader`'s token parser builds (the tests
compare them on mutated and generated files).

It covers what the writer emits and what large generated files use: figures with segments (psurf,
attribute, mass, com, inertia, sites), joints (connect, type, displacement, limits), root and
location, with any spacing, and comments between statements. It never reports an error: on
anything else (a group, a human marker, a comment inside a statement, a token out of place, a
value out of range, a duplicate, a graph that is not a tree...) :func:`parse_fast` returns None and
the token parser reads the text, so every error still comes from one place, at its
``file:line:column``. The 2 MB bench file (``peabody-read-2mb``) reads in about 40-50 % of the
token parser's time; the rest is the figure model itself (a Segment, three Sites, a Joint and
three Dofs per segment) and ``Figure.validate``.
"""

from __future__ import annotations

import re

import numpy as np

from jackpy.errors import FigureError
from jackpy.peabody.geometry import Psurf, SourcePosition
from jackpy.peabody.kinematics import MAX_JOINT_DOFS
from jackpy.peabody.lexer import MAX_MAGNITUDE, string_value
from jackpy.peabody.model import DEFAULT_ROTATION_LIMITS, DEFAULT_TRANSLATION_LIMITS, Dof, Figure, Joint, Segment, Site
from jackpy.peabody.notation import (
    ANGLE_UNITS,
    CM,
    DEG,
    LENGTH_UNITS,
    MAX_LINEAR,
    PRIM_ARGS,
    Prim,
    bounded_compose,
    bounded_entries,
    is_rigid_prim,
    rt_entries,
)

#: the token parser's relative slack on MAX_MAGNITUDE for a value after its unit is applied
_LIMIT = MAX_MAGNITUDE * (1.0 + 1e-9)

# ----- the statements, as the lexer splits them into tokens ------------------------------------
#: whitespace and comments between tokens (texts without comments use plain ``\s*+``: faster)
_COMMENTS = r"(?:\s++|#[^\n]*+|//[^\n]*+|/\*(?:[^*]++|\*(?!/))*+\*/)*+"
_NAME = r"[A-Za-z_]\w*+"
_NUM = r"(?:\d++(?:\.\d*+)?+|\.\d++)(?:[eE][+-]?+\d++)?+"  # the lexer's number, maximal munch
_BARE = rf"-?+{_NUM}"  # a number ``float`` reads as the token parser does (sign joined, no unit)
_UNIT = r"(?:cm|mm|m|in|deg|rad)\b"
_STRING = r'"(?:[^"\\\n]|\\.)*+"'
_RT_GROUPS = ("rt_name", "rt_rx", "rt_a", "rt_ax", "rt_ay", "rt_az", "rt_aa", "rt_x", "rt_y", "rt_z")
_BLOCK_JOINT = ("b_joint", "b_c0", "b_c1", "b_c2", "b_c3", "b_type", "b_lo", "b_hi", "b_d")


def _site_rt_pattern(S: str, groups: str = "") -> str:
    """``site NAME->location = [rot...(bare numbers) *] trans(cm or bare numbers);`` after ``S``, its
    name and numbers as 10 groups (see :func:`_site_rt`): ``"named"`` ones (``rt_...``), ``"plain"``
    ones or none."""
    cm, deg = rf"(?:{S}cm\b)?+", rf"(?:{S}deg\b)?+"
    g = [{"named": f"(?P<{n}>", "plain": "("}.get(groups, "(?:") for n in _RT_GROUPS]
    return (rf"{S}site\b{S}{g[0]}{_NAME}){S}->{S}location\b{S}={S}"
            rf"(?:{g[1]}rot[xyz]){S}\({S}{g[2]}{_BARE}){deg}{S}\){S}\*{S}"
            rf"|rot{S}\({S}{g[3]}{_BARE}){S},{S}{g[4]}{_BARE}){S},{S}{g[5]}{_BARE}){S},{S}"
            rf"{g[6]}{_BARE}){deg}{S}\){S}\*{S})?"
            rf"trans{S}\({S}{g[7]}{_BARE}){cm}{S},{S}{g[8]}{_BARE}){cm}{S},{S}{g[9]}{_BARE}){cm}{S}\){S};")


def _statements(S: str) -> re.Pattern[str]:
    """One statement of a figure body (its name: the match's ``lastgroup``), after skipping ``S``;
    first the common forms with their numbers as groups, then the general forms."""
    snum = rf"[-+]?+{S}{_NUM}"
    qty = rf"{snum}(?:{S}{_UNIT})?+"
    values = rf"\({S}{qty}(?:{S},{S}{qty})*+{S}\)(?:{S}{_UNIT})?+"
    prim = rf"(?:trans|scale|rotx|roty|rotz|rot|matrix){S}\({S}{qty}(?:{S},{S}{qty})*+{S}\)"
    xform = rf"{prim}(?:{S}\*{S}{prim})*+"
    dof = rf"[RT]{S}\({S}(?:[xyz]|{snum}{S},{S}{snum}{S},{S}{snum}){S}\)"
    cm, deg, end = rf"(?:{S}cm\b)?+", rf"(?:{S}deg\b)?+", rf"{S};"
    site_rt = _site_rt_pattern(S)

    def bare(group: str) -> str:
        return rf"\({S}(?P<{group}>{_BARE}(?:{S},{S}{_BARE})*+){S}\){end}"

    items = [  # (most frequent first: the alternatives are tried in order)
        # a whole segment or joint as the writer writes it (without psurf, attribute, inertia)
        rf"(?P<seg_block>segment\b{S}(?P<b_seg>{_NAME}){S}\{{"
        rf"(?:{S}mass\b{S}={S}(?P<b_mass>{_BARE})(?:{S}kg\b)?+{end})?"
        rf"(?:{S}com\b{S}={S}\({S}(?P<b_cx>{_BARE}){S},{S}(?P<b_cy>{_BARE}){S},{S}(?P<b_cz>{_BARE}){S}\){cm}{end})?"
        rf"(?P<b_sites>(?:{site_rt})*+){S}\}})",
        rf"(?P<joint_block>joint\b{S}(?P<b_joint>{_NAME}){S}\{{"
        rf"{S}connect\b{S}(?P<b_c0>{_NAME}){S}\.{S}(?P<b_c1>{_NAME}){S}to\b{S}(?P<b_c2>{_NAME}){S}\.{S}"
        rf"(?P<b_c3>{_NAME}){end}"
        rf"{S}type\b{S}={S}(?P<b_type>{dof}(?:{S}\*{S}{dof})*+){end}"
        rf"(?:{S}lower\b{S}={S}{bare('b_lo')})?(?:{S}upper\b{S}={S}{bare('b_hi')})?"
        rf"(?:{S}displacement\b{S}={S}{bare('b_d')})?"
        rf"{S}\}})",
        # one statement
        rf"(?P<site_rt>{_site_rt_pattern(S, 'named')})",
        r"(?P<close>\})",
        rf"(?P<bare>(?P<bare_key>displacement|lower_limits|upper_limits|lower|upper)\b{S}={S}"
        rf"\({S}(?P<bare_v>{_BARE}(?:{S},{S}{_BARE})*+){S}\){end})",
        rf"(?P<seg>segment\b{S}(?P<seg_name>{_NAME}){S}\{{)",
        rf"(?P<joint>joint\b{S}(?P<joint_name>{_NAME}){S}\{{)",
        rf"(?P<connect>connect\b{S}(?P<c0>{_NAME}){S}\.{S}(?P<c1>{_NAME}){S}to\b{S}(?P<c2>{_NAME}){S}\.{S}"
        rf"(?P<c3>{_NAME}){end})",
        rf"(?P<type>type\b{S}={S}(?P<dofs>{dof}(?:{S}\*{S}{dof})*+){end})",
        rf"(?P<com_cm>com\b{S}={S}\({S}(?P<cx>{_BARE}){S},{S}(?P<cy>{_BARE}){S},{S}(?P<cz>{_BARE}){S}\){cm}{end})",
        rf"(?P<mass>mass\b{S}={S}(?P<mass_v>{snum})(?:{S}kg\b)?+{end})",
        rf"(?P<site>site\b{S}(?P<site_name>{_NAME}){S}->{S}location\b{S}={S}(?P<site_x>{xform}){end})",
        rf"(?P<jvalues>(?P<jkey>displacement|lower_limits|upper_limits|lower|upper)\b{S}={S}(?P<jv>{values}){end})",
        rf"(?P<com>com\b{S}={S}(?P<com_v>{values}){end})",
        rf"(?P<inertia>inertia\b{S}={S}(?P<inertia_v>\({S}{snum}(?:{S},{S}{snum})*+{S}\)){end})",
        rf"(?P<psurf>psurf\b{S}={S}(?P<psurf_file>{_STRING})(?:{S}\*{S}(?P<psurf_x>{xform}))?{end})",
        rf"(?P<attribute>attribute\b{S}={S}(?:(?P<attr_name>{_NAME})|(?P<attr_text>{_STRING})){end})",
        rf"(?P<root>root\b{S}={S}(?P<r0>{_NAME}){S}\.{S}(?P<r1>{_NAME}){end})",
        rf"(?P<location>location\b{S}={S}(?P<loc_x>{xform}){end})",
    ]
    return re.compile(rf"{S}(?:{'|'.join(items)})", re.ASCII | re.DOTALL)


_ITEM = {False: _statements(r"\s*+"), True: _statements(_COMMENTS)}
#: the sites of a ``seg_block``: one tuple of :data:`_RT_GROUPS` each
_SITES = {False: re.compile(_site_rt_pattern(r"\s*+", "plain"), re.ASCII),
          True: re.compile(_site_rt_pattern(_COMMENTS, "plain"), re.ASCII | re.DOTALL)}
_FIGURE = {False: re.compile(rf"\s*+(?:figure\b\s*+({_NAME})\s*+\{{|\Z)", re.ASCII),
           True: re.compile(rf"{_COMMENTS}(?:figure\b{_COMMENTS}({_NAME}){_COMMENTS}\{{|\Z)", re.ASCII | re.DOTALL)}
# ----- pieces of a matched statement (one without comments: a comment inside declines) --------
_PRIM_PART = re.compile(r"(\w+)\s*+\(([^)]*+)\)", re.ASCII)
_DOF_PART = re.compile(r"([RT])\s*+\(\s*+(?:([xyz])|([^,)]*+),([^,)]*+),([^,)]*+))\s*+\)", re.ASCII)
_QTY_PART = re.compile(rf"\s*+([-+]?+)\s*+({_NUM})\s*+({_UNIT})?\s*+", re.ASCII)
_JOINT_KEYS = {"displacement": "displacement", "lower": "lower", "upper": "upper",
               "lower_limits": "lower", "upper_limits": "upper"}
#: the statements of a segment (each at most once) by match name
_SEGMENT_ITEMS = {"mass": "mass", "com": "com", "com_cm": "com", "inertia": "inertia", "psurf": "psurf",
                  "attribute": "attribute"}


class _Decline(Exception):
    """The text is not in the fast path's subset (or is wrong): the token parser reads it."""


def parse_fast(text: str, filename: str) -> list[Figure] | None:
    """The validated figures of ``.fig`` text, or None when the token parser must read it."""
    try:
        return _Reader(text, filename).figures()
    except (_Decline, FigureError):
        return None


def _plain(piece: str) -> str:
    """``piece`` if it holds no comment (the part parsers below do not skip comments)."""
    if "/" in piece or "#" in piece:
        raise _Decline
    return piece


def _number(x: str) -> float:
    """One signed number as the statement matched it (the sign may stand apart)."""
    try:
        return float(x)
    except ValueError:  # ("- 5")
        m = _QTY_PART.fullmatch(x)
        if m is None or m[3]:
            raise _Decline from None
        v = float(m[2])
        return -v if m[1] == "-" else v


def _numbers(piece: str) -> list[float]:
    """The comma-separated plain numbers of ``piece``, each within MAX_MAGNITUDE."""
    try:
        values = list(map(float, piece.split(",")))
    except ValueError:
        values = [_number(x) for x in piece.split(",")]
    if max(values) > MAX_MAGNITUDE or min(values) < -MAX_MAGNITUDE:
        raise _Decline
    return values


def _quantities(parts: list[str]) -> tuple[list[float], list[str]]:
    """Numbers (each within MAX_MAGNITUDE) and units ("" for none) of quantity texts."""
    values, units = [], []
    for x in parts:
        m = _QTY_PART.fullmatch(x)
        if m is None:
            raise _Decline
        v = float(m[2])
        if v > MAX_MAGNITUDE:
            raise _Decline
        values.append(-v if m[1] == "-" else v)
        units.append(m[3] or "")
    return values, units


def _value_list(vtext: str) -> tuple[list[float], list[str] | None]:
    """``( quantity {, quantity} ) [unit]``: numbers and units (None: all bare); a trailing unit
    applies to the bare numbers."""
    close = _plain(vtext).rindex(")")
    parts = vtext[1:close].split(",")
    units: list[str] | None = None
    try:
        values = list(map(float, parts))
    except ValueError:
        values, units = _quantities(parts)
    else:
        if max(values) > MAX_MAGNITUDE or min(values) < -MAX_MAGNITUDE:
            raise _Decline
    tail = vtext[close + 1:].strip()
    if tail:
        units = [u or tail for u in units] if units else [tail] * len(values)
    return values, units


def _scaled(v: float, unit: str, units: dict[str, float]) -> float:
    """``v`` in the default unit of ``units`` (cm or deg), within the token parser's range."""
    if unit:
        factor = units.get(unit)
        if factor is None:
            raise _Decline
        v *= factor
        if not -_LIMIT <= v <= _LIMIT:
            raise _Decline
    return v


def _args(piece: str, kinds: str) -> tuple[float, ...]:
    """The arguments of a primitive in file units (cm, deg): lengths ('L') and angles ('A') may
    carry a unit, plain numbers ('N') not."""
    parts = piece.split(",")
    if len(parts) != len(kinds):
        raise _Decline
    args = []
    for x, kind in zip(parts, kinds):
        if kind == "L" and x.endswith("cm"):  # (the default units: the same number, times 1)
            x = x[:-2]
        elif kind == "A" and x.endswith("deg"):
            x = x[:-3]
        try:
            v = float(x)
        except ValueError:  # (another unit, or a sign apart from its number)
            (v,), (unit,) = _quantities([x])
            if unit:
                factor = None if kind == "N" else (LENGTH_UNITS if kind == "L" else ANGLE_UNITS).get(unit)
                if factor is None:
                    raise _Decline from None
                v *= factor
        args.append(v)
    if max(args) > MAX_MAGNITUDE or min(args) < -MAX_MAGNITUDE:
        raise _Decline
    return tuple(args)


def _prims(xtext: str, rigid: bool) -> list[Prim]:
    """The primitives of a matched transform product."""
    prims: list[Prim] = []
    for name, piece in _PRIM_PART.findall(_plain(xtext)):
        args = _args(piece, PRIM_ARGS[name])
        if name == "rot" and max(abs(args[0]), abs(args[1]), abs(args[2])) < 1e-12:
            raise _Decline
        prims.append((name, args))
        if rigid and (name == "scale" or (name == "matrix" and not is_rigid_prim(prims[-1]))):
            raise _Decline
    return prims


def _matrix(prims: list[Prim]) -> np.ndarray:
    """The range-checked matrix of ``prims``."""
    m = bounded_compose(prims)
    if m is None:
        raise _Decline
    return m


def _dofs(dtext: str) -> list[tuple[str, str | np.ndarray]]:
    """The DOFs of a matched joint type: kind and axis (a name, or numbers :class:`Dof` normalises)."""
    out: list[tuple[str, str | np.ndarray]] = []
    for kind, name, x, y, z in _DOF_PART.findall(_plain(dtext)):
        if name:
            out.append((kind, name))
            continue
        axis = np.array(_numbers(f"{x},{y},{z}"))
        if np.max(np.abs(axis)) < 1e-12:
            raise _Decline
        out.append((kind, axis))
    if len(out) > MAX_JOINT_DOFS:
        raise _Decline
    return out


def _si(values: tuple[list[float], list[str] | None], kinds: list[str]) -> list[float]:
    """Joint values (deg for 'R', cm for 'T') in radians and metres, one per DOF."""
    numbers, units = values
    if len(numbers) != len(kinds):
        raise _Decline
    if units is None:
        return [v * DEG if k == "R" else v * CM for v, k in zip(numbers, kinds)]
    return [_scaled(v, u, ANGLE_UNITS) * DEG if k == "R" else _scaled(v, u, LENGTH_UNITS) * CM
            for v, u, k in zip(numbers, units, kinds)]


class _JointText:
    """A joint's statements, built once the whole figure is read (as the token parser does)."""

    __slots__ = ("name", "connect", "dofs", "values")

    def __init__(self, name: str) -> None:
        self.name = name
        self.connect: tuple[str, str, str, str] | None = None
        self.dofs: list[tuple[str, str | np.ndarray]] | None = None
        self.values: dict[str, tuple[list[float], list[str] | None]] = {}

    def build(self) -> Joint:
        if self.connect is None:
            raise _Decline
        spec = self.dofs or []
        kinds = [k for k, _ in spec]
        vals = {key: _si(v, kinds) for key, v in self.values.items()}
        lower, upper = vals.get("lower"), vals.get("upper")
        dofs = []
        for k, (kind, axis) in enumerate(spec):
            lo, hi = DEFAULT_ROTATION_LIMITS if kind == "R" else DEFAULT_TRANSLATION_LIMITS
            lo, hi = (lower[k] if lower else lo), (upper[k] if upper else hi)
            d = Dof.about(kind, axis, lo, hi) if isinstance(axis, str) else Dof(kind, axis, lo, hi)
            if d.lower > d.upper:
                raise _Decline
            dofs.append(d)
        disp = vals.get("displacement")
        if disp is None:
            disp = np.clip(np.zeros(len(dofs)), [d.lower for d in dofs], [d.upper for d in dofs])
        elif not all(d.lower - 1e-9 <= v <= d.upper + 1e-9 for d, v in zip(dofs, disp)):
            raise _Decline
        return Joint(self.name, *self.connect, dofs=dofs, displacement=disp)


class _Reader:
    """One pass over the statements of a text; raises :class:`_Decline` where it cannot go on."""

    def __init__(self, text: str, filename: str) -> None:
        self.text, self.file = text, filename
        self.comments = "#" in text or "//" in text or "/*" in text
        self.types: dict[str, list[tuple[str, str | np.ndarray]]] = {}
        if "/*" in text and text.find("/*", text.rfind("*/") + 1) >= 0:
            raise _Decline  # (an unterminated comment: each try at it would scan to the end)

    def figures(self) -> list[Figure]:
        text, pos, head = self.text, 0, _FIGURE[self.comments].match
        figures: list[Figure] = []
        names: set[str] = set()
        while True:
            m = head(text, pos)
            if m is None:
                raise _Decline
            if m[1] is None:  # (the end of the text)
                return figures
            if m[1] in names:
                raise _Decline
            names.add(m[1])
            fig, pos = self.figure(m[1], m.end())
            fig.validate()
            figures.append(fig)

    def figure(self, name: str, pos: int) -> tuple[Figure, int]:
        """The figure whose body starts at ``pos``, and the position after its ``}``."""
        fig = Figure(name)
        self.sites: list[Site] = []  # (their locations are made at the end, in one array)
        self.locations: list[float] = []
        joints: list[_JointText] = []
        given: set[str] = set()  # (root, location)
        seen: set[str] = set()  # (the current segment's psurf, attribute, mass, com, inertia)
        seg: Segment | None = None
        joint: _JointText | None = None
        match = _ITEM[self.comments].scanner(self.text, pos).match
        while True:
            m = match()
            if m is None:
                raise _Decline
            item = m.lastgroup
            if item == "joint_block":
                if seg is not None or joint is not None:
                    raise _Decline
                joints.append(self.joint_block(m))
            elif item == "seg_block":
                if seg is not None or joint is not None:
                    raise _Decline
                self.segment_block(fig, m)
            elif item == "close":
                if seg is None and joint is None:
                    break
                seg = joint = None
            elif seg is not None:
                if item == "site_rt":
                    self.add_site(seg, m["rt_name"], _site_rt(m.group(*_RT_GROUPS)))
                elif item == "site":
                    self.add_site(seg, m["site_name"], bounded_entries(_prims(m["site_x"], True)))
                else:
                    key = _SEGMENT_ITEMS.get(item)  # type: ignore[arg-type]
                    if key is None or key in seen:
                        raise _Decline
                    seen.add(key)
                    self.segment_item(seg, m, item)
            elif joint is not None:
                if item == "bare" or item == "jvalues":
                    key = _JOINT_KEYS[m["bare_key"] or m["jkey"]]
                    if key in joint.values:
                        raise _Decline
                    joint.values[key] = _bare(m["bare_v"]) if item == "bare" else _value_list(m["jv"])
                elif item == "connect" and joint.connect is None:
                    joint.connect = (m["c0"], m["c1"], m["c2"], m["c3"])
                elif item == "type" and joint.dofs is None:
                    joint.dofs = self.dofs(m["dofs"])
                else:
                    raise _Decline
            elif item == "seg":
                seg = self.new_segment(fig, m["seg_name"])
                seen = set()
            elif item == "joint":
                joint = _JointText(m["joint_name"])
                joints.append(joint)
            elif item in ("root", "location") and item not in given:
                given.add(item)
                if item == "root":
                    fig.root = (m["r0"], m["r1"])
                else:
                    fig.location = _matrix(_prims(m["loc_x"], True))
            else:
                raise _Decline
        for site, location in zip(self.sites, np.array(self.locations).reshape(-1, 4, 4)):
            site.location = location
        for jt in joints:
            fig.add_joint(jt.build())
        return fig, m.end()

    def new_segment(self, fig: Figure, name: str) -> Segment:
        if name in fig.segments:
            raise _Decline
        return fig.add_segment(Segment(name))

    def add_site(self, seg: Segment, name: str, entries: list[float] | None) -> None:
        """Site ``name`` of ``seg`` with the 16 ``entries`` of its location (None: out of range)."""
        if entries is None or name in seg.sites:
            raise _Decline
        seg.sites[name] = site = Site(name, None)  # type: ignore[arg-type]
        self.sites.append(site)
        self.locations += entries

    def dofs(self, dtext: str) -> list[tuple[str, str | np.ndarray]]:
        """:func:`_dofs`, once per distinct text (joint types repeat)."""
        dofs = self.types.get(dtext)
        if dofs is None:
            dofs = self.types[dtext] = _dofs(dtext)
        return dofs

    def segment_block(self, fig: Figure, m: re.Match[str]) -> None:
        """A ``seg_block``: ``segment NAME { [mass] [com] {site} }`` in the common forms."""
        seg = self.new_segment(fig, m["b_seg"])
        mass, cx = m["b_mass"], m["b_cx"]
        if mass is not None:
            seg.mass = float(mass)
            if not 0 <= seg.mass <= MAX_MAGNITUDE:  # (-0.0 passes, as in the token parser)
                raise _Decline
        if cx is not None:
            seg.com = _com([cx, m["b_cy"], m["b_cz"]])
        for groups in _SITES[self.comments].findall(m["b_sites"]):
            self.add_site(seg, groups[0], _site_rt(groups))

    def joint_block(self, m: re.Match[str]) -> _JointText:
        """A ``joint_block``: ``joint NAME { connect; type; [lower;] [upper;] [displacement;] }``."""
        name, c0, c1, c2, c3, dtext, lower, upper, disp = m.group(*_BLOCK_JOINT)
        joint = _JointText(name)
        joint.connect = (c0, c1, c2, c3)
        joint.dofs = self.dofs(dtext)
        for key, vtext in (("lower", lower), ("upper", upper), ("displacement", disp)):
            if vtext is not None:
                joint.values[key] = _bare(vtext)
        return joint

    def segment_item(self, seg: Segment, m: re.Match[str], item: str) -> None:
        """``mass``, ``com``, ``inertia``, ``psurf`` or ``attribute`` of ``seg``."""
        if item == "com_cm":
            seg.com = _com([m["cx"], m["cy"], m["cz"]])
        elif item == "mass":
            mass = _number(_plain(m["mass_v"]))
            if not 0 <= mass <= MAX_MAGNITUDE:  # (-0.0 passes, as in the token parser)
                raise _Decline
            seg.mass = mass
        elif item == "com":
            numbers, units = _value_list(m["com_v"])
            if len(numbers) != 3:
                raise _Decline
            if units is not None:
                numbers = [_scaled(v, u, LENGTH_UNITS) for v, u in zip(numbers, units)]
            seg.com = np.array(numbers) * CM
        elif item == "inertia":
            values = _numbers(_plain(m["inertia_v"])[1:-1])
            if len(values) != 6:
                raise _Decline
            ixx, iyy, izz, ixy, ixz, iyz = (v * CM * CM for v in values)
            seg.inertia = np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])
        elif item == "psurf":
            prims = _prims(m["psurf_x"], False) if m["psurf_x"] else []
            matrix = _matrix(prims) if prims else np.eye(4)
            seg.psurf = Psurf(string_value(m["psurf_file"]), matrix, scale_text=prims,
                              origin=SourcePosition.at_offset(self.file, self.text, m.start("psurf_file")))
        else:
            seg.attribute = m["attr_name"] or string_value(m["attr_text"])


def _com(texts: list[str]) -> np.ndarray:
    """A centre of mass from three bare numbers in cm (or with the unit cm: the same numbers)."""
    com = [float(t) for t in texts]
    if max(com) > MAX_MAGNITUDE or min(com) < -MAX_MAGNITUDE:
        raise _Decline
    return np.array(com) * CM


def _site_rt(groups: tuple[str, ...]) -> list[float]:
    """The location entries (:func:`~jackpy.peabody.notation.rt_entries`) of a ``site_rt`` match's
    :data:`_RT_GROUPS`: ``[rot...(bare numbers) *] trans(cm or bare numbers)``."""
    _, rx, a, ax, ay, az, aa, x, y, z = groups
    t = (float(x), float(y), float(z))
    if max(abs(t[0]), abs(t[1]), abs(t[2])) > MAX_LINEAR:
        raise _Decline
    if rx:
        angle = float(a)
        if not -MAX_MAGNITUDE <= angle <= MAX_MAGNITUDE:
            raise _Decline
        return rt_entries((rx, (angle,)), t)
    if ax:
        args = (float(ax), float(ay), float(az), float(aa))
        if max(args) > MAX_MAGNITUDE or min(args) < -MAX_MAGNITUDE or max(map(abs, args[:3])) < 1e-12:
            raise _Decline
        return rt_entries(("rot", args), t)
    return rt_entries(None, t)


def _bare(vtext: str) -> tuple[list[float], None]:
    """Numbers of a ``bare`` joint value list (signs joined, no units)."""
    try:
        values = list(map(float, vtext.split(",")))
    except ValueError:  # (a comment between them)
        return _value_list(f"({vtext})")  # type: ignore[return-value]
    if max(values) > MAX_MAGNITUDE or min(values) < -MAX_MAGNITUDE:
        raise _Decline
    return values, None
