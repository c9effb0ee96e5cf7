"""Obstacles on the floor for walking (digest §2.10.6): each CAD object's part below the figure's
height, projected on the floor (its convex hull, a conservative footprint), inflated by the
figure's half-width (shapely), plus any forbidden zones the caller gives.

Floor coordinates are (x, z) metres.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from shapely.geometry import MultiPoint, Polygon
from shapely.ops import unary_union

#: the figure's half-width beyond its centre line: half the shoulder breadth plus an arm's swing
#: allowance is measured on the figure (m); this margin is added for the baked posture's errors
MARGIN = 0.05


def half_width(figure) -> float:
    """Half the figure's widest breadth in its neutral posture (m): its surface points' lateral extent."""
    from jackpy.body.measure import surface_points

    q, loc = figure.q, figure.location.copy()
    try:
        figure.q = np.zeros_like(q)
        names = [n for n in figure.segments if figure.segment(n).psurf is not None]
        pts = surface_points(figure, names)
        c = figure.site_world("pelvis", "centre")[:3, 3]
        R = figure.site_world("pelvis", "centre")[:3, :3]
        local = (pts - c) @ R
        lateral = np.abs(local[:, 0]).max()
        depth = np.abs(local[:, 2]).max()
        return float(max(lateral, depth))
    finally:
        figure.q = q
        figure.location = loc


def footprints(objects: Iterable, height: float) -> list[Polygon]:
    """Floor footprints of the objects' parts below ``height`` (m above the floor)."""
    out = []
    for o in objects:
        m = o.mesh()
        v = np.asarray(m.vertices, dtype=float)
        w = v @ o.location[:3, :3].T + o.location[:3, 3]
        low = w[w[:, 1] < height]
        if len(low) >= 3:
            hull = MultiPoint([tuple(p) for p in low[:, [0, 2]]]).convex_hull
            if hull.area > 0:
                out.append(hull)
    return out


def obstacles(objects: Iterable, height: float, radius: float,
              forbidden: Iterable[Polygon] = ()) -> Polygon:
    """The union of the footprints and forbidden zones inflated by ``radius`` (m)."""
    shapes = footprints(objects, height) + list(forbidden)
    if not shapes:
        return Polygon()
    return unary_union([s.buffer(radius, join_style=2) for s in shapes])
