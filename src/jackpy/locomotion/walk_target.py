"""Where to stand to walk to a target: a floor point, a site (``object.site``) or a CAD object
(issue 13 "walk to a point, a site or an object"; digest §2.10.6).

- a **point** ``(x, z)`` (or a world ``(x, y, z)``): stand there, facing ``facing`` (default: along
  the path's end);
- an **object** (its name or the object): stand in front of it, on the side nearest the start, at
  the standing distance ``r + STAND_GAP`` from its floor footprint (``r``: the figure's half-width
  plus the planner's margin, the inflation of :mod:`.floor_plan`), square to an edge at least
  ``CORNER`` in from the footprint's corners where the edge allows, facing the footprint;
- a **site**: the same ring round the site's object, at its point nearest the site, facing the
  site; a site standing clear of every obstacle (farther than the standing distance from its
  object) is walked to, facing it from the path.

Every candidate standing point outside the inflated obstacles is tried nearest the start first
(at most ``TRIES``) until one has a free path. Floor coordinates (x, z) metres; headings rad about
+y, 0 facing +z.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from shapely.geometry import MultiPoint, Point
from shapely.ops import nearest_points, unary_union

from jackpy.errors import JackpyError
from jackpy.locomotion.walk_to import WalkError

#: beyond the inflated footprint (m): the pelvis centre stands this much further from the object
STAND_GAP = 0.02
#: spacing of the candidate standing points along the ring (m) and how many are tried
RING_SPACING = 0.05
TRIES = 8
#: an object is stood in front of square to an edge, at least this far in from its corners (m)
CORNER = 0.15


@dataclass
class Goal:
    """Where the walk ends: the pelvis centre's floor point (x, z), the heading at the end (None:
    along the path) and what it was made from (``"point"``, ``"object NAME"``, ``"site NAME"``)."""

    point: tuple[float, float]
    facing: float | None
    what: str


def heading_to(a, b) -> float:
    """Heading (rad) from floor point ``a`` toward ``b``."""
    d = np.asarray(b, dtype=float) - np.asarray(a, dtype=float)
    return float(np.arctan2(d[0], d[1]))


def find_object(objects: list, name: str) -> Any:
    for o in objects:
        if o.name == name:
            return o
    raise WalkError(f"no object named {name!r} in the scene (objects: {', '.join(o.name for o in objects)})")


def site_point(obj: Any, site: str) -> np.ndarray:
    """World position (m) of ``obj``'s user site ``site``."""
    sites = obj.user_sites()
    if site not in sites:
        raise WalkError(f"object {obj.name!r} has no site {site!r} (sites: {', '.join(sorted(sites)) or 'none'})")
    return (obj.location @ sites[site].location)[:3, 3]


def standing_goals(figure, target, objects: list, start, facing: float | None = None,
                   forbidden=()) -> list[Goal]:
    """The :class:`Goal` candidates for ``target`` (see the module docstring), best first."""
    from jackpy.locomotion import floor_plan

    height = float(max(figure.site_world("head", "base")[1, 3] + 0.15, 0.0))
    r = floor_plan.half_width(figure) + floor_plan.MARGIN
    blocked = floor_plan.obstacles(objects, height, r, forbidden)
    if not isinstance(target, str) and not hasattr(target, "mesh"):
        v = np.asarray(target, dtype=float).ravel()
        if v.size not in (2, 3) or not np.all(np.isfinite(v)):
            raise WalkError(f"a walk target is a point (x, z), a site 'object.site' or an object, not {target!r}")
        xz = (float(v[0]), float(v[-1]))
        return [Goal(xz, facing, "point")]
    if not isinstance(target, str):
        obj, site = target, None
    else:
        name, _, site = target.partition(".")
        obj, site = find_object(objects, name), (site or None)
    fps = floor_plan.footprints([obj], height)
    look = None if site is None else site_point(obj, site)[[0, 2]]
    what = f"{'site' if site else 'object'} {target if isinstance(target, str) else obj.name}"
    # what to stand beside: the object's footprint, or its floor point when nothing of it is low
    # enough to bump into (a shelf overhead); the free space ends at the inflated obstacles
    foot = fps[0] if fps else Point(*obj.location[:3, 3][[0, 2]])
    region = unary_union([blocked, foot.buffer(r, join_style=2)])
    if look is not None and not region.buffer(STAND_GAP).contains(Point(*look)):
        return [Goal((float(look[0]), float(look[1])), facing, what)]  # a site out in the open
    edge = region.buffer(STAND_GAP, join_style=2).boundary
    cands = []
    for line in getattr(edge, "geoms", [edge]):
        n = max(8, int(np.ceil(line.length / RING_SPACING)))
        cands += [np.array(line.interpolate(k / n, normalized=True).coords[0]) for k in range(n)]
    inner = blocked.buffer(-1e-6) if not blocked.is_empty else blocked
    cands = [c for c in cands if inner.is_empty or not inner.contains(Point(*c))]
    if not cands:
        raise WalkError(f"there is no room to stand beside {obj.name!r}")
    s = np.asarray(start, dtype=float)
    if look is not None:  # nearest the site
        cands.sort(key=lambda c: (float(np.linalg.norm(c - look)), float(np.linalg.norm(c - s))))
    else:  # nearest the object (2 cm bands: the ring round it), square to an edge, nearest the start
        corners = MultiPoint(list(foot.exterior.coords)) if hasattr(foot, "exterior") else None

        def off_corner(c: np.ndarray) -> bool:
            near = nearest_points(foot, Point(*c))[0]
            return corners is not None and near.distance(corners) < CORNER

        cands.sort(key=lambda c: (int(foot.distance(Point(*c)) / 0.02), off_corner(c), float(np.linalg.norm(c - s))))
    out = []
    for c in cands[:TRIES]:
        if look is not None:
            face = heading_to(c, look)
        else:
            face = heading_to(c, nearest_points(foot, Point(*c))[0].coords[0])
        out.append(Goal((float(c[0]), float(c[1])), face if facing is None else facing, what))
    return out


def plan(figure, p, target, objects: list, facing: float | None = None, start=None, forbidden=()):
    """Footsteps for ``figure`` (gait ``p``) from ``start`` (its pelvis floor point by default) to
    ``target`` (a point, ``"object.site"``, an object name or object) around ``objects``:
    ``(steps, path, goal)``."""
    from jackpy.locomotion.walk_to import walk_to

    if start is None:
        c = figure.site_world("pelvis", "centre")[:3, 3]
        start = (float(c[0]), float(c[2]))
    goals = standing_goals(figure, target, objects, start, facing, forbidden)
    last: Exception | None = None
    for g in goals:
        try:
            steps, path, _ = walk_to(figure, p, g.point, objects, facing=g.facing, forbidden=forbidden, start=start)
            return steps, path, g
        except JackpyError as exc:
            last = exc
    raise WalkError(f"cannot walk to {goals[0].what}: {last}")
