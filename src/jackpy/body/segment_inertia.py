"""Segment mass, centre of mass and inertia from de Leva (1996), scaled to body mass.

Each de Leva segment's mass fraction (``data/de_leva_1996.csv``) is shared among the figure segments
that make it up **in proportion to their generated volumes** (uniform density, the rule the quarterly
report uses for the hand): e.g. the hand's 0.61 % over palm and 15 phalanges, the trunk's upper / mid /
lower parts over their vertebral slabs. Segments that are one de Leva segment each (upper arm, thigh,
shank) take de Leva's centre-of-mass position and radii of gyration; the others take their mesh's
uniform-density centroid and inertia, and then every member of a multi-segment de Leva segment
(forearm, hand, foot, head + neck, trunk) is moved along de Leva's endpoint axis so that the
**combined** centre of mass lies at de Leva's position (``com_pct`` of the endpoint distance). Endpoints
on the figure: forearm elbow -> wrist joint centres, hand wrist -> 3rd metacarpophalangeal joint
(de Leva's 3rd metacarpale), foot heel -> toe tip, head vertex -> mid-gonion and trunk suprasternale ->
mid-hip (the last two along the body axis, their lengths de Leva's mean lengths scaled by stature /
de Leva's mean stature: 1.741 m men, 1.735 m women). Masses sum to body mass by construction.
"""

from __future__ import annotations

from functools import cache

import numpy as np

from jackpy.body.anthropometry import data_rows
from jackpy.peabody.geometry import Mesh
from jackpy.peabody.model import Figure, Segment

#: de Leva segment -> figure segments (``{side}`` expands to left/right)
GROUPS: dict[str, list[str]] = {
    "head": ["head", "neck", "left_eye", "right_eye"],
    "upper_trunk": [f"t{k}" for k in range(1, 10)] + ["left_clavicle", "right_clavicle"],
    "mid_trunk": ["t10", "t11", "t12", "l1", "l2", "l3"],
    "lower_trunk": ["l4", "l5", "pelvis"],
    "upper_arm": ["{side}_upper_arm"],
    "forearm": ["{side}_forearm", "{side}_forearm_mid", "{side}_forearm_distal"],
    "hand": ["{side}_palm"] + [f"{{side}}_{d}_{k}" for d in ("thumb", "index", "middle", "ring", "little")
                               for k in (1, 2, 3)],
    "thigh": ["{side}_thigh"],
    "shank": ["{side}_shank"],
    "foot": ["{side}_foot", "{side}_toes"],
}
#: de Leva segments whose proximal and distal endpoints are these figure sites (segment, site) pairs
ENDPOINTS = {"upper_arm": ("base", "elbow"), "thigh": ("base", "knee"), "shank": ("base", "ankle")}
#: multi-segment de Leva segments: (first endpoint, second endpoint) as (segment, site) with {side}
GROUP_ENDPOINTS = {"forearm": (("{side}_forearm", "base"), ("{side}_palm", "base")),
                   "hand": (("{side}_palm", "base"), ("{side}_middle_1", "base")),
                   "foot": (("{side}_foot", "heel"), ("{side}_toes", "tip"))}
#: de Leva's (1996) sample mean statures (Zatsiorsky-Seluyanov subjects), m
DE_LEVA_STATURE = {"male": 1.741, "female": 1.735}


@cache
def de_leva(sex: str) -> dict[str, dict[str, float]]:
    """de Leva's Table 4 for ``sex``: ``{segment: {mass_pct, com_pct, r_sag, r_trans, r_long, length_mm}}``."""
    keys = ("mass_pct", "com_pct", "r_sag", "r_trans", "r_long", "length_mm")
    return {r["segment"]: {k: float(r[k]) for k in keys} for r in data_rows("de_leva_1996.csv") if r["sex"] == sex}


def mesh_mass_properties(mesh: Mesh) -> tuple[float, np.ndarray, np.ndarray]:
    """Volume (m^3), centroid (3,) and inertia tensor per unit density about the centroid (3,3)."""
    v = mesh.vertices[mesh.faces]
    a, b, c = v[:, 0], v[:, 1], v[:, 2]
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    vol = det.sum() / 6.0
    centroid = (det[:, None] * (a + b + c)).sum(axis=0) / (24.0 * vol)
    # second moments  integral x_i x_j dV over tetrahedra (0, a, b, c)
    s = a + b + c
    outer = (np.einsum("n,ni,nj->ij", det, s, s) + np.einsum("n,ni,nj->ij", det, a, a)
             + np.einsum("n,ni,nj->ij", det, b, b) + np.einsum("n,ni,nj->ij", det, c, c)) / 120.0
    outer -= vol * np.outer(centroid, centroid)
    inertia = np.trace(outer) * np.eye(3) - outer
    return float(vol), centroid, inertia


