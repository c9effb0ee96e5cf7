"""Ground-plane geometry of balance: support polygon and the (x, z) balance parametrisation.

Book §4.1.2 (shared/spec/behaviors.md §2.4). Everything here is 2-D in the floor plane: a point is
``(world x, world z)`` in metres (y is up and dropped). The support polygon is the convex hull of
the foot contact points; the *balance line* joins the left and right foot reference points.

Balance parameters of a floor point ``b``:

- ``x``: parameter of the projection ``p`` of ``b`` onto the (infinite) balance line, 0 at the left
  reference point, 1 at the right one, i.e. the fraction of weight on the right foot;
- ``z``: signed distance from ``p`` to ``b`` along *forward* (the balance-line normal on the side the
  figure faces), divided by the distance from ``p`` to the hull boundary that way: +1 on the front
  edge, -1 on the back edge. For ``p`` outside the feet (``x`` outside [0, 1]) the normaliser is
  taken at the nearest point of the balance segment, so the map stays invertible.

[proposal] When the feet are closer than :data:`MIN_LINE` the balance line is replaced by a line
through their midpoint perpendicular to the facing direction, one :data:`MIN_LINE` long.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: shortest usable balance line (m)
MIN_LINE = 0.02


def floor(p: np.ndarray) -> np.ndarray:
    """World point(s) (...,3) to floor coordinates (...,2) = (x, z)."""
    p = np.asarray(p, dtype=float)
    return p[..., [0, 2]]


def convex_hull(points: np.ndarray) -> np.ndarray:
    """Counter-clockwise convex hull (m,2) of floor points (n,2) (Andrew's monotone chain)."""
    pts = np.unique(np.asarray(points, dtype=float).reshape(-1, 2), axis=0)
    if len(pts) <= 2:
        return pts

    def cross(o: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list[np.ndarray] = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 1e-15:
            lower.pop()
        lower.append(p)
    upper: list[np.ndarray] = []
    for p in pts[::-1]:
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 1e-15:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def signed_distance(p: np.ndarray, hull: np.ndarray) -> float:
    """Signed distance (m) from floor point ``p`` to a CCW convex polygon: negative inside."""
    p = np.asarray(p, dtype=float)
    n = len(hull)
    if n == 0:
        return np.inf
    if n == 1:
        return float(np.linalg.norm(p - hull[0]))
    a = hull
    b = np.roll(hull, -1, axis=0)
    e = b - a
    ee = np.maximum((e * e).sum(axis=1), 1e-300)
    t = np.clip(((p - a) * e).sum(axis=1) / ee, 0.0, 1.0)
    d = np.sqrt((((a + t[:, None] * e) - p) ** 2).sum(axis=1)).min()
    if n == 2:
        return float(d)
    inside = np.all(e[:, 0] * (p[1] - a[:, 1]) - e[:, 1] * (p[0] - a[:, 0]) >= 0.0)
    return float(-d if inside else d)


def ray_exit(p: np.ndarray, d: np.ndarray, hull: np.ndarray) -> float:
    """Distance (m) along unit direction ``d`` from ``p`` (inside) to the hull boundary; 0 if none."""
    if len(hull) < 3:
        return 0.0
    a = hull
    e = np.roll(hull, -1, axis=0) - a
    # solve p + t d = a + s e
    den = d[0] * e[:, 1] - d[1] * e[:, 0]
    w = a - p
    ok = np.abs(den) > 1e-15
    t = np.where(ok, (w[:, 0] * e[:, 1] - w[:, 1] * e[:, 0]) / np.where(ok, den, 1.0), -np.inf)
    s = np.where(ok, (w[:, 0] * d[1] - w[:, 1] * d[0]) / np.where(ok, den, 1.0), -1.0)
    hit = ok & (s >= -1e-12) & (s <= 1 + 1e-12) & (t >= 0)
    return float(t[hit].max()) if hit.any() else 0.0


def yaw_of(forward: np.ndarray) -> float:
    """Yaw (rad) of a world or floor direction: the rotation about +y taking +z to it."""
    f = np.asarray(forward, dtype=float)
    fx, fz = (f[0], f[2]) if f.size == 3 else (f[0], f[1])
    return float(np.arctan2(fx, fz))


def wrap(angle: float) -> float:
    """Angle wrapped to (-pi, pi]."""
    return float(-((-angle + np.pi) % (2 * np.pi) - np.pi))


def mean_yaw(a: float, b: float) -> float:
    """Circular mean of two yaws (rad): the yaw of the sum of their unit vectors."""
    return float(np.arctan2(np.sin(a) + np.sin(b), np.cos(a) + np.cos(b)))


@dataclass
class BalanceFrame:
    """Balance line and support polygon of one posture, in floor coordinates (m).

    ``left``/``right`` are the foot reference points, ``facing`` a rough horizontal direction the
    figure faces (only its side of the balance line matters), ``hull`` the CCW support polygon.
    """

    left: np.ndarray
    right: np.ndarray
    facing: np.ndarray
    hull: np.ndarray

    def __post_init__(self) -> None:
        self.left = np.asarray(self.left, dtype=float)
        self.right = np.asarray(self.right, dtype=float)
        f = np.asarray(self.facing, dtype=float)
        f = f / max(np.linalg.norm(f), 1e-12)
        u = self.right - self.left
        if np.linalg.norm(u) < MIN_LINE:
            mid = 0.5 * (self.left + self.right)
            side = np.array([-f[1], f[0]])  # the figure's right (facing +z, right is -x)
            self.left = mid - 0.5 * MIN_LINE * side
            self.right = mid + 0.5 * MIN_LINE * side
            u = self.right - self.left
        self.origin = self.left
        self.line = u
        n = np.array([-u[1], u[0]]) / np.linalg.norm(u)
        self.forward = n if n @ f >= 0 else -n

    def _extent(self, x: float, sign: float) -> float:
        """Distance from the balance segment at ``x`` (clamped) to the hull along ``sign``·forward."""
        p = self.origin + np.clip(x, 0.0, 1.0) * self.line
        return max(ray_exit(p, sign * self.forward, self.hull), 1e-3)

    def params(self, b: np.ndarray) -> tuple[float, float]:
        """Balance parameters (x, z) of floor point ``b``."""
        b = np.asarray(b, dtype=float)
        x = float((b - self.origin) @ self.line / (self.line @ self.line))
        dist = float((b - self.origin - x * self.line) @ self.forward)
        return x, dist / self._extent(x, 1.0 if dist >= 0 else -1.0)

    def point(self, x: float, z: float) -> np.ndarray:
        """Floor point of balance parameters (x, z); the inverse of :meth:`params`."""
        p = self.origin + x * self.line
        return p + z * self._extent(x, 1.0 if z >= 0 else -1.0) * self.forward

    def margin(self, b: np.ndarray) -> float:
        """Signed distance (m) of ``b`` to the support polygon, negative inside."""
        return signed_distance(b, self.hull)
