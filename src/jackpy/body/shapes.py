"""Segment surfaces generated from the body dimensions: lofted superellipse sections, closed meshes.

Every shape is built in world coordinates of the zero pose (see :mod:`jackpy.body.skeleton`) as rings
of superellipse cross-sections along a path, closed at both ends (rounded or flat caps), then moved
into its segment's frame. The torso is one profile (width, depth, centre as functions of height,
through the hip, waist, chest, armpit and neck-base measurements) cut into one slab per vertebra;
limbs taper between their proximal and distal measurements with muscle bulges; the head is a
displaced ellipsoid with a nose, brow, eye sockets, ears and a narrower jaw; hands have a rounded palm
and capsule fingers; the feet are shoe-shaped. About 20k triangles for the whole body.
"""

from __future__ import annotations

import numpy as np

from jackpy.body.sass import BodySpec
from jackpy.body.skeleton import (
    BUCHHOLZ,
    DIGITS,
    FINGERS,
    FOREARM_PARTS,
    SIDES,
    Skeleton,
)
from jackpy.peabody.geometry import Mesh

#: display attribute (X11 colour name) per body region
ATTRIBUTES = {"skin": "peachpuff", "shirt": "steelblue", "trousers": "darkslategray",
              "shoe": "saddlebrown", "eye": "white"}
AROUND_TORSO, AROUND_LIMB, AROUND_DIGIT = 28, 16, 10


def superellipse_ring(centre: np.ndarray, u: np.ndarray, v: np.ndarray, ru: float, rv: float,
                      n: int, exponent: float = 2.0) -> np.ndarray:
    """``n`` points (n,3) of the superellipse ``|x/ru|^e + |y/rv|^e = 1`` in the plane (u, v) at ``centre``."""
    a = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    c, s = np.cos(a), np.sin(a)
    k = 2.0 / exponent
    cu = np.sign(c) * np.abs(c) ** k
    sv = np.sign(s) * np.abs(s) ** k
    return centre + np.outer(ru * cu, u) + np.outer(rv * sv, v)


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


def signed_volume(mesh: Mesh) -> float:
    """Signed volume (m^3) of a closed mesh; positive when its faces point outward."""
    v = mesh.vertices[mesh.faces]
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)


