"""Segment surfaces generated from the body dimensions: lofted superellipse sections, closed meshes.

Every shape is built in world coordinates of the zero pose (see :mod:`jackpy.body.skeleton`) as rings
of cross-sections along a path, closed at both ends (primitives in :mod:`jackpy.body.mesh_loft`), then
moved into its segment's frame. The torso is one smooth profile (monotone cubic through the hip, waist,
chest, armpit and neck-base measurements) with sex-specific bumps (breasts or pectorals, buttocks,
shoulder blades), cut into one slab per vertebra; each slab reaches into its neighbours with sections a
little inside theirs, so bending the spine opens no gaps and nothing z-fights. Limbs taper between their
proximal and distal measurements with muscle bulges; the head is a superellipsoid with a flat face, jaw,
brow, eye sockets, nose, cheekbones, lips, chin and ears; the hand is a rounded palm box of the hand
breadth and thickness with tapered phalanges and a thick thenar thumb; the feet are shoe-shaped.
About 28-30k triangles for the whole body.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import PchipInterpolator

from jackpy.body.mesh_loft import (
    limb,
    merge,
    signed_volume,
    superellipse_ring,
    superellipse_unit,
    tube,
)
from jackpy.body.sass import BodySpec
from jackpy.body.skin_face import refine_face
from jackpy.body.skeleton import (
    BUCHHOLZ,
    DIGITS,
    FINGERS,
    FOREARM_PARTS,
    SIDES,
    Skeleton,
)
from jackpy.peabody.geometry import Mesh

__all__ = ["ATTRIBUTES", "body_shapes", "limb", "merge", "signed_volume", "superellipse_ring", "tube"]

#: display attribute (X11 colour name) per body region
ATTRIBUTES = {"skin": "peachpuff", "shirt": "steelblue", "trousers": "darkslategray",
              "shoe": "saddlebrown", "eye": "white"}
AROUND_TORSO, AROUND_LIMB, AROUND_DIGIT = 32, 16, 12
#: torso slabs reach this fraction of the shorter neighbour's height into it, ending OVERLAP_INSET (m) inside
#: its surface (never coincident with it, so no z-fighting)
OVERLAP, OVERLAP_INSET = 0.45, 0.0012
#: the buttock and thigh surfaces stay this far (m) above the ischial seat contact
SEAT_CLEARANCE = 0.001
#: shoe outline allowance around the barefoot foot, m: behind the heel, beyond the toes, each side
SHOE_HEEL, SHOE_TOE, SHOE_SIDE = 0.008, 0.010, 0.005


class _Torso:
    """The torso surface: a smooth profile (half width, half depth, centre z as monotone cubic functions
    of height through the hip, waist, chest, armpit and neck-base measurements) with superellipse
    sections, plus sex-specific shaping (breasts or pectorals, buttocks, shoulder blades) as smooth
    bumps pushed out along z. Every vertebral slab samples the same surface, so neighbours match."""

    def __init__(self, spec: BodySpec, sk: Skeleton) -> None:
        d = spec.dims
        s = spec.stature / 1.756
        female = spec.sex == "female"
        yh = sk.points["hip_y"][1]
        yt = sk.points["spine_top"][1]
        hb, bd, wb, wd, cb, cd = (d[k] for k in ("hip.breadth", "buttock.depth", "waist.breadth",
                                                 "waist.depth", "chest.breadth", "chest.depth"))
        bust = 0.87 if female else 0.96  # chest depth taken by the base section (bumps add the rest)
        seat = 0.9 if female else 0.93
        rows = [  # y, full width, full depth, centre z
            (yh - 0.085 * s, 0.62 * hb, 0.6 * bd, -0.01 * s),
            (yh - 0.04 * s, 0.93 * hb, 0.86 * seat * bd, -0.015 * s),
            (yh + 0.01 * s, hb, seat * bd, -0.02 * s),
            (yh + 0.08 * s, 0.5 * (hb + wb), 0.5 * (seat * bd + wd), -0.01 * s),
            (yh + 0.16 * s, wb, wd, 0.0),
            (yt - 0.30 * s, 0.5 * (wb + cb), 0.5 * (wd + bust * cd), 0.0),
            (yt - 0.21 * s, cb, bust * cd, 0.005 * s),
            (yt - 0.13 * s, 1.03 * cb, 0.93 * cd, 0.0),
            (yt - 0.06 * s, 0.95 * cb, 0.8 * cd, -0.01 * s),
            (yt - 0.01 * s, 0.72 * cb, 0.62 * cd, -0.02 * s),
            (yt + 0.02 * s, 1.15 * d["neck.breadth"], 1.05 * d["neck.breadth"], -0.02 * s),
        ]
        a = np.array(rows)
        self.y0, self.y1 = float(a[0, 0]), float(a[-1, 0])
        self._rx = PchipInterpolator(a[:, 0], a[:, 1] / 2)
        self._rz = PchipInterpolator(a[:, 0], a[:, 2] / 2)
        self._cz = PchipInterpolator(a[:, 0], a[:, 3])
        # bumps: (x0, y0, half extent x, extent up, extent down, amount, +1 front / -1 back)
        self.bumps: list[tuple[float, ...]] = []
        for sx in (1.0, -1.0):
            if female:
                self.bumps.append((sx * 0.3 * cb, yt - 0.195 * s, 0.085 * s, 0.11 * s, 0.055 * s, 0.16 * cd, 1.0))
            else:
                self.bumps.append((sx * 0.27 * cb, yt - 0.15 * s, 0.085 * s, 0.08 * s, 0.06 * s, 0.045 * cd, 1.0))
            self.bumps.append((sx * 0.2 * hb, yh - 0.005 * s, 0.1 * s, 0.1 * s, 0.06 * s,
                               (0.12 if female else 0.09) * bd, -1.0))
            self.bumps.append((sx * 0.22 * cb, yt - 0.12 * s, 0.07 * s, 0.07 * s, 0.07 * s, 0.03 * cd, -1.0))
        self.cu, self.sv = superellipse_unit(AROUND_TORSO, 2.3)

    def ring(self, y: float, inset: float = 0.0, lift: float = 0.0, scale: float = 1.0) -> np.ndarray:
        """Section at height ``y``, moved ``inset`` metres inward (about) and shrunk toward its centre by
        ``scale``, placed at ``y + lift``."""
        yc = min(max(y, self.y0), self.y1)
        rx, rz, cz = float(self._rx(yc)), float(self._rz(yc)), float(self._cz(yc))
        x = rx * self.cu
        z = rz * self.sv
        for x0, y0, ex, up, down, amount, side in self.bumps:
            q2 = ((x - x0) / ex) ** 2 + ((y - y0) / (up if y > y0 else down)) ** 2
            facing = np.clip(side * self.sv * 1.6, 0.0, 1.0)
            z = z + side * amount * np.clip(1.0 - q2, 0.0, None) ** 2 * facing
        scale = scale * (1.0 - inset / (0.5 * (rx + rz)))
        return np.column_stack([scale * x, np.full_like(x, y + lift), cz + scale * z])

    def slab(self, y0: float, y1: float, below: float, above: float, bottom: bool, top: bool) -> Mesh:
        """The part of the surface from ``y0`` to ``y1``, reaching ``below``/``above`` metres into the
        neighbouring slabs there with sections moving OVERLAP_INSET inward (inside the neighbour, so bending
        opens no gap and coincident surfaces never z-fight); rounded crotch at the ``bottom``."""
        ys = np.linspace(y0, y1, max(2, int(np.ceil((y1 - y0) / 0.015)) + 1))
        rings = [self.ring(y) for y in ys]
        # overlaps: the inset grows quadratically, so the visible edge ring keeps the surface's normal
        if below > 0:
            rings[:0] = [self.ring(y0 - below, OVERLAP_INSET), self.ring(y0 - 0.5 * below, 0.25 * OVERLAP_INSET)]
        if above > 0:
            rings += [self.ring(y1 + 0.5 * above, 0.25 * OVERLAP_INSET), self.ring(y1 + above, OVERLAP_INSET)]
        # hidden overlap ends close with a plain fan (no inset ring needed for the side normals)
        start = rings[0].mean(axis=0) if below > 0 else None
        end = rings[-1].mean(axis=0) if above > 0 else None
        if bottom:  # rounded crotch / seat
            rz0, cz0 = float(self._rz(y0)), float(self._cz(y0))
            for f in (0.95, 0.8, 0.55):
                rings.insert(0, self.ring(y0, 0.0, -0.6 * rz0 * np.sqrt(1 - f * f), f))
            start = np.array([0.0, y0 - 0.6 * rz0, cz0])
        if top:
            end = np.array([0.0, y1 + 0.25 * float(self._rz(y1)), float(self._cz(y1))])
        return tube(np.stack(rings), start, end)


def _head(spec: BodySpec, sk: Skeleton) -> Mesh:
    """Cranium ellipsoid with a flatter, fuller face (front profile from forehead to chin), a narrower
    jaw, and a generic face: brow ridge, eye sockets, nose (bridge, tip, wings), cheekbones, lips,
    chin; ears. Longitudes are packed toward the face so the features have vertices to live on."""
    d = spec.dims
    s = spec.stature / 1.756
    vertex = sk.points["vertex"]
    view = sk.points["view"]
    ax, ay, az = d["head.breadth"] / 2, 0.118 * s, d["head.length"] / 2
    c = np.array([0.0, vertex[1] - ay, view[2] + 0.012 - az])
    nlat, nlon = 46, 44
    lat = np.linspace(0, np.pi, nlat + 1)[1:-1]
    u = np.linspace(-1.0, 1.0, nlon, endpoint=False) + 1.0 / nlon
    lon = np.pi * np.sign(u) * np.abs(u) ** 1.45  # O=0 -> +z front, dense there
    L, O = np.meshgrid(lat, lon, indexing="ij")
    cl, sl = np.cos(L), np.sin(L)
    e = np.where(cl > 0, 2.5, 2.3)  # a fuller, rounder cranium and a squarer jaw than an ellipsoid
    cl, sl = np.sign(cl) * np.abs(cl) ** (2 / e), sl ** (2 / e)
    dirs = np.stack([sl * np.sin(O), cl, sl * np.cos(O)], axis=-1)
    p = dirs * [ax, ay, az]
    y_rel = dirs[..., 1]
    jaw = np.clip(-y_rel, 0, 1)  # 0 above the centre, 1 at the chin
    front = np.clip(np.cos(O), 0, 1) ** 3  # 1 on the midline front
    # face: the lower face stands further forward than an ellipsoid (flat face, forward chin)
    face_fill = np.interp(y_rel, [-1.0, -0.93, -0.8, -0.55, -0.2, 0.2, 0.5], [0.0, 0.26, 0.24, 0.13, 0.03, 0.0, 0.0])
    p[..., 2] += az * face_fill * front * (p[..., 2] > 0)
    p[..., 0] *= 1.0 - 0.3 * jaw ** 1.8
    p[..., 2] *= 1.0 - 0.14 * jaw * (p[..., 2] < 0)  # nape
    p[..., 1] -= 0.05 * ay * jaw ** 2 * (p[..., 2] > 0)  # chin reaches down
    world = c + p
    x, y = world[..., 0], world[..., 1]

    def bump(x0: float, y0: float, ex: float, ey: float, amount: float) -> np.ndarray:
        return amount * s * np.exp(-0.5 * (((x - x0 * s) / (ex * s)) ** 2 + ((y - y0) / (ey * s)) ** 2))

    eye_y = view[1]
    eb = d["eyes.breadth"] / 2
    # nose: protrusion rising from the bridge to the tip, then tucked under to its base
    tip_y, base_y, bridge_y = eye_y - 0.042 * s, eye_y - 0.054 * s, eye_y + 0.004 * s
    prof = np.interp(y, [base_y - 0.004 * s, base_y, tip_y, bridge_y, bridge_y + 0.012 * s],
                     [0.0, 0.008 * s, 0.021 * s, 0.005 * s, 0.0])
    wide = np.interp(y, [base_y, tip_y, bridge_y], [0.013, 0.011, 0.0075]) * s
    nose = prof * np.exp(-0.5 * (x / wide) ** 2)
    nose += sum(bump(sx * 0.014, base_y + 0.006 * s, 0.006, 0.006, 0.005) for _, sx in SIDES)  # wings
    brow = np.exp(-0.5 * (x / (0.045 * s)) ** 4) * 0.006 * s * np.exp(-0.5 * ((y - eye_y - 0.02 * s) / (0.008 * s)) ** 2)
    # eye sockets deep enough that the eyeballs (radius 0.0125 s, centre 12 mm behind the view point)
    # show their front half
    k = np.argmin((x - eb) ** 2 + (y - eye_y) ** 2 + 1e3 * (world[..., 2] < c[2]))
    depth = world.reshape(-1, 3)[k, 2]
    socket = max(0.0, depth - (view[2] - 0.012 + 0.5 * 0.0125 * s)) / s
    sockets = sum(bump(sx * eb / s, eye_y, 0.015, 0.011, -socket) for _, sx in SIDES)
    cheeks = sum(bump(sx * 0.04, eye_y - 0.03 * s, 0.014, 0.014, 0.004) for _, sx in SIDES)
    lips = (bump(0.0, eye_y - 0.07 * s, 0.02, 0.0055, 0.0045) + bump(0.0, eye_y - 0.085 * s, 0.017, 0.006, 0.004)
            + bump(0.0, eye_y - 0.0775 * s, 0.022, 0.0018, -0.0015))
    chin = bump(0.0, eye_y - 0.113 * s, 0.02, 0.012, 0.006)
    face = (nose + brow + sockets + cheeks + lips + chin) * np.clip(dirs[..., 2] * 3, 0, 1)
    world[..., 2] += face
    ears = sum(np.exp(-0.5 * (((y - eye_y + 0.015 * s) / (0.028 * s)) ** 2 + ((world[..., 2] - c[2] + 0.008 * s)
                                                                             / (0.015 * s)) ** 2))
               * (np.sign(x) == sx) for _, sx in SIDES) * 0.011 * s
    world[..., 0] += ears * np.sign(x)
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

    # torso slabs, one per vertebra, meeting at the joint heights and overlapping their neighbours
    torso = _Torso(spec, sk)
    spine = ["pelvis", "l5", "l4", "l3", "l2", "l1"] + [f"t{k}" for k in range(12, 0, -1)]
    bounds = [torso.y0] + [org[n][1] for n in spine[1:]] + [torso.y1]
    heights = np.diff(bounds)
    last = len(spine) - 1
    for k, name in enumerate(spine):
        below = OVERLAP * min(heights[k], heights[k - 1]) if k > 0 else 0.0
        above = OVERLAP * min(heights[k], heights[k + 1]) if k < last else 0.0
        mesh = torso.slab(bounds[k], bounds[k + 1], below, above, k == 0, k == last)
        if k == 0:  # buttocks flattened on the seat plane: nothing hangs below the ischial tuberosities
            v = mesh.vertices.copy()
            v[:, 1] = np.maximum(v[:, 1], pts["seat_y"][1] + SEAT_CLEARANCE)
            mesh = Mesh(v, mesh.faces)
        put(name, mesh, "trousers" if k <= 2 else "shirt")
    nb = d["neck.breadth"] / 2
    put("neck", limb(pts["spine_top"] + [0, -0.03 * s, 0.015 * s], pts["head_joint"] + [0, 0.02 * s, 0.01 * s],
                     [(0, nb * 1.05, nb * 1.0), (1, nb * 0.95, nb * 0.95)], AROUND_LIMB, cap0=0, cap1=0), "skin")
    put("head", refine_face(_head(spec, sk), spec.stature, pts["view"], d["eyes.breadth"]), "skin")
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
    # the deltoid bulges out to half the bideltoid breadth (its lateral offset fades by 40 % down)
    deltoid = max(0.0, d["bideltoid.breadth"] / 2 - abs(sh[0]) - 1.12 * ub)
    put(f"{side}_upper_arm", limb(sh + [0, 0.015 * s, 0], elbow,
                                  [(0, 1.12 * ub, 1.12 * ub), (0.3, 1.05 * ub, ub), (0.6, 0.92 * ub, 0.95 * ub),
                                   (1, 0.86 * fb, 0.82 * fb)], hint=np.array([1.0, 0.0, 0.0]),
                                  offsets=[(0, sx * deltoid, 0.0), (0.15, sx * 0.8 * deltoid, 0.0),
                                           (0.4, 0.0, 0.0), (1, 0.0, 0.0)]), "shirt")
    fl = float(elbow[1] - pts[f"{side}_wrist"][1])
    stations = [(0, 0.84 * fb, 0.86 * fb), (0.2, 0.95 * fb, fb), (0.5, 0.78 * fb, 0.85 * fb), (1, 0.72 * wb, wb)]
    names = [f"{side}_forearm", f"{side}_forearm_mid", f"{side}_forearm_distal"]
    t0 = 0.0
    for k, (name, frac) in enumerate(zip(names, FOREARM_PARTS)):
        t1 = t0 + frac
        a, b_ = t0, t1
        st = [(0.0, *_interp_st(stations, a))] + [((t - a) / (b_ - a), ru, rv) for t, ru, rv in stations if a < t < b_] \
            + [(1.0, *_interp_st(stations, b_))]
        put(name, limb(elbow - [0, a * fl, 0], elbow - [0, b_ * fl, 0], st, cap0=1.0 if k == 0 else 0.0,
                       cap1=0.4 if k == 2 else 0.0, hint=np.array([1.0, 0.0, 0.0])), "shirt" if k < 2 else "skin")
        t0 = t1
    _hand_shapes(spec, sk, side, sx, put)


def _hand_shapes(spec: BodySpec, sk: Skeleton, side: str, sx: float, put) -> None:
    """Palm: a rounded box of the hand breadth and thickness from the wrist to the slanted knuckle line;
    fingers: tapered, slightly flattened phalanges touching their neighbours, rounded tips; thumb: a
    thick metacarpal (the thenar pad) and two phalanges, opposed (forward and toward the palm)."""
    d = spec.dims
    pts, org = sk.points, sk.origins
    hl, hb, wb = d["hand.length"], d["hand.breadth"], d["wrist.breadth"]
    wrist = pts[f"{side}_wrist"]
    # knuckle line: MCP heights against the across-the-palm position z (thumb side +z)
    mz = np.array([pts[f"{side}_{f}_mcp"][2] for f in reversed(FINGERS)])
    my = np.array([pts[f"{side}_{f}_mcp"][1] for f in reversed(FINGERS)])
    y_top = wrist[1] + 0.06 * hl  # inside the forearm's end
    # stations along the palm (fraction of the way to the knuckle line): half thickness (x), half
    # width (z), centre z; then a rounded knuckle end in the thickness only
    st = np.array([(0.0, 0.3 * wb, 0.42 * wb, 0.0), (0.15, 0.33 * wb, 0.47 * wb, 0.0),
                   (0.45, 0.16 * hb, 0.45 * hb, 0.02 * hb), (0.8, 0.15 * hb, 0.45 * hb, 0.02 * hb),
                   (1.0, 0.14 * hb, 0.44 * hb, 0.02 * hb)])
    ts = np.linspace(0.0, 1.0, 9)
    cu, sv = superellipse_unit(AROUND_LIMB + 4, 2.8)
    rings = []
    for t in ts:
        tx, tz, cz = (np.interp(t, st[:, 0], st[:, k]) for k in (1, 2, 3))
        z = wrist[2] + cz + tz * sv
        y_end = np.interp(z, mz, my)
        rings.append(np.column_stack([wrist[0] + tx * cu, y_top + t * (y_end - y_top), z]))
    t_end, z_end = st[-1, 1], st[-1, 2]
    for a in np.linspace(0.0, np.pi / 2, 5)[1:-1]:  # rounded knuckles, reaching 0.6 of the thickness
        z = wrist[2] + st[-1, 3] + z_end * (1.0 - 0.12 * (1 - np.cos(a))) * sv
        rings.append(np.column_stack([wrist[0] + t_end * np.cos(a) * cu,
                                      np.interp(z, mz, my) - 0.6 * t_end * np.sin(a), z]))
    tip = np.array([wrist[0], np.interp(0.0, mz, my) - 0.6 * t_end, wrist[2] + st[-1, 3]])
    put(f"{side}_palm", tube(np.stack(rings), None, tip), "skin")

    width = {"thumb": 0.125, "index": 0.116, "middle": 0.118, "ring": 0.11, "little": 0.097}
    for digit in DIGITS:
        w0 = width[digit] * hb
        lengths = np.array(BUCHHOLZ[digit][1:] if digit != "thumb" else BUCHHOLZ[digit]) * hl
        total = lengths.sum()
        taper = 0.22 if digit != "thumb" else 0.18
        done = 0.0
        for k, length in enumerate(lengths, start=1):
            seg = f"{side}_{digit}_{k}"
            p0 = org[seg]
            direction = pts[f"{seg}_dir"]
            wa, wb_ = (w0 * (1.0 - taper * x / total) for x in (done, done + length))
            done += length
            last = k == len(lengths)
            if digit == "thumb" and k == 1:  # thenar pad: thick, bulging toward the palm
                mesh = limb(p0 - direction * 0.25 * length, p0 + direction * length,
                            [(0, 1.25 * w0, 1.35 * w0), (0.45, 1.3 * w0, 1.35 * w0), (1, 1.0 * w0, 1.02 * w0)],
                            AROUND_DIGIT + 2, hint=(1.0, 0.0, 0.0), cap0=0.6, cap1=0.8, step=0.012,
                            offsets=[(0, -sx * 0.25 * w0, 0.0), (0.6, -sx * 0.15 * w0, 0.0), (1, 0, 0)])
            else:
                end = length - (0.75 * wb_ if last else 0.0)  # the rounded tip ends at the tip site
                mesh = limb(p0, p0 + direction * end,
                            [(0, 0.86 * wa, 1.02 * wa), (0.5, 0.8 * 0.5 * (wa + wb_), 0.94 * 0.5 * (wa + wb_)),
                             (1, 0.82 * wb_ if not last else 0.72 * wb_, 0.98 * wb_ if not last else 0.92 * wb_)],
                            AROUND_DIGIT, hint=(1.0, 0.0, 0.0), cap0=0.5, cap1=0.9, step=0.03,
                            cap_rings=(1, 2 if not last else 3), exponent=2.2)
            put(seg, mesh, "skin")


def _interp_st(stations: list[tuple[float, float, float]], t: float) -> tuple[float, float]:
    a = np.array(stations)
    return float(np.interp(t, a[:, 0], a[:, 1])), float(np.interp(t, a[:, 0], a[:, 2]))


def _leg_shapes(spec: BodySpec, sk: Skeleton, side: str, sx: float, put) -> None:
    d = spec.dims
    s = spec.stature / 1.756
    org = sk.origins
    hip, knee, ankle = org[f"{side}_thigh"], org[f"{side}_shank"], org[f"{side}_foot"]
    tb, kb, cb, ab = (d[k] / 2 for k in ("thigh.breadth", "knee.breadth", "calf.breadth", "ankle.breadth"))
    # thigh: its back (the underside when sitting) no deeper than the seat contact below the hip joint
    # (ANSUR II seat-to-hip height) and its sagittal thickness that of THIGHCLEARANCE; the section
    # centre moves forward to keep the thickness
    seat_hip = hip[1] - sk.points["seat_y"][1] - SEAT_CLEARANCE
    half_depth = min(tb, d["thigh.clearance"] / 2)
    # the top of the knee when sitting (thigh front at the knee) is KNEEHEIGHTSITTING above the floor
    knee_top = d["knee.height_sitting"] - knee[1]
    kd = min(kb, knee_top - 0.006)
    stations = [(0, 0.95 * tb, 1.0 * half_depth), (0.15, 0.97 * tb, half_depth), (0.55, 0.8 * tb, 0.82 * half_depth),
                (0.9, 1.05 * kb, kd), (1, kb, 0.95 * kd)]
    offsets = [(t, 0.0, max(0.0, rv - seat_hip) + 0.005 * t) for t, _, rv in stations]
    put(f"{side}_thigh", limb(hip + [sx * 0.012 * s, 0.03 * s, -0.005 * s], knee + [0, -0.01 * s, 0],
                              stations, offsets=offsets, cap0=0.5), "trousers")
    # the shank's rounded top stays under the knee top (it is the knee's upper surface when sitting)
    cap_top = float(np.clip((knee_top - 0.02 * s - 0.008) / (0.95 * kb), 0.0, 1.0))
    put(f"{side}_shank", limb(knee + [0, 0.02 * s, 0], ankle + [0, 0.02 * s, 0],
                              [(0, 0.95 * kb, 0.95 * kb), (0.3, cb, 1.05 * cb), (0.75, 0.7 * cb, 0.7 * cb),
                               (1, ab * 0.85, ab * 0.9)],
                              offsets=[(0, 0, 0), (0.3, 0, -0.012 * s), (1, 0, 0)], cap0=cap_top), "trousers")
    fl, fw, ya = d["foot.length"], d["foot.breadth"] / 2, d["foot.height"]
    shoe = spec.footwear == "shoe"
    heel_extra, toe_extra, side_extra = (SHOE_HEEL, SHOE_TOE, SHOE_SIDE) if shoe else (0.0, 0.0, 0.0)
    fw = fw + side_extra
    region = "shoe" if shoe else "skin"
    # sections along +z from the heel to past the ball; flat sole on the floor. The heel point (the
    # foot's rear, 0.22 foot lengths behind the ankle) and the toe tip (0.78 ahead) are FOOTLENGTH apart
    rows = [(-0.22, 0.62, 0.75), (-0.17, 0.72, 1.25), (-0.05, 0.8, 1.45), (0.12, 0.9, 1.15), (0.3, 0.98, 0.85),
            (0.45, 1.0, 0.68), (0.53, 1.0, 0.62)]
    rings = []
    for zf, wf, hf in rows:
        h = hf * ya
        c = np.array([ankle[0] - sx * 0.06 * wf * fw * (zf > 0.2), h / 2, zf * fl])
        rings.append(superellipse_ring(c, np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), wf * fw, h / 2,
                                       AROUND_LIMB, 3.0))
    back = 0.5 * (rings[0] - rings[0].mean(0)) + rings[0].mean(0)
    rings[0] = rings[0] + [0, 0, 0.01 * fl]
    rings.insert(0, back - [0, 0, heel_extra])
    foot = tube(np.stack(rings))
    put(f"{side}_foot", foot, region)
    toes0 = np.array([ankle[0] - sx * 0.06 * fw, 0.31 * ya, 0.49 * fl])
    toes1 = np.array([ankle[0] - sx * 0.08 * fw, 0.27 * ya, 0.78 * fl + toe_extra])
    cap = 0.35
    r_tip = 0.5 * (fw * 0.6 + 0.22 * ya)  # the cap reaches cap * r_tip beyond toes1
    toes1 = toes1 - [0, 0, cap * r_tip]
    put(f"{side}_toes", limb(toes0, toes1, [(0, fw * 0.98, 0.31 * ya), (0.6, fw * 0.85, 0.27 * ya), (1, fw * 0.6, 0.22 * ya)],
                             AROUND_LIMB, hint=np.array([1.0, 0.0, 0.0]), cap0=0.0, cap1=cap, exponent=2.6), region)
