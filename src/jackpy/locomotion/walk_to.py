"""Walk to a floor point around obstacles: a visibility graph over the inflated floor obstacles
(:mod:`.floor_plan`), shortest path by Dijkstra, then footsteps (:mod:`.footsteps`)."""

from __future__ import annotations

import heapq

import numpy as np
from shapely.geometry import LineString, Point, Polygon

from jackpy.errors import JackpyError


class WalkError(JackpyError):
    """A walk the scene does not allow (a goal or start inside an obstacle, no way round, a
    target that is not there): bad input, one line, exit 2."""

    exit_code = 2


def visibility_path(start, goal, blocked: Polygon) -> np.ndarray:
    """Shortest polyline (N, 2) from ``start`` to ``goal`` avoiding the interior of ``blocked``."""
    s, g = tuple(map(float, start)), tuple(map(float, goal))
    for name, p in (("start", s), ("goal", g)):
        if not blocked.is_empty and blocked.contains(Point(p)):
            raise WalkError(f"the {name} point ({p[0]:.2f}, {p[1]:.2f}) lies inside an obstacle")
    nodes = [s, g]
    if not blocked.is_empty:
        polys = getattr(blocked, "geoms", [blocked])
        for poly in polys:
            # corners pushed out a little so that paths along them stay outside
            for c in poly.buffer(0.01, join_style=2).exterior.coords[:-1]:
                nodes.append(tuple(c))
    inner = blocked.buffer(-1e-6) if not blocked.is_empty else blocked

    def free(a, b) -> bool:
        return inner.is_empty or not LineString([a, b]).intersects(inner)

    n = len(nodes)
    dist = [np.inf] * n
    prev = [-1] * n
    dist[0] = 0.0
    heap = [(0.0, 0)]
    while heap:
        d, i = heapq.heappop(heap)
        if d > dist[i]:
            continue
        if i == 1:
            break
        for j in range(n):
            if j != i and free(nodes[i], nodes[j]):
                nd = d + float(np.hypot(nodes[i][0] - nodes[j][0], nodes[i][1] - nodes[j][1]))
                if nd < dist[j]:
                    dist[j], prev[j] = nd, i
                    heapq.heappush(heap, (nd, j))
    if not np.isfinite(dist[1]):
        raise WalkError("no path to the goal around the obstacles")
    path, k = [], 1
    while k != -1:
        path.append(nodes[k])
        k = prev[k]
    return np.array(path[::-1])


def walk_to(figure, p, goal, objects=(), facing: float | None = None, forbidden=(), start=None):
    """Footsteps for ``figure`` (gait ``p``) from ``start`` (its pelvis floor point by default) to
    ``goal`` (x, z) around ``objects``' floor footprints and ``forbidden`` polygons."""
    from jackpy.locomotion import floor_plan, footsteps

    if start is None:
        c = figure.site_world("pelvis", "centre")[:3, 3]
        start = (c[0], c[2])
    height = float(max(figure.site_world("head", "base")[1, 3] + 0.15, 0.0))
    blocked = floor_plan.obstacles(objects, height, floor_plan.half_width(figure) + floor_plan.MARGIN, forbidden)
    path = visibility_path(start, goal, blocked)
    # the footstep spline passes through the corners: add midpoints so it hugs the polyline
    dense = [path[0]]
    for a, b in zip(path[:-1], path[1:]):
        k = max(1, int(np.ceil(np.linalg.norm(b - a) / 0.25)))
        dense += [a + (b - a) * (i / k) for i in range(1, k + 1)]
    return footsteps.from_path(p, np.array(dense), facing=facing), path, blocked
