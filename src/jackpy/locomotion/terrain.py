"""Terrain (Sims 1987, Ch. 8): a regular height grid with O(1) bilinear height and normal queries,
and a forbidden-footstep raster (steep slopes plus a foot-radius band on their downhill side, plus
user polygons).

World frame: y up, heights in metres. Grid vertex ``(i, j)`` (row ``i`` along z, column ``j``
along x) lies at ``x = x0 + j * cell``, ``z = z0 + i * cell``. Queries outside the grid clamp to
its edge.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from jackpy.errors import ParseError

#: default forbidden-zone parameters (also in :class:`jackpy.locomotion.config.WalkConfig`)
DEFAULT_MAX_SLOPE_DEG = 35.0
DEFAULT_FOOT_RADIUS = 0.03


class Terrain:
    """Height grid ``heights[i, j]`` (m) with spacing ``cell`` (m) and origin ``(x0, z0)``."""

    def __init__(self, heights: np.ndarray, cell: float, x0: float = 0.0, z0: float = 0.0, *,
                 max_slope_deg: float = DEFAULT_MAX_SLOPE_DEG, foot_radius: float = DEFAULT_FOOT_RADIUS,
                 polygons: Sequence[Sequence[Sequence[float]]] = (), name: str = "terrain") -> None:
        h = np.asarray(heights, dtype=float)
        if h.ndim != 2 or h.shape[0] < 2 or h.shape[1] < 2:
            raise ValueError("terrain heights must be a 2-D grid of at least 2 x 2 values")
        if not np.all(np.isfinite(h)):
            raise ValueError("terrain heights must be finite")
        if not cell > 0:
            raise ValueError(f"terrain cell size must be > 0, not {cell}")
        self.heights, self.cell, self.x0, self.z0, self.name = h, float(cell), float(x0), float(z0), name
        self.max_slope_deg, self.foot_radius = float(max_slope_deg), float(foot_radius)
        self.polygons = [np.asarray(p, dtype=float).reshape(-1, 2) for p in polygons]
        self._forbidden: np.ndarray | None = None

    # ----- geometry ---------------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, int]:
        return self.heights.shape  # type: ignore[return-value]

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """``(x_min, x_max, z_min, z_max)`` in metres."""
        nz, nx = self.shape
        return self.x0, self.x0 + (nx - 1) * self.cell, self.z0, self.z0 + (nz - 1) * self.cell

    def _cell_coords(self, x: Any, z: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        nz, nx = self.shape
        u = np.clip((np.asarray(x, dtype=float) - self.x0) / self.cell, 0.0, nx - 1.0)
        v = np.clip((np.asarray(z, dtype=float) - self.z0) / self.cell, 0.0, nz - 1.0)
        j = np.minimum(np.floor(u).astype(int), nx - 2)
        i = np.minimum(np.floor(v).astype(int), nz - 2)
        return i, j, u - j, v - i

    def height(self, x: Any, z: Any) -> Any:
        """Bilinear height (m) at world ``(x, z)``; scalars or arrays (vectorised, O(1) each)."""
        i, j, fu, fv = self._cell_coords(x, z)
        h = self.heights
        out = ((h[i, j] * (1 - fu) + h[i, j + 1] * fu) * (1 - fv)
               + (h[i + 1, j] * (1 - fu) + h[i + 1, j + 1] * fu) * fv)
        return float(out) if np.ndim(out) == 0 else out

    def gradient(self, x: Any, z: Any) -> tuple[Any, Any]:
        """``(dh/dx, dh/dz)`` of the bilinear patch at ``(x, z)``."""
        i, j, fu, fv = self._cell_coords(x, z)
        h = self.heights
        dx = ((h[i, j + 1] - h[i, j]) * (1 - fv) + (h[i + 1, j + 1] - h[i + 1, j]) * fv) / self.cell
        dz = ((h[i + 1, j] - h[i, j]) * (1 - fu) + (h[i + 1, j + 1] - h[i, j + 1]) * fu) / self.cell
        return (float(dx), float(dz)) if np.ndim(dx) == 0 else (dx, dz)

    def normal(self, x: float, z: float) -> np.ndarray:
        """Unit upward surface normal at ``(x, z)``."""
        gx, gz = self.gradient(x, z)
        n = np.array([-gx, 1.0, -gz])
        return n / np.linalg.norm(n)

    def max_height_along(self, a: Sequence[float], b: Sequence[float], step: float | None = None) -> float:
        """Highest terrain point (m) on the straight xz segment from ``a`` to ``b`` (sampled at
        half a cell or ``step``)."""
        a2, b2 = np.asarray(a, float)[[0, -1]], np.asarray(b, float)[[0, -1]]
        n = max(2, int(math.ceil(np.linalg.norm(b2 - a2) / (step or self.cell * 0.5))) + 1)
        s = np.linspace(0.0, 1.0, n)
        pts = a2[None, :] + s[:, None] * (b2 - a2)[None, :]
        return float(np.max(self.height(pts[:, 0], pts[:, 1])))

    # ----- forbidden zones ----------------------------------------------------------------------
    def steep_cells(self) -> np.ndarray:
        """Boolean ``(nz-1, nx-1)``: cells whose slope (largest of the cell's facet slopes) exceeds
        ``max_slope_deg``."""
        h, c = self.heights, self.cell
        gx = np.maximum(np.abs(h[:-1, 1:] - h[:-1, :-1]), np.abs(h[1:, 1:] - h[1:, :-1])) / c
        gz = np.maximum(np.abs(h[1:, :-1] - h[:-1, :-1]), np.abs(h[1:, 1:] - h[:-1, 1:])) / c
        slope = np.degrees(np.arctan(np.hypot(gx, gz)))
        return slope > self.max_slope_deg

    @property
    def raster_step(self) -> float:
        """Spacing (m) of the forbidden raster: a quarter of the foot radius, at most half a cell."""
        return min(0.5 * self.cell, max(self.foot_radius, 1e-3) / 4.0)

    @property
    def forbidden(self) -> np.ndarray:
        """The forbidden raster ``[a, b]`` at ``x = x0 + b * raster_step``, ``z = z0 + a * raster_step``
        (computed once)."""
        if self._forbidden is None:
            self._forbidden = self._compute_forbidden()
        return self._forbidden

    def _raster_axes(self) -> tuple[np.ndarray, np.ndarray]:
        x1, x2, z1, z2 = self.extent
        r = self.raster_step
        return (self.x0 + np.arange(int(math.floor((x2 - x1) / r + 1e-9)) + 1) * r,
                self.z0 + np.arange(int(math.floor((z2 - z1) / r + 1e-9)) + 1) * r)

    def _compute_forbidden(self) -> np.ndarray:
        """A sample is forbidden if it lies on a steep cell, or some point of a steep cell within
        ``foot_radius`` of it is higher than it (the downhill band, digest §6.2: a foot there would
        hit the face), or it lies inside a user polygon."""
        xs, zs = self._raster_axes()
        out = np.zeros((len(zs), len(xs)), dtype=bool)
        r, c, fr = self.raster_step, self.cell, self.foot_radius
        for i, j in zip(*np.nonzero(self.steep_cells())):
            cx0, cz0 = self.x0 + j * c, self.z0 + i * c
            b0, b1 = np.searchsorted(xs, cx0 - fr - r), np.searchsorted(xs, cx0 + c + fr + r, side="right")
            a0, a1 = np.searchsorted(zs, cz0 - fr - r), np.searchsorted(zs, cz0 + c + fr + r, side="right")
            zz, xx = np.meshgrid(zs[a0:a1], xs[b0:b1], indexing="ij")
            on = (xx >= cx0) & (xx <= cx0 + c) & (zz >= cz0) & (zz <= cz0 + c)
            # the steep cell sampled finely: is any of it within a foot radius and above the point?
            k = int(math.ceil(c / r)) + 1
            sub = np.linspace(0.0, c, k)
            sz, sx = np.meshgrid(cz0 + sub, cx0 + sub, indexing="ij")
            sx, sz = sx.ravel(), sz.ravel()
            sh = self.height(sx, sz)
            q = np.column_stack([xx.ravel(), zz.ravel()])
            near = np.hypot(q[:, :1] - sx[None, :], q[:, 1:] - sz[None, :]) <= fr
            above = sh[None, :] > self.height(q[:, 0], q[:, 1])[:, None] + 1e-6
            band = np.any(near & above, axis=1).reshape(xx.shape)
            out[a0:a1, b0:b1] |= on | band
        if self.polygons:
            import shapely

            zz, xx = np.meshgrid(zs, xs, indexing="ij")
            for poly in self.polygons:
                out |= shapely.contains_xy(shapely.Polygon(poly), xx, zz)
        return out

    def is_forbidden(self, x: Any, z: Any) -> Any:
        """Whether a foothold at ``(x, z)`` is forbidden: the nearest raster sample (O(1))."""
        f = self.forbidden
        r = self.raster_step
        b = np.clip(np.rint((np.asarray(x, float) - self.x0) / r).astype(int), 0, f.shape[1] - 1)
        a = np.clip(np.rint((np.asarray(z, float) - self.z0) / r).astype(int), 0, f.shape[0] - 1)
        out = f[a, b]
        return bool(out) if np.ndim(out) == 0 else out

    # ----- construction and files -----------------------------------------------------------------
    @classmethod
    def from_function(cls, fn: Callable[[np.ndarray, np.ndarray], np.ndarray], x_range: tuple[float, float],
                      z_range: tuple[float, float], cell: float, **kw: Any) -> "Terrain":
        """Sample ``fn(x, z) -> height`` on a grid covering the ranges (m)."""
        nx = int(round((x_range[1] - x_range[0]) / cell)) + 1
        nz = int(round((z_range[1] - z_range[0]) / cell)) + 1
        zz, xx = np.meshgrid(z_range[0] + np.arange(nz) * cell, x_range[0] + np.arange(nx) * cell, indexing="ij")
        return cls(fn(xx, zz), cell, x_range[0], z_range[0], **kw)

    @classmethod
    def flat(cls, size: float = 20.0, cell: float = 0.5, height: float = 0.0) -> "Terrain":
        """A flat square terrain centred on the origin."""
        return cls.from_function(lambda x, z: np.full_like(x, height), (-size / 2, size / 2),
                                 (-size / 2, size / 2), cell, name="flat")

    @classmethod
    def from_mesh(cls, vertices: np.ndarray, faces: np.ndarray, cell: float, **kw: Any) -> "Terrain":
        """Sample a triangle mesh (world metres, y up) by vertical rays on a grid over its xz extent;
        cells with no surface above take the lowest height hit."""
        import trimesh

        mesh = trimesh.Trimesh(np.asarray(vertices, float), np.asarray(faces, int), process=False)
        lo, hi = mesh.bounds
        nx = int(math.floor((hi[0] - lo[0]) / cell)) + 1
        nz = int(math.floor((hi[2] - lo[2]) / cell)) + 1
        zz, xx = np.meshgrid(lo[2] + np.arange(nz) * cell, lo[0] + np.arange(nx) * cell, indexing="ij")
        origins = np.column_stack([xx.ravel(), np.full(xx.size, hi[1] + 1.0), zz.ravel()])
        dirs = np.tile([0.0, -1.0, 0.0], (xx.size, 1))
        locs, idx, _ = mesh.ray.intersects_location(origins, dirs, multiple_hits=False)
        h = np.full(xx.size, np.nan)
        h[idx] = locs[:, 1]
        h[np.isnan(h)] = np.nanmin(h) if np.any(~np.isnan(h)) else 0.0
        return cls(h.reshape(nz, nx), cell, lo[0], lo[2], **kw)

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (also how a scene document stores it)."""
        return {"jackpy_terrain": 1, "name": self.name, "cell": self.cell, "origin": [self.x0, self.z0],
                "max_slope_deg": self.max_slope_deg, "foot_radius": self.foot_radius,
                "polygons": [p.tolist() for p in self.polygons], "heights": self.heights.tolist()}

    @classmethod
    def from_dict(cls, d: Any, file: str = "<terrain>") -> "Terrain":
        from jackpy import jsonfile as jf

        try:
            d = jf.obj(d, "")
            heights = jf.arr(jf.required(d, "heights", ""), "heights")
            rows = [[jf.num(v, f"heights[{i}][{k}]") for k, v in enumerate(jf.arr(r, f"heights[{i}]"))]
                    for i, r in enumerate(heights)]
            if len(rows) < 2 or len({len(r) for r in rows}) != 1 or len(rows[0]) < 2:
                raise jf.Invalid("heights", "expected a rectangular grid of at least 2 x 2 numbers")
            cell = jf.num(jf.required(d, "cell", ""), "cell", lo=1e-9)
            origin = jf.vector(d.get("origin", [0.0, 0.0]), "origin", 2)
            polys = [[jf.vector(p, f"polygons[{i}][{k}]", 2).tolist() for k, p in enumerate(jf.arr(poly, f"polygons[{i}]"))]
                     for i, poly in enumerate(jf.arr(d.get("polygons", []), "polygons"))]
            for i, poly in enumerate(polys):
                if len(poly) < 3:
                    raise jf.Invalid(f"polygons[{i}]", "a polygon needs at least 3 points")
            return cls(np.array(rows), cell, float(origin[0]), float(origin[1]),
                       max_slope_deg=jf.num(d.get("max_slope_deg", DEFAULT_MAX_SLOPE_DEG), "max_slope_deg", 0, 90),
                       foot_radius=jf.num(d.get("foot_radius", DEFAULT_FOOT_RADIUS), "foot_radius", 0),
                       polygons=polys, name=str(d.get("name", "terrain")))
        except jf.Invalid as exc:
            raise jf.schema_error(ParseError, file, exc) from None

    @classmethod
    def from_png(cls, path: str | os.PathLike[str], size: tuple[float, float], height_scale: float,
                 **kw: Any) -> "Terrain":
        """A greyscale heightmap: black 0 m, white ``height_scale`` m, image ``size = (x, z)`` metres
        wide; image rows run along +z, columns along +x, centred on the origin."""
        from PIL import Image

        try:
            img = np.asarray(Image.open(path).convert("F"), dtype=float)
        except OSError as exc:
            raise ParseError(f"cannot read heightmap: {exc}", str(path)) from None
        peak = 65535.0 if img.max() > 255 else 255.0
        cell = size[0] / (img.shape[1] - 1)
        return cls(img / peak * height_scale, cell, -size[0] / 2, -size[1] / 2, name=os.path.basename(str(path)), **kw)


def load(path: str | os.PathLike[str]) -> Terrain:
    """A terrain file: ``.json`` (:meth:`Terrain.to_dict` form) or ``.png`` with a sidecar-free
    default of 10 m x 10 m and 1 m height scale."""
    from jackpy import jsonfile

    p = str(path)
    if p.lower().endswith(".png"):
        return Terrain.from_png(p, (10.0, 10.0), 1.0)
    try:
        data = jsonfile.load(p)
    except OSError as exc:
        raise ParseError(f"cannot read terrain: {exc.strerror or exc}", p) from None
    return Terrain.from_dict(data, p)


def save(terrain: Terrain, path: str | os.PathLike[str]) -> None:
    """Write ``terrain`` as JSON atomically."""
    import json

    from jackpy.atomic import atomic_write_text

    atomic_write_text(path, json.dumps(terrain.to_dict()))