def _basis(d: np.ndarray, hint: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors perpendicular to ``d``; the first as close to ``hint`` as possible."""
    u = hint - np.dot(hint, d) * d
    if np.linalg.norm(u) < 1e-9:
        u = np.cross(d, [1.0, 0.0, 0.0] if abs(d[0]) < 0.9 else [0.0, 1.0, 0.0])
    u = u / np.linalg.norm(u)
    return u, np.cross(d, u)


def limb(p0: np.ndarray, p1: np.ndarray, stations: list[tuple[float, float, float]], n: int = AROUND_LIMB,
         hint: tuple[float, float, float] = (1.0, 0.0, 0.0), cap0: float = 1.0, cap1: float = 1.0,
         offsets: list[tuple[float, float, float]] | None = None, exponent: float = 2.0) -> Mesh:
    """A rounded limb from ``p0`` to ``p1``: ``stations`` are ``(t, r_u, r_v)`` (t in [0,1] along the
    axis, radii along ``hint`` and across); ``cap0``/``cap1`` scale the rounded end caps (0 = flat);
    ``offsets`` optionally shift each station's centre ``(t, du, dv)`` (interpolated)."""
    p0, p1 = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
    axis = p1 - p0
    length = np.linalg.norm(axis)
    d = axis / length
    u, v = _basis(d, np.asarray(hint, dtype=float))
    st = np.array(stations, dtype=float)
    ts = [st[0, 0]]
    for a, b in zip(st[:-1, 0], st[1:, 0]):  # densify to ~2.5 cm steps
        k = max(1, int(np.ceil((b - a) * length / 0.025)))
        ts += list(np.linspace(a, b, k + 1)[1:])
    ts = np.array(ts)
    ru = np.interp(ts, st[:, 0], st[:, 1])
    rv = np.interp(ts, st[:, 0], st[:, 2])
    pos = ts * length
    rings_s, rings_u, rings_v = list(pos), list(ru), list(rv)
    # rounded caps: quarter-ellipse of depth cap * radius beyond each end
    for end, sign, cap in ((0, -1.0, cap0), (-1, 1.0, cap1)):
        if cap <= 0:
            continue
        r_end = 0.5 * (ru[end] + rv[end])
        extra = []
        for a in np.linspace(0.0, np.pi / 2, 5)[1:-1]:
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
    start = p0 + (s_arr[0] - cap0 * 0.13 * 0.5 * (ru[0] + rv[0])) * d + du[0] * u + dv[0] * v if cap0 > 0 else None
    end = p0 + (s_arr[-1] + cap1 * 0.13 * 0.5 * (ru[-1] + rv[-1])) * d + du[-1] * u + dv[-1] * v if cap1 > 0 else None
    return tube(rings, start, end)


def _torso_profile(spec: BodySpec, sk: Skeleton) -> dict[str, np.ndarray]:
    """Key heights (y) and (half width, half depth, centre z) of the torso surface."""
    d = spec.dims
    s = spec.stature / 1.756
    yh = sk.points["hip_y"][1]
    yt = sk.points["spine_top"][1]
    rows = [  # y, full width, full depth, centre z
        (yh - 0.085 * s, 0.62 * d["hip.breadth"], 0.62 * d["buttock.depth"], -0.01 * s),
        (yh - 0.04 * s, 0.93 * d["hip.breadth"], 0.9 * d["buttock.depth"], -0.015 * s),
        (yh + 0.01 * s, d["hip.breadth"], d["buttock.depth"], -0.02 * s),
        (yh + 0.08 * s, 0.5 * (d["hip.breadth"] + d["waist.breadth"]), 0.5 * (d["buttock.depth"] + d["waist.depth"]), -0.01 * s),
        (yh + 0.16 * s, d["waist.breadth"], d["waist.depth"], 0.0),
        (yt - 0.30 * s, 0.5 * (d["waist.breadth"] + d["chest.breadth"]), 0.5 * (d["waist.depth"] + d["chest.depth"]), 0.0),
        (yt - 0.22 * s, d["chest.breadth"], d["chest.depth"], 0.01 * s),
        (yt - 0.13 * s, 1.04 * d["chest.breadth"], 0.95 * d["chest.depth"], 0.0),
        (yt - 0.06 * s, 0.95 * d["chest.breadth"], 0.8 * d["chest.depth"], -0.01 * s),
        (yt - 0.01 * s, 0.7 * d["chest.breadth"], 0.62 * d["chest.depth"], -0.02 * s),
        (yt + 0.02 * s, 1.15 * d["neck.breadth"], 1.05 * d["neck.breadth"], -0.02 * s),
    ]
    a = np.array(rows)
    return {"y": a[:, 0], "rx": a[:, 1] / 2, "rz": a[:, 2] / 2, "cz": a[:, 3]}


def _torso_slab(prof: dict[str, np.ndarray], y0: float, y1: float, cap0: bool, cap1: bool) -> Mesh:
    ys = np.linspace(y0, y1, max(2, int(np.ceil((y1 - y0) / 0.02)) + 1))
    rx, rz, cz = (np.interp(ys, prof["y"], prof[k]) for k in ("rx", "rz", "cz"))
    ex, ez = np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])
    rings = [superellipse_ring(np.array([0.0, y, c]), ex, ez, a, b, AROUND_TORSO, 2.3)
             for y, a, b, c in zip(ys, rx, rz, cz)]
    start = np.array([0.0, ys[0] - 0.6 * rz[0], cz[0]]) if cap0 else None
    end = np.array([0.0, ys[-1] + 0.25 * rz[-1], cz[-1]]) if cap1 else None
    if cap0:  # rounded crotch / seat
        for f in (0.95, 0.8, 0.55):
            rings.insert(0, superellipse_ring(np.array([0.0, ys[0] - 0.6 * rz[0] * np.sqrt(1 - f * f), cz[0]]),
                                              ex, ez, rx[0] * f, rz[0] * f, AROUND_TORSO, 2.3))
    return tube(np.stack(rings), start, end)


