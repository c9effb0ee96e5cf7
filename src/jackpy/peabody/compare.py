"""Structural comparison of figures (used by round-trip tests and file tools)."""

from __future__ import annotations

import os

import numpy as np

from jackpy.peabody.groups import LinearDriver, driver_kind
from jackpy.peabody.model import Figure


def figure_differences(a: Figure, b: Figure, tol: float = 1e-9,
                       dirs: tuple[str | os.PathLike[str], str | os.PathLike[str]] | None = None,
                       rtol: float = 0.0) -> list[str]:
    """What differs between two figures, one line per difference (empty when equal).

    Compares names, root, location, segments (psurf file and transform, attribute, mass, com,
    inertia, sites), joints (connection, DOF kinds, axes, limits, displacement) and groups (joints,
    angles, driver kind and parameters, limits) and the human marker. Numbers agree within ``tol`` (metres, radians). With ``dirs`` the psurf
    file names are compared as paths resolved against ``dirs[0]`` and ``dirs[1]``; ``rtol`` adds a
    relative tolerance (for figures with very large numbers).
    """
    out: list[str] = []

    def close(what: str, x: object, y: object) -> None:
        xa, ya = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        if xa.shape != ya.shape or not np.allclose(xa, ya, atol=tol, rtol=rtol):
            out.append(f"{what}: {xa.tolist()} != {ya.tolist()}")

    def same(what: str, x: object, y: object) -> None:
        if x != y:
            out.append(f"{what}: {x!r} != {y!r}")

    def resolved(base: str | os.PathLike[str] | None, p: str) -> str:
        return p if base is None else os.path.normpath(os.path.join(os.path.abspath(base), p))

    same("name", a.name, b.name)
    same("root", a.root, b.root)
    close("location", a.location, b.location)
    same("segments", list(a.segments), list(b.segments))
    for name in a.segments.keys() & b.segments.keys():
        sa, sb, w = a.segments[name], b.segments[name], f"segment {name}"
        same(f"{w} psurf", sa.psurf is None, sb.psurf is None)
        if sa.psurf is not None and sb.psurf is not None:
            da, db = dirs if dirs is not None else (None, None)
            same(f"{w} psurf source", resolved(da, sa.psurf.source), resolved(db, sb.psurf.source))
            close(f"{w} psurf transform", sa.psurf.transform, sb.psurf.transform)
        same(f"{w} attribute", sa.attribute, sb.attribute)
        close(f"{w} mass", sa.mass, sb.mass)
        close(f"{w} com", sa.com, sb.com)
        close(f"{w} inertia", sa.inertia, sb.inertia)
        same(f"{w} sites", list(sa.sites), list(sb.sites))
        for site in sa.sites.keys() & sb.sites.keys():
            close(f"{w} site {site}", sa.sites[site].location, sb.sites[site].location)
    same("joints", list(a.joints), list(b.joints))
    for name in a.joints.keys() & b.joints.keys():
        ja, jb, w = a.joints[name], b.joints[name], f"joint {name}"
        same(f"{w} connect", (ja.from_seg, ja.from_site, ja.to_seg, ja.to_site),
             (jb.from_seg, jb.from_site, jb.to_seg, jb.to_site))
        same(f"{w} kinds", [d.kind for d in ja.dofs], [d.kind for d in jb.dofs])
        if ja.ndof == jb.ndof:
            close(f"{w} axes", [d.axis for d in ja.dofs], [d.axis for d in jb.dofs])
            close(f"{w} lower", ja.lower, jb.lower)
            close(f"{w} upper", ja.upper, jb.upper)
            close(f"{w} displacement", ja.displacement, jb.displacement)
    same("groups", list(a.groups), list(b.groups))
    for name in a.groups.keys() & b.groups.keys():
        ga, gb, w = a.groups[name], b.groups[name], f"group {name}"
        same(f"{w} joints", ga.joints, gb.joints)
        same(f"{w} angles", ga.angle_names, gb.angle_names)
        for attr in ("lower", "upper", "A", "b", "angles"):
            close(f"{w} {attr}", getattr(ga, attr), getattr(gb, attr))
        ka, kb = driver_kind(ga.driver), driver_kind(gb.driver)
        same(f"{w} driver", ka or type(ga.driver).__name__, kb or type(gb.driver).__name__)
        if isinstance(ga.driver, LinearDriver) and isinstance(gb.driver, LinearDriver):
            for attr in ("matrix", "offset"):
                close(f"{w} driver {attr}", getattr(ga.driver, attr), getattr(gb.driver, attr))
        elif ka is not None and ka == kb:
            same(f"{w} driver parameters", ga.driver.to_dict(), gb.driver.to_dict())  # type: ignore[attr-defined]
    ha, hb = a.human, b.human
    same("human", ha is None, hb is None)
    if ha is not None and hb is not None:  # the marker's names exactly, its numbers within tol
        same("human", (ha.population, ha.sex), (hb.population, hb.sex))
        close("human percentile", ha.percentile, hb.percentile)
        for attr in ("mass", "eye_drop"):
            close(f"human {attr}", getattr(ha, attr), getattr(hb, attr))
        for attr in ("dims", "overrides"):
            da, db = getattr(ha, attr), getattr(hb, attr)
            same(f"human {attr}", sorted(da), sorted(db))
            if sorted(da) == sorted(db):
                close(f"human {attr}", [da[k] for k in sorted(da)], [db[k] for k in sorted(db)])
    return out
