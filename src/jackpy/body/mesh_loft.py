"""Closed lofted meshes for the body surfaces: superellipse rings, tubes with caps, tapered limbs.

All functions work in world coordinates of the zero pose; :mod:`jackpy.body.shapes` moves the results
into the segment frames. Every mesh returned is closed and oriented outward (positive signed volume).
"""

from __future__ import annotations

import numpy as np

from jackpy.peabody.geometry import Mesh


def superellipse_ring(centre: np.ndarray, u: np.ndarray, v: np.ndarray, ru: float, rv: float,
                      n: int, exponent: float = 2.0) -> np.ndarray:
    """``n`` points (n,3) of the superellipse ``|x/ru|^e + |y/rv|^e = 1`` in the plane (u, v) at ``centre``."""
    cu, sv = superellipse_unit(n, exponent)
    return centre + np.outer(ru * cu, u) + np.outer(rv * sv, v)


def superellipse_unit(n: int, exponent: float = 2.0) -> tuple[np.ndarray, np.ndarray]:
    """Unit superellipse coordinates (cos-like, sin-like) of ``n`` points, the first on +u."""
    a = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    c, s = np.cos(a), np.sin(a)
    k = 2.0 / exponent
    return np.sign(c) * np.abs(c) ** k, np.sign(s) * np.abs(s) ** k


def tube(rings: np.ndarray, start: np.ndarray | None = None, end: np.ndarray | None = None) -> Mesh:
    """Closed mesh from rings (m, n, 3): quads between rings, fans to ``start``/``end`` (default: flat caps).

    Faces are oriented outward (counter-clockwise seen from outside).
    """
    if start is None:  # flat cap: a ring inset by 0.5 % keeps the cap out of the side normals
        start = rings[0].mean(axis=0)
        rings = np.concatenate([(start + 0.995 * (rings[0] - start))[None], rings])
    if end is None:
        end = rings[-1].mean(axis=0)
        rings = np.concatenate([rings, (end + 0.995 * (rings[-1] - end))[None]])
    m, n, _ = rings.shape
    start, end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    verts = np.vstack([rings.reshape(-1, 3), start, end])
    i = np.arange(n)
    j = (i + 1) % n
    faces = []
    for r in range(m - 1):
        a, b = r * n + i, r * n + j
        c, d = (r + 1) * n + i, (r + 1) * n + j
        faces += [np.stack([a, b, d], 1), np.stack([a, d, c], 1)]
    s_idx, e_idx = m * n, m * n + 1
    faces.append(np.stack([np.full(n, s_idx), j, i], 1))
    faces.append(np.stack([np.full(n, e_idx), (m - 1) * n + i, (m - 1) * n + j], 1))
    f = np.vstack(faces)
    mesh = Mesh(verts, f)
    if signed_volume(mesh) < 0:
        mesh = Mesh(verts, f[:, ::-1].copy())
    return mesh


def merge(*meshes: Mesh) -> Mesh:
    """One mesh made of several closed components (each stays closed and outward)."""
    verts, faces, base = [], [], 0
    for m in meshes:
        verts.append(m.vertices)
        faces.append(m.faces + base)
        base += len(m.vertices)
    return Mesh(np.vstack(verts), np.vstack(faces))


def signed_volume(mesh: Mesh) -> float:
    """Signed volume (m^3) of a closed mesh; positive when its faces point outward."""
    v = mesh.vertices[mesh.faces]
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)


def basis(d: np.ndarray, hint: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors perpendicular to ``d``; the first as close to ``hint`` as possible."""
    u = hint - np.dot(hint, d) * d
    if np.linalg.norm(u) < 1e-9:
        u = np.cross(d, [1.0, 0.0, 0.0] if abs(d[0]) < 0.9 else [0.0, 1.0, 0.0])
    u = u / np.linalg.norm(u)
    return u, np.cross(d, u)


def limb(p0: np.ndarray, p1: np.ndarray, stations: list[tuple[float, float, float]], n: int = 16,
         hint: tuple[float, float, float] = (1.0, 0.0, 0.0), cap0: float = 1.0, cap1: float = 1.0,
         offsets: list[tuple[float, float, float]] | None = None, exponent: float = 2.0,
         step: float = 0.025, cap_rings: tuple[int, int] = (3, 3)) -> Mesh:
    """A rounded limb from ``p0`` to ``p1``: ``stations`` are ``(t, r_u, r_v)`` (t in [0,1] along the
    axis, radii along ``hint`` and across); ``cap0``/``cap1`` scale the rounded end caps (0 = flat)
    built of ``cap_rings`` rings; ``offsets`` optionally shift each station's centre ``(t, du, dv)``
    (interpolated); rings are at most ``step`` metres apart."""
    p0, p1 = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
    axis = p1 - p0
    length = np.linalg.norm(axis)
    d = axis / length
    u, v = basis(d, np.asarray(hint, dtype=float))
    st = np.array(stations, dtype=float)
    ts = [st[0, 0]]
    for a, b in zip(st[:-1, 0], st[1:, 0]):
        k = max(1, int(np.ceil((b - a) * length / step)))
        ts += list(np.linspace(a, b, k + 1)[1:])
    ts = np.array(ts)
    ru = np.interp(ts, st[:, 0], st[:, 1])
    rv = np.interp(ts, st[:, 0], st[:, 2])
    pos = ts * length
    rings_s, rings_u, rings_v = list(pos), list(ru), list(rv)
    # rounded caps: quarter-ellipse of depth cap * radius beyond each end
    for end, sign, cap, nr in ((0, -1.0, cap0, cap_rings[0]), (-1, 1.0, cap1, cap_rings[1])):
        if cap <= 0:
            continue
        r_end = 0.5 * (ru[end] + rv[end])
        extra = []
        for a in np.linspace(0.0, np.pi / 2, nr + 2)[1:-1]:
            extra.append((pos[end] + sign * cap * r_end * np.sin(a), ru[end] * np.cos(a), rv[end] * np.cos(a)))
        if sign < 0:
            for s, a_, b_ in extra:
                rings_s.insert(0, s), rings_u.insert(0, a_), rings_v.insert(0, b_)
        else:
            for s, a_, b_ in extra:
                rings_s.append(s), rings_u.append(a_), rings_v.append(b_)
    s_arr = np.array(rings_s)
    tt = s_arr / length
    du = dv = np.zeros_like(tt)
    if offsets:
        off = np.array(offsets, dtype=float)
        du, dv = np.interp(tt, off[:, 0], off[:, 1]), np.interp(tt, off[:, 0], off[:, 2])
    rings = np.stack([superellipse_ring(p0 + s * d + a * u + b * v, u, v, ru_, rv_, n, exponent)
                      for s, ru_, rv_, a, b in zip(s_arr, rings_u, rings_v, du, dv)])
    r0, r1 = 0.5 * (ru[0] + rv[0]), 0.5 * (ru[-1] + rv[-1])
    start = p0 + (pos[0] - cap0 * r0) * d + du[0] * u + dv[0] * v if cap0 > 0 else None
    end = p0 + (pos[-1] + cap1 * r1) * d + du[-1] * u + dv[-1] * v if cap1 > 0 else None
    return tube(rings, start, end)