def _head(spec: BodySpec, sk: Skeleton) -> Mesh:
    d = spec.dims
    s = spec.stature / 1.756
    vertex = sk.points["vertex"]
    view = sk.points["view"]
    ax, ay, az = d["head.breadth"] / 2, 0.118 * s, d["head.length"] / 2
    c = np.array([0.0, vertex[1] - ay, view[2] + 0.012 - az])
    nlat, nlon = 24, 32
    lat = np.linspace(0, np.pi, nlat + 1)[1:-1]
    lon = np.linspace(0, 2 * np.pi, nlon, endpoint=False)
    L, O = np.meshgrid(lat, lon, indexing="ij")
    dirs = np.stack([np.sin(L) * np.sin(O), np.cos(L), np.sin(L) * np.cos(O)], axis=-1)  # O=0 -> +z front
    p = dirs * [ax, ay, az]
    y_rel = p[..., 1] / ay
    jaw = np.clip(-y_rel, 0, 1)  # 0 above the centre, 1 at the chin
    p[..., 0] *= 1.0 - 0.28 * jaw ** 1.5
    p[..., 2] *= 1.0 - 0.12 * jaw * (p[..., 2] < 0)
    world = c + p

    def bump(centre: np.ndarray, sigma: np.ndarray, amount: float) -> np.ndarray:
        q = (world - centre) / sigma
        return amount * np.exp(-0.5 * (q ** 2).sum(axis=-1))

    front = np.array([0.0, 0.0, 1.0])
    eye_y = view[1]
    nose = bump(np.array([0.0, eye_y - 0.03 * s, c[2] + az]), np.array([0.011, 0.022, 0.03]) * s, 0.022 * s)
    brow = bump(np.array([0.0, eye_y + 0.017 * s, c[2] + az]), np.array([0.05, 0.01, 0.03]) * s, 0.006 * s)
    chin = bump(np.array([0.0, c[1] - 0.9 * ay, c[2] + 0.8 * az]), np.array([0.02, 0.015, 0.03]) * s, 0.008 * s)
    sockets = sum(bump(np.array([sx * d["eyes.breadth"] / 2, eye_y, c[2] + az]), np.array([0.014, 0.011, 0.03]) * s,
                       -0.009 * s) for _, sx in SIDES)
    ears = sum(bump(np.array([sx * ax, eye_y - 0.02 * s, c[2] - 0.01 * s]), np.array([0.012, 0.025, 0.012]) * s,
                    0.012 * s) for _, sx in SIDES)
    world = world + (nose + brow + chin + sockets)[..., None] * front
    world = world + ears[..., None] * np.stack([np.sign(world[..., 0]), 0 * world[..., 0], 0 * world[..., 0]], -1)
    return tube(world, c + [0.0, ay, 0.0], c - [0.0, ay * 1.0, 0.0])


def _sphere(centre: np.ndarray, r: float, n: int = 12) -> Mesh:
    lat = np.linspace(0, np.pi, n + 1)[1:-1]
    rings = np.stack([superellipse_ring(centre + [0.0, r * np.cos(a), 0.0], np.array([1.0, 0, 0]),
                                        np.array([0, 0, 1.0]), r * np.sin(a), r * np.sin(a), n) for a in lat])
    return tube(rings, centre + [0.0, r, 0.0], centre - [0.0, r, 0.0])


def body_shapes(spec: BodySpec, sk: Skeleton) -> dict[str, tuple[Mesh, str]]:
    """``{segment: (mesh in the segment frame, attribute)}`` for every segment that has a surface."""
    d = spec.dims
    s = spec.stature / 1.756
    pts, org = sk.points, sk.origins
    out: dict[str, tuple[Mesh, str]] = {}

    def put(seg: str, mesh: Mesh, region: str) -> None:
        out[seg] = (Mesh(mesh.vertices - org[seg], mesh.faces), ATTRIBUTES[region])

    # torso slabs, one per vertebra, meeting at the joint heights (overlapping coincident surfaces
    # would z-fight); the joint centres lie near the back, so bending opens only shallow creases
    prof = _torso_profile(spec, sk)
    spine = ["pelvis", "l5", "l4", "l3", "l2", "l1"] + [f"t{k}" for k in range(12, 0, -1)]
    bounds = [prof["y"][0]] + [org[n][1] for n in spine[1:]] + [prof["y"][-1]]
    for k, name in enumerate(spine):
        put(name, _torso_slab(prof, bounds[k], bounds[k + 1], k == 0, k == len(spine) - 1),
            "trousers" if k <= 2 else "shirt")
    nb = d["neck.breadth"] / 2
    put("neck", limb(pts["spine_top"] + [0, -0.03 * s, 0.015 * s], pts["head_joint"] + [0, 0.02 * s, 0.01 * s],
                     [(0, nb * 1.05, nb * 1.0), (1, nb * 0.95, nb * 0.95)], AROUND_LIMB, cap0=0, cap1=0), "skin")
    put("head", _head(spec, sk), "skin")
    for side, sx in SIDES:
        eye = org[f"{side}_eye"]
        put(f"{side}_eye", _sphere(eye, 0.0125 * s), "eye")
        _arm_shapes(spec, sk, side, sx, put)
        _leg_shapes(spec, sk, side, sx, put)
    return out


