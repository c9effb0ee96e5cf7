"""Writer of Peabody text: ``.fig`` (figures) and ``.env`` (environment) files.

Everything is written in centimetres and degrees so that :mod:`jackpy.peabody.reader` reads back
the same figures (transforms to 1e-9): each site and figure location as the canonical product
``rot...(deg) * trans(x,y,z cm)`` (rotate, then translate, in the file's row-vector reading), a
psurf transform as it was read when that still holds (else ``scale * rot * trans`` or
``matrix(...)``), displacements, limits (when not the defaults), mass properties and joint groups.
Files are written atomically.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

from jackpy.atomic import atomic_write_text
from jackpy.errors import FigureError
from jackpy.peabody.groups import LinearDriver, driver_kind
from jackpy.peabody.model import (
    DEFAULT_ROTATION_LIMITS,
    DEFAULT_TRANSLATION_LIMITS,
    Environment,
    Figure,
    HumanMarker,
    Joint,
    Segment,
)
from jackpy.peabody.notation import CM, DEG, compose, decompose, fmt, prims_text
from jackpy.peabody.transforms import close

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_IND = "    "


def _ident(name: str) -> str:
    if not _IDENT.match(name):
        raise FigureError(f"cannot write {name!r}: Peabody names are letters, digits and '_' "
                          "(not starting with a digit)")
    return name


def _quote(text: str) -> str:
    if "\n" in text:
        raise FigureError(f"cannot write {text!r}: a quoted name cannot hold a line break")
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _values(values: Iterable[float], kinds: Iterable[str]) -> str:
    """``(v1, v2)`` in file units: degrees for kind 'R', centimetres (suffix cm) for 'T'."""
    return "(" + ", ".join(fmt(v / DEG) if k == "R" else fmt(v / CM) + "cm"
                           for v, k in zip(values, kinds)) + ")"


def _segment_lines(seg: Segment, relocate: Callable[[str], str]) -> list[str]:
    ind = _IND * 2
    lines = [f"{_IND}segment {_ident(seg.name)} {{"]
    if seg.psurf is not None:
        ps = seg.psurf
        if close(compose(ps.scale_text), ps.transform, 1e-12):
            prims = ps.scale_text
        elif close(ps.transform, np.eye(4), 1e-15):
            prims = []
        else:
            prims = decompose(ps.transform)
        tail = f" * {prims_text(prims)}" if prims else ""
        lines.append(f"{ind}psurf = {_quote(relocate(ps.source))}{tail};")
    if seg.attribute is not None:
        attr = seg.attribute if _IDENT.match(seg.attribute) else _quote(seg.attribute)
        lines.append(f"{ind}attribute = {attr};")
    if seg.mass:
        lines.append(f"{ind}mass = {fmt(seg.mass)}kg;")
    if np.any(seg.com != 0):
        lines.append(f"{ind}com = ({', '.join(fmt(v / CM) for v in seg.com)})cm;")
    if np.any(seg.inertia != 0):
        i = np.asarray(seg.inertia) / (CM * CM)
        six = (i[0, 0], i[1, 1], i[2, 2], i[0, 1], i[0, 2], i[1, 2])
        lines.append(f"{ind}inertia = ({', '.join(fmt(v) for v in six)});  # kg cm^2, about com")
    for site in seg.sites.values():
        lines.append(f"{ind}site {_ident(site.name)}->location = {prims_text(decompose(site.location))};")
    lines.append(f"{_IND}}}")
    return lines


def _joint_lines(j: Joint) -> list[str]:
    ind = _IND * 2
    kinds = [d.kind for d in j.dofs]
    lines = [f"{_IND}joint {_ident(j.name)} {{",
             f"{ind}connect {_ident(j.from_seg)}.{_ident(j.from_site)} to {_ident(j.to_seg)}.{_ident(j.to_site)};"]
    if j.dofs:
        lines.append(f"{ind}type = {j.type_text()};")
        defaults = [DEFAULT_ROTATION_LIMITS if k == "R" else DEFAULT_TRANSLATION_LIMITS for k in kinds]
        if any((d.lower, d.upper) != tuple(lim) for d, lim in zip(j.dofs, defaults)):
            lines.append(f"{ind}lower = {_values(j.lower, kinds)};")
            lines.append(f"{ind}upper = {_values(j.upper, kinds)};")
        if np.any(j.displacement != 0):
            lines.append(f"{ind}displacement = {_values(j.displacement, kinds)};")
    lines.append(f"{_IND}}}")
    return lines


def _group_lines(fig: Figure, name: str) -> list[str]:
    g = fig.groups[name]
    ind = _IND * 2
    kinds = [d.kind for jn in g.joints for d in fig.joint(jn).dofs]
    if isinstance(g.driver, LinearDriver):
        per_unit = np.array([1.0 if k == "R" else DEG / CM for k in kinds])
        matrix = g.driver.matrix * per_unit[:, None]
        driver = "matrix(" + ", ".join("(" + ", ".join(fmt(v) for v in row) + ")" for row in matrix) + ")"
    else:
        kind = driver_kind(g.driver)
        if kind is None:
            raise FigureError(f"figure {fig.name!r}: cannot write group {g.name!r}: its driver "
                              f"{type(g.driver).__name__} has no registered kind (jackpy.peabody.groups."
                              "register_driver)")
        driver = f"{kind}(" + ", ".join(f"{_ident(k)} = {_param(v)}" for k, v in g.driver.to_dict().items()) + ")"
    angle_kinds = ["R"] * g.nangles
    lines = [f"{_IND}group {_ident(g.name)} {{",
             f"{ind}joints = {', '.join(_ident(n) for n in g.joints)};",
             f"{ind}angles = {', '.join(_ident(n) for n in g.angle_names)};",
             f"{ind}driver = {driver};"]
    offset = getattr(g.driver, "offset", None) if isinstance(g.driver, LinearDriver) else None
    if offset is not None and np.any(offset != 0):
        lines.append(f"{ind}offset = {_values(offset, kinds)};")
    lines.append(f"{ind}lower = {_values(g.lower, angle_kinds)};")
    lines.append(f"{ind}upper = {_values(g.upper, angle_kinds)};")
    for row, b in zip(g.A, g.b):
        terms = ""
        for k, (c, a) in enumerate(zip(row, g.angle_names)):
            if k == 0:
                terms = f"{fmt(c)}*{a}"
            else:
                terms += f" {'-' if c < 0 else '+'} {fmt(abs(c))}*{a}"
        lines.append(f"{ind}limit {terms} <= {fmt(b / DEG)};")
    if np.any(g.angles != 0):
        lines.append(f"{ind}displacement = {_values(g.angles, angle_kinds)};")
    lines.append(f"{_IND}}}")
    return lines


def _param(v: object) -> str:
    """A driver parameter as Peabody text: ``true``/``false``, a number or a quoted string."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float, np.integer, np.floating)):
        return fmt(float(v))
    if isinstance(v, str):
        return _quote(v)
    raise FigureError(f"cannot write the driver parameter {v!r} (numbers, true/false or text only)")