def assign_mass_properties(figure: Figure, sex: str, body_mass: float) -> None:
    """Set every segment's ``mass`` (kg), ``com`` and ``inertia`` (segment frame, SI) from its mesh and
    de Leva's table; segments without a mesh get zero mass."""
    table = de_leva(sex)
    total_pct = sum(table[g]["mass_pct"] * (2 if "{side}" in m[0] else 1) for g, m in GROUPS.items())
    for seg in figure.segments.values():
        seg.mass, seg.com, seg.inertia = 0.0, np.zeros(3), np.zeros((3, 3))
    for dl_name, members in GROUPS.items():
        sides = ("left", "right") if any("{side}" in m for m in members) else ("",)
        for side in sides:
            names = [m.format(side=side) for m in members]
            props = {n: mesh_mass_properties(figure.segment(n).psurf.posed_mesh()) for n in names}
            total_vol = sum(p[0] for p in props.values())
            group_mass = body_mass * table[dl_name]["mass_pct"] / total_pct  # table sums to 99.99-100 %
            for n, (vol, centroid, inertia) in props.items():
                seg = figure.segment(n)
                seg.mass = group_mass * vol / total_vol
                seg.com = centroid
                seg.inertia = inertia * seg.mass / vol
            if dl_name in ENDPOINTS:
                _de_leva_segment(figure.segment(names[0]), ENDPOINTS[dl_name], table[dl_name])
            elif dl_name in GROUP_ENDPOINTS:
                a, b = ((seg.format(side=side), site) for seg, site in GROUP_ENDPOINTS[dl_name])
                p0, p1 = figure.site_world(*a)[:3, 3], figure.site_world(*b)[:3, 3]
                _place_group_com(figure, names, p0, p1, table[dl_name]["com_pct"])
    stature_ratio = float(figure.site_world("head", "top")[1, 3] - _floor(figure)) / DE_LEVA_STATURE[sex]
    top = figure.site_world("head", "top")[:3, 3]
    head = table["head"]
    _place_group_com(figure, [m.format(side="") for m in GROUPS["head"]], top,
                     top - [0.0, head["length_mm"] * 1e-3 * stature_ratio, 0.0], head["com_pct"])
    hip = figure.site_world("pelvis", "centre")[:3, 3]
    trunk = table["trunk"]
    members = GROUPS["upper_trunk"] + GROUPS["mid_trunk"] + GROUPS["lower_trunk"]
    _place_group_com(figure, members, hip + [0.0, trunk["length_mm"] * 1e-3 * stature_ratio, 0.0], hip,
                     trunk["com_pct"])
    figure.topology_changed()  # the kinematics cache holds mass properties


def _floor(figure: Figure) -> float:
    return min(float(figure.site_world(f"{side}_foot", "heel")[1, 3]) for side in ("left", "right"))


def _place_group_com(figure: Figure, names: list[str], p0: np.ndarray, p1: np.ndarray, com_pct: float) -> None:
    """Move the centres of mass of segments ``names`` (all frames parallel to the world: zero pose) by one
    common shift along ``p1 - p0`` so their combined centre of mass lies ``com_pct`` % of the way."""
    world = figure.world_transforms()
    masses = np.array([figure.segment(n).mass for n in names])
    coms = np.array([world[n][:3, :3] @ figure.segment(n).com + world[n][:3, 3] for n in names])
    current = masses @ coms / masses.sum()
    axis = (p1 - p0) / np.linalg.norm(p1 - p0)
    target = p0 + (p1 - p0) * com_pct / 100.0
    shift = axis * float(np.dot(target - current, axis))
    for n in names:
        seg = figure.segment(n)
        seg.com = seg.com + world[n][:3, :3].T @ shift


def _de_leva_segment(seg: Segment, ends: tuple[str, str], row: dict[str, float]) -> None:
    """COM at de Leva's fraction between the two sites; principal inertia from the radii of gyration
    (about x: medio-lateral = r_trans, y: long axis = r_long, z: antero-posterior = r_sag)."""
    p0 = seg.site(ends[0]).location[:3, 3]
    p1 = seg.site(ends[1]).location[:3, 3]
    length = float(np.linalg.norm(p1 - p0))
    seg.com = p0 + (p1 - p0) * row["com_pct"] / 100.0
    r = np.array([row["r_trans"], row["r_long"], row["r_sag"]]) / 100.0 * length
    seg.inertia = np.diag(seg.mass * r ** 2)