def _arm_shapes(spec: BodySpec, sk: Skeleton, side: str, sx: float, put) -> None:
    d = spec.dims
    s = spec.stature / 1.756
    pts, org = sk.points, sk.origins
    sh = pts[f"{side}_shoulder"]
    ub, fb, wb = d["upper_arm.breadth"] / 2, d["forearm.breadth"] / 2, d["wrist.breadth"] / 2
    # shoulder top (trapezius to deltoid) on the clavicle
    neck_side = np.array([sx * 0.045 * s, sk.points["spine_top"][1] - 0.005 * s, -0.025 * s])
    put(f"{side}_clavicle", limb(neck_side, sh + [sx * 0.01 * s, 0.02 * s, 0.0],
                                 [(0, 0.035 * s, 0.045 * s), (0.6, 0.045 * s, 0.055 * s), (1, 0.05 * s, 0.055 * s)],
                                 AROUND_LIMB, hint=np.array([0.0, 1.0, 0.0]), cap0=0.6, cap1=1.0), "shirt")
    elbow = org[f"{side}_forearm"]
    put(f"{side}_upper_arm", limb(sh + [0, 0.015 * s, 0], elbow,
                                  [(0, 1.12 * ub, 1.12 * ub), (0.3, 1.05 * ub, ub), (0.6, 0.92 * ub, 0.95 * ub),
                                   (1, 0.86 * fb, 0.82 * fb)], hint=np.array([1.0, 0.0, 0.0])), "shirt")
    wrist = pts[f"{side}_wrist"]
    fl = d["forearm.length"]
    stations = [(0, 0.84 * fb, 0.86 * fb), (0.2, 0.95 * fb, fb), (0.5, 0.78 * fb, 0.85 * fb), (1, 0.72 * wb, wb)]
    names = [f"{side}_forearm", f"{side}_forearm_mid", f"{side}_forearm_distal"]
    t0 = 0.0
    for k, (name, frac) in enumerate(zip(names, FOREARM_PARTS)):
        t1 = t0 + frac
        a, b_ = t0, t1
        st = [(0.0, *_interp_st(stations, a))] + [((t - a) / (b_ - a), ru, rv) for t, ru, rv in stations if a < t < b_] \
            + [(1.0, *_interp_st(stations, b_))]
        put(name, limb(elbow - [0, a * fl, 0], elbow - [0, b_ * fl, 0], st, cap0=1.0 if k == 0 else 0.0,
                       cap1=0.0, hint=np.array([1.0, 0.0, 0.0])), "shirt" if k < 2 else "skin")
        t0 = t1
    # palm: a rounded slab from the wrist to the knuckles, thin across x (palm faces medially)
    hl, hb = d["hand.length"], d["hand.breadth"]
    knuckle_y = np.mean([pts[f"{side}_{f}_mcp"][1] for f in FINGERS])
    put(f"{side}_palm", limb(wrist + [0, 0.01 * s, 0], np.array([wrist[0], knuckle_y, wrist[2]]),
                             [(0, 0.62 * wb, 0.95 * wb), (0.3, 0.15 * hb, 0.47 * hb), (1, 0.13 * hb, 0.5 * hb)],
                             hint=np.array([1.0, 0.0, 0.0]), cap0=0.4, cap1=0.35, exponent=2.6,
                             offsets=[(0, 0, 0), (1, 0, 0.01 * hb)]), "skin")
    for digit in DIGITS:
        radius = (0.125 if digit == "thumb" else 0.105 if digit != "little" else 0.09) * hb
        lengths = BUCHHOLZ[digit][1:] if digit != "thumb" else BUCHHOLZ[digit]
        for k, length in enumerate(lengths, start=1):
            seg = f"{side}_{digit}_{k}"
            p0 = org[seg]
            p1 = p0 + pts[f"{seg}_dir"] * length * hl
            r0 = radius * (1.0 - 0.1 * (k - 1))
            r1 = radius * (1.0 - 0.1 * k) if k < len(lengths) else radius * 0.75
            put(seg, limb(p0, p1, [(0, r0, r0), (1, r1, r1)], AROUND_DIGIT, cap0=0.8, cap1=1.0), "skin")


