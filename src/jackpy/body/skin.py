"""One continuous skinned surface for the standard human's torso (and limbs), deformed by its skeleton.

The rigid surfaces of :mod:`jackpy.body.shapes` are one slab per vertebra: bending the 17-vertebra
spine stacks them like discs (banding, a seam, dark dots where an inner slab pokes through). The
skin replaces them by one closed surface with per-vertex bone weights, deformed by linear-blend
skinning (LBS):

    p = sum_b w_b M_b v,    M_b = W_b(q) T(-o_b)

with ``v`` the rest vertex in the zero-pose frame of :mod:`jackpy.body.skeleton` (every segment frame
parallel to it, segment ``b``'s origin at ``o_b``), ``W_b(q)`` the segment's world transform now, and
``T(-o_b)`` the inverse bind matrix (so a vertex bound wholly to ``b`` moves exactly as ``b``'s rigid
surface). The renderer does this in its vertex shader (:mod:`jackpy.render.skinning`); :func:`deform`
is the same on the CPU (report pictures, ID buffers, tests).

Weights [proposal; the sources draw the rigid slabs]: all chains are vertical in the zero pose, so a
vertex's weights depend on its height. Across each joint of a chain at height ``h`` the weight passes
from the segment below to the one above by a smoothstep over ``h +- r``, with ``r`` half the shorter
of the two segments (``BLEND``), so at most two bones share a vertex and consecutive blends never
overlap. With 17 vertebrae a 60 degree bend turns each joint by about 3.5 degrees: linear blending
shows no candy-wrapper loss at that scale, so dual quaternions are not needed.

The torso section is the same smooth profile the rigid slabs sample (``shapes._Torso``), lofted in
one piece from the crotch to the neck base, 48 points around, rings 8 mm apart; the seat is
flattened as the pelvis slab is. Limbs keep their rigid surfaces.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage as ndi

from jackpy.body.mesh_loft import superellipse_unit, tube
from jackpy.body.shapes import SEAT_CLEARANCE, _Torso
from jackpy.body.skeleton import build_skeleton
from jackpy.peabody.geometry import Mesh
from jackpy.peabody.model import Figure

__all__ = ["SPINE_SEGMENTS", "Skin", "SkinPiece", "bone_matrices", "build_skin", "build_skins", "deform",
           "segment_surfaces", "skin_for", "skinned_pieces", "skins_for"]

#: the torso's bones from the bottom up (the segments whose rigid slabs the skin replaces)
SPINE_SEGMENTS = ("pelvis", "l5", "l4", "l3", "l2", "l1") + tuple(f"t{k}" for k in range(12, 0, -1))
#: the limb chains skinned on each side, bottom up (hands, feet and clavicles stay rigid)
LIMB_CHAINS = (("forearm_distal", "forearm_mid", "forearm", "upper_arm"), ("shank", "thigh"))
#: blend half-width across a joint as a fraction of the shorter neighbouring segment; on limbs at
#: most LIMB_BLEND m at 1.756 m stature (a tighter elbow and knee: less linear-blend pinching)
BLEND, LIMB_BLEND = 0.5, 0.04
#: points around the torso and limb sections, and the largest gap between rings (m)
AROUND, LIMB_AROUND, RING_STEP = 48, 28, 0.008


@dataclass(frozen=True)
class Skin:
    """A skinned surface: ``vertices`` (n,3) at rest in the zero-pose frame (m), outward triangles
    ``faces`` (m,3), per vertex four bone indices ``joints`` (n,4) into ``bones`` and ``weights``
    (n,4) summing to 1, rest unit ``normals`` (n,3), and ``owner`` (n,): the bone whose segment a
    vertex counts as (picking, colour). ``origins`` (b,3): each bone's zero-pose origin (the inverse
    bind matrix is the translation by ``-origins[b]``)."""

    bones: tuple[str, ...]
    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    joints: np.ndarray
    weights: np.ndarray
    owner: np.ndarray
    origins: np.ndarray

    @property
    def covers(self) -> frozenset[str]:
        """Segments drawn by the skin instead of their rigid surfaces."""
        return frozenset(self.bones)

    def inverse_bind(self) -> np.ndarray:
        """(b,4,4) inverse bind matrices: zero-pose frame to each bone's segment frame."""
        m = np.tile(np.eye(4), (len(self.bones), 1, 1))
        m[:, :3, 3] = -self.origins
        return m