def _human_lines(h: HumanMarker) -> list[str]:
    ind = _IND * 2
    lines = [f"{_IND}human {{", f"{ind}population = {_quote(h.population)};", f"{ind}sex = {_quote(h.sex)};",
             f"{ind}percentile = {fmt(h.percentile)};"]
    if h.mass:
        lines.append(f"{ind}mass = {fmt(h.mass)}kg;")
    if h.eye_drop:  # (lengths in metres here: they read back bit for bit)
        lines.append(f"{ind}eye_drop = {fmt(h.eye_drop)}m;")
    lines += [f"{ind}dim {_quote(k)} = {fmt(v)}m;" for k, v in h.dims.items()]
    lines += [f"{ind}override {_quote(k)} = " + (f"{fmt(v)}kg;" if k == "mass" else f"{fmt(v)}m;")
              for k, v in h.overrides.items()]
    return lines + [f"{_IND}}}"]


def _figure_text(fig: Figure, relocate: Callable[[str], str]) -> str:
    lines = [f"figure {_ident(fig.name)} {{"]
    if fig.human is not None:
        lines += _human_lines(fig.human)
    for seg in fig.segments.values():
        lines += _segment_lines(seg, relocate)
    for j in fig.joints.values():
        lines += _joint_lines(j)
    for name in fig.groups:
        lines += _group_lines(fig, name)
    if fig.root is not None:
        lines.append(f"{_IND}root = {_ident(fig.root[0])}.{_ident(fig.root[1])};")
    if not np.array_equal(fig.location, np.eye(4)):
        lines.append(f"{_IND}location = {prims_text(decompose(fig.location))};")
    lines.append("}")
    return "\n".join(lines) + "\n"