def _interp_st(stations: list[tuple[float, float, float]], t: float) -> tuple[float, float]:
    a = np.array(stations)
    return float(np.interp(t, a[:, 0], a[:, 1])), float(np.interp(t, a[:, 0], a[:, 2]))


def _leg_shapes(spec: BodySpec, sk: Skeleton, side: str, sx: float, put) -> None:
    d = spec.dims
    s = spec.stature / 1.756
    org = sk.origins
    hip, knee, ankle = org[f"{side}_thigh"], org[f"{side}_shank"], org[f"{side}_foot"]
    tb, kb, cb, ab = (d[k] / 2 for k in ("thigh.breadth", "knee.breadth", "calf.breadth", "ankle.breadth"))
    put(f"{side}_thigh", limb(hip + [sx * 0.012 * s, 0.03 * s, -0.005 * s], knee + [0, -0.01 * s, 0],
                              [(0, 0.95 * tb, 1.0 * tb), (0.15, 0.97 * tb, tb), (0.55, 0.8 * tb, 0.82 * tb),
                               (0.9, 1.05 * kb, 1.0 * kb), (1, kb, 0.95 * kb)],
                              offsets=[(0, 0, 0), (0.5, 0, 0.004), (1, 0, 0.005)], cap0=0.5), "trousers")
    put(f"{side}_shank", limb(knee + [0, 0.02 * s, 0], ankle + [0, 0.02 * s, 0],
                              [(0, 0.95 * kb, 0.95 * kb), (0.3, cb, 1.05 * cb), (0.75, 0.7 * cb, 0.7 * cb),
                               (1, ab * 0.85, ab * 0.9)],
                              offsets=[(0, 0, 0), (0.3, 0, -0.012 * s), (1, 0, 0)]), "trousers")
    fl, fw, ya = d["foot.length"], d["foot.breadth"] / 2, d["foot.height"]
    # shoe: sections along +z from the heel to past the ball; flat sole on the floor
    rows = [(-0.22, 0.62, 0.75), (-0.17, 0.72, 1.25), (-0.05, 0.8, 1.45), (0.12, 0.9, 1.15), (0.3, 0.98, 0.85),
            (0.45, 1.0, 0.68), (0.53, 1.0, 0.62)]
    rings = []
    for zf, wf, hf in rows:
        h = hf * ya
        c = np.array([ankle[0] - sx * 0.06 * wf * fw * (zf > 0.2), h / 2, zf * fl])
        rings.append(superellipse_ring(c, np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), wf * fw, h / 2,
                                       AROUND_LIMB, 3.0))
    rings.insert(0, 0.5 * (rings[0] - rings[0].mean(0)) + rings[0].mean(0) - [0, 0, 0.01 * s])
    foot = tube(np.stack(rings))
    put(f"{side}_foot", foot, "shoe")
    toes0 = np.array([ankle[0] - sx * 0.06 * fw, 0.31 * ya, 0.49 * fl])
    toes1 = np.array([ankle[0] - sx * 0.08 * fw, 0.27 * ya, 0.78 * fl])
    put(f"{side}_toes", limb(toes0, toes1, [(0, fw * 0.98, 0.31 * ya), (0.6, fw * 0.85, 0.27 * ya), (1, fw * 0.6, 0.22 * ya)],
                             AROUND_LIMB, hint=np.array([1.0, 0.0, 0.0]), cap0=0.0, cap1=0.35, exponent=2.6), "shoe")