@dataclass
class SkinPiece(Mesh):
    """The part of the posed skin one segment owns, in that segment's frame, with ``normals`` (n,3):
    the whole skin's unit normals at its vertices (the piece's own faces would crease its border)."""

    normals: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))

    def vertex_normals(self) -> np.ndarray:
        return self.normals


def chain_weights(height: np.ndarray, joints: np.ndarray, blend: np.ndarray) -> np.ndarray:
    """(n, k+1) weights of the k+1 segments of a vertical chain for vertices at ``height`` (n,), m:
    ``joints`` (k,) ascending joint heights, ``blend`` (k,) half-widths of the smoothstep across each."""
    h = np.asarray(height, float)[:, None]
    t = np.clip((h - (joints - blend)) / (2.0 * blend), 0.0, 1.0)
    above = t * t * (3.0 - 2.0 * t)  # share of the chain above each joint
    ones, zeros = np.ones((len(h), 1)), np.zeros((len(h), 1))
    up = np.hstack([ones, above, zeros])
    return np.clip(up[:, :-1] - up[:, 1:], 0.0, 1.0)


def _top4(w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The four largest weights per row (renormalised) and their column indices; unused slots are
    bone 0 with weight 0."""
    w = np.hstack([w, np.zeros((len(w), max(0, 4 - w.shape[1])))])
    idx = np.argsort(-w, axis=1, kind="stable")[:, :4]
    top = np.take_along_axis(w, idx, axis=1)
    idx = np.where(top > 0, idx, 0)
    return idx.astype(np.int32), (top / top.sum(axis=1, keepdims=True)).astype(np.float64)


def _vertex_normals(v: np.ndarray, f: np.ndarray) -> np.ndarray:
    face_n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n = np.zeros_like(v)
    for k in range(3):
        np.add.at(n, f[:, k], face_n)
    return n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)


def _torso_surface(torso: _Torso, seat_y: float) -> tuple[np.ndarray, np.ndarray]:
    """The whole torso as one closed tube: rounded crotch, rings from ``torso.y0`` to ``torso.y1``,
    a rounded top; the seat flattened ``SEAT_CLEARANCE`` above ``seat_y``."""
    torso.cu, torso.sv = superellipse_unit(AROUND, 2.3)
    y0, y1 = torso.y0, torso.y1
    rings = [torso.ring(y) for y in np.linspace(y0, y1, int(np.ceil((y1 - y0) / RING_STEP)) + 1)]
    rz0, cz0 = float(torso._rz(y0)), float(torso._cz(y0))
    for f in (0.95, 0.8, 0.55):  # the crotch, rounded as the pelvis slab's
        rings.insert(0, torso.ring(y0, 0.0, -0.6 * rz0 * np.sqrt(1 - f * f), f))
    rz1, cz1 = float(torso._rz(y1)), float(torso._cz(y1))
    for f in (0.95, 0.8, 0.55):  # a rounded top under the neck (a plain fan would crease)
        rings.append(torso.ring(y1, 0.0, 0.25 * rz1 * np.sqrt(1 - f * f), f))
    start = np.array([0.0, y0 - 0.6 * rz0, cz0])
    end = np.array([0.0, y1 + 0.25 * rz1, cz1])
    mesh = tube(np.stack(rings), start, end)
    v = mesh.vertices.copy()
    v[:, 1] = np.maximum(v[:, 1], seat_y + SEAT_CLEARANCE)
    return v, mesh.faces


def _chain_skin(bones: tuple[str, ...], v: np.ndarray, f: np.ndarray, joint_h: np.ndarray,
                max_blend: float = np.inf) -> Skin:
    """A skin of surface ``(v, f)`` over the vertical chain ``bones`` (bottom up) whose joints are at
    heights ``joint_h`` (ascending); blends of BLEND times the shorter neighbour, at most ``max_blend`` m."""
    seg_len = np.diff(np.r_[v[:, 1].min(), joint_h, v[:, 1].max()])
    blend = np.minimum(BLEND * np.maximum(np.minimum(seg_len[:-1], seg_len[1:]), 1e-3), max_blend)
    w = chain_weights(v[:, 1], joint_h, blend)
    joints, weights = _top4(w)
    return Skin(bones, v, f, _vertex_normals(v, f), joints, weights, np.argmax(w, axis=1).astype(np.int32),
                np.zeros((len(bones), 3)))


def build_skin(figure: Figure) -> Skin:
    """The torso skin of a standard human (``figure.body_spec`` set by :func:`jackpy.body.make_human`)."""
    return build_skins(figure)[0]


def build_skins(figure: Figure) -> tuple[Skin, ...]:
    """The skins of a standard human: the torso, then each arm (upper arm and the three forearm
    twist parts) and each leg (thigh and shank)."""
    spec = figure.body_spec  # type: ignore[attr-defined]
    sk = build_skeleton(spec, figure.name)
    org = sk.origins
    v, f = _torso_surface(_Torso(spec, sk), float(sk.points["seat_y"][1]))
    skins = [_chain_skin(SPINE_SEGMENTS, v, f, np.array([org[b][1] for b in SPINE_SEGMENTS[1:]]))]
    s = spec.stature / 1.756
    for side in ("left", "right"):
        for chain in LIMB_CHAINS:
            bones = tuple(f"{side}_{b}" for b in chain)  # bottom up; each joint at the lower bone's origin
            if not set(bones) <= set(figure.segments):
                continue
            meshes = [figure.segment(b).psurf.posed_mesh() for b in bones]
            if any(m is None for m in meshes):
                continue
            lv, lf = _limb_surface([m.vertices + org[b] for m, b in zip(meshes, bones)], [m.faces for m in meshes],
                                   org[bones[-1]][[0, 2]])
            skins.append(_chain_skin(bones, lv, lf, np.array([org[b][1] for b in bones[:-1]]), LIMB_BLEND * s))
    return tuple(Skin(k.bones, k.vertices, k.faces, k.normals, k.joints, k.weights, k.owner,
                      np.array([org[b] for b in k.bones])) for k in skins)


def _limb_surface(vertices: list[np.ndarray], faces: list[np.ndarray], axis_xz: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
    """One closed surface around the union of a vertical chain's rigid surfaces (zero pose, m): at
    heights RING_STEP apart, the farthest hit of LIMB_AROUND horizontal rays from the chain's axis,
    smoothed a little along and around; closed by fans just beyond the end sections."""
    tri = np.concatenate([v[f] for v, f in zip(vertices, faces)])
    lo, hi = tri[..., 1].min(axis=1), tri[..., 1].max(axis=1)
    ys = np.arange(hi.max() - 0.002, lo.min() + 0.002, -RING_STEP)
    phi = (np.arange(LIMB_AROUND) + 0.5) * 2 * np.pi / LIMB_AROUND
    dirs = np.column_stack([np.sin(phi), np.zeros_like(phi), np.cos(phi)])  # phi = 0 faces +z
    radii = np.full((len(ys), LIMB_AROUND), np.nan)
    for i, y in enumerate(ys):
        t = tri[(lo <= y) & (hi >= y)]
        radii[i] = _farthest_hits(np.array([axis_xz[0], y, axis_xz[1]]), dirs, t)
    keep = np.isfinite(radii).mean(axis=1) > 0.75
    ys, radii = ys[keep], radii[keep]
    ang = np.r_[phi - 2 * np.pi, phi, phi + 2 * np.pi]
    for row in radii:  # rays that missed (a notch between parts): from their neighbours around
        ok = np.isfinite(np.r_[row, row, row])
        row[~np.isfinite(row)] = np.interp(phi[~np.isfinite(row)], ang[ok], np.r_[row, row, row][ok])
    radii = ndi.gaussian_filter1d(ndi.gaussian_filter1d(radii, 1.0, axis=0, mode="nearest"), 0.7, axis=1, mode="wrap")
    centre = np.array([axis_xz[0], 0.0, axis_xz[1]])
    rings = centre + radii[..., None] * dirs[None] + ys[:, None, None] * np.array([0.0, 1.0, 0.0])
    r_top, r_bottom = radii[0].mean(), radii[-1].mean()
    mesh = tube(rings, centre + [0.0, ys[0] + 0.3 * r_top, 0.0], centre + [0.0, ys[-1] - 0.3 * r_bottom, 0.0])
    return mesh.vertices, mesh.faces


def _farthest_hits(origin: np.ndarray, dirs: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Per ray from ``origin`` along ``dirs`` (n,3), the distance to the farthest of triangles
    ``tri`` (k,3,3) it hits (Moller-Trumbore), NaN where it hits none."""
    if len(tri) == 0:
        return np.full(len(dirs), np.nan)
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    p = np.cross(dirs[:, None, :], e2[None])  # (n,k,3)
    det = np.einsum("kj,nkj->nk", e1, p)
    safe = np.where(np.abs(det) > 1e-14, det, np.inf)
    tvec = origin - tri[:, 0]
    u = np.einsum("kj,nkj->nk", tvec, p) / safe
    q = np.cross(tvec, e1)
    w = np.einsum("nj,kj->nk", dirs, q) / safe
    t = np.einsum("kj,kj->k", e2, q)[None] / safe
    hit = (u >= 0) & (w >= 0) & (u + w <= 1) & (t > 0) & np.isfinite(safe)
    far = np.where(hit, t, -np.inf).max(axis=1)
    return np.where(np.isfinite(far), far, np.nan)


def skin_for(figure: Figure) -> Skin | None:
    """The figure's torso skin, or ``None`` for a figure that is not a jackpy standard human."""
    skins = skins_for(figure)
    return skins[0] if skins else None


def skins_for(figure: Figure) -> tuple[Skin, ...]:
    """The figure's skins (:func:`build_skins`; built once per body specification and cached on the
    figure); empty for a figure that is not a jackpy standard human."""
    spec = getattr(figure, "body_spec", None)
    if spec is None or not set(SPINE_SEGMENTS) <= set(figure.segments):
        return ()
    cached = getattr(figure, "_jackpy_skins", None)
    if cached is not None and cached[0] is spec:
        return cached[1]
    skins = build_skins(figure)
    figure._jackpy_skins = (spec, skins)  # type: ignore[attr-defined]
    return skins


def bone_matrices(skin: Skin, world: np.ndarray | dict[str, np.ndarray], names: list[str] | None = None) -> np.ndarray:
    """(b,4,4) skinning matrices ``W_b T(-o_b)`` from the segments' world transforms: a dict by
    name, or an (s,4,4) array with ``names`` its segment order."""
    if isinstance(world, dict):
        w = np.stack([world[b] for b in skin.bones])
    else:
        index = {n: i for i, n in enumerate(names or [])}
        w = np.asarray(world, float)[[index[b] for b in skin.bones]]
    return w @ skin.inverse_bind()


def deform(skin: Skin, matrices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Linear-blend skinning on the CPU: (positions (n,3), unit normals (n,3)) for ``matrices``
    (b,4,4) from :func:`bone_matrices`; the vertex shader computes the same."""
    m = np.einsum("nk,nkij->nij", skin.weights, np.asarray(matrices, float)[skin.joints])
    p = np.einsum("nij,nj->ni", m[:, :3, :3], skin.vertices) + m[:, :3, 3]
    n = np.einsum("nij,nj->ni", m[:, :3, :3], skin.normals)
    return p, n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)


def skinned_pieces(figure: Figure, world: dict[str, np.ndarray] | None = None) -> dict[str, SkinPiece] | None:
    """The posed skin cut along its owners: ``{segment: piece in that segment's frame}`` for every
    bone, or ``None`` for a figure without a skin. A face belongs to the owner of its first vertex;
    neighbouring pieces share their boundary points and normals exactly, so drawn together (each
    with its segment's world transform) they are the continuous skin."""
    skins = skins_for(figure)
    if not skins:
        return None
    world = figure.world_transforms() if world is None else world
    out = {}
    for skin in skins:
        p, n = deform(skin, bone_matrices(skin, world))
        face_owner = skin.owner[skin.faces[:, 0]]
        for b, name in enumerate(skin.bones):
            faces = skin.faces[face_owner == b]
            used, local = np.unique(faces, return_inverse=True)
            inv = np.linalg.inv(world[name])
            out[name] = SkinPiece(p[used] @ inv[:3, :3].T + inv[:3, 3], local.reshape(-1, 3), n[used] @ inv[:3, :3].T)
    return out


def segment_surfaces(figure: Figure, world: dict[str, np.ndarray] | None = None) -> dict[str, Mesh]:
    """Every segment's drawn surface in its own frame at the current posture: for a standard human
    the posed skin's pieces (:func:`skinned_pieces`) in place of the rigid torso slabs, else (and for
    every other segment) its rigid psurf. Segments without geometry are left out. Report pictures,
    ID-buffer visibility and torque colouring use this, so they show what the window shows."""
    pieces = skinned_pieces(figure, world) or {}
    out = {}
    for name, seg in figure.segments.items():
        if name in pieces:
            out[name] = pieces[name]
            continue
        mesh = seg.psurf.posed_mesh() if seg.psurf is not None else None
        if mesh is not None and len(mesh.faces):
            out[name] = mesh
    return out