def relocator(source_dir: str | os.PathLike[str] | None, out_dir: Path) -> Callable[[str], str]:
    """Map a path relative to ``source_dir`` to one relative to ``out_dir`` (identity if same)."""
    if source_dir is None or Path(source_dir).resolve() == out_dir.resolve():
        return lambda p: p

    def relocate(p: str) -> str:
        if os.path.isabs(p):
            return p
        full = os.path.abspath(os.path.join(source_dir, p))
        return Path(os.path.relpath(full, out_dir.resolve())).as_posix()

    return relocate


def figures_to_text(figures: Iterable[Figure], *, relocate: Callable[[str], str] | None = None) -> str:
    """``.fig`` text of ``figures``; ``relocate`` maps each psurf file name (default: unchanged)."""
    rel = relocate or (lambda p: p)
    return "\n".join(_figure_text(f, rel) for f in figures)


def write_figures(path: str | os.PathLike[str], figures: Iterable[Figure], *,
                  source_dir: str | os.PathLike[str] | None = None) -> None:
    """Write figures to a ``.fig`` file atomically.

    ``source_dir`` is the directory the psurf names are relative to (where they were read from);
    when given, names are rewritten relative to the new file's directory.
    """
    out_dir = Path(path).absolute().parent
    atomic_write_text(path, figures_to_text(figures, relocate=relocator(source_dir, out_dir)))


def environment_to_text(env: Environment, base_dir: str | os.PathLike[str], *,
                        relocate: Callable[[str], str] | None = None) -> str:
    """``.env`` text: ``include`` lines, a ``place`` line for each included figure, inline figures.

    ``base_dir`` is where the includes are found (their figure names decide which figures are
    written as includes); ``relocate`` maps include and psurf file names (default: unchanged).
    """
    from jackpy.peabody.reader import parse_figures, read_text

    rel = relocate or (lambda p: p)
    included: list[str] = []
    lines = ["# jackpy environment: included figure files, their placement, inline figures"]
    for inc in env.includes:
        path = Path(base_dir) / inc
        try:
            names = [f.name for f in parse_figures(read_text(path), str(path))]
        except OSError as exc:
            raise FigureError(f"cannot write environment: included file {inc!r}: "
                              f"{exc.strerror or exc}") from None
        included += names
        lines.append(f"include {_quote(rel(inc))};")
    for name in included:
        if name in env.figures:
            loc = env.figures[name].location
            lines.append(f"place {_ident(name)} at {prims_text(decompose(loc))};")
    text = "\n".join(lines) + "\n"
    inline = [f for f in env.figures.values() if f.name not in included]
    if inline:
        text += "\n" + figures_to_text(inline, relocate=rel)
    return text


def write_environment(path: str | os.PathLike[str], env: Environment, *,
                      source_dir: str | os.PathLike[str] | None = None) -> None:
    """Write an environment to a ``.env`` file atomically.

    ``source_dir`` is the directory its include and psurf names are relative to (default: the new
    file's directory); names are rewritten relative to the new file.
    """
    out_dir = Path(path).absolute().parent
    base = Path(source_dir) if source_dir is not None else out_dir
    atomic_write_text(path, environment_to_text(env, base, relocate=relocator(source_dir, out_dir)))
