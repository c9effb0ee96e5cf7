"""Triangle meshes as plain arrays, and the primitive shapes the renderer instances.

A :class:`Mesh` is in its own local frame (metres). Triangles are counter-clockwise seen from
outside (the glTF and trimesh convention); the renderer relies on it only to draw the back faces
of a transparent volume before its front faces.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Mesh:
    """Vertices (N, 3) float32 in m, unit normals (N, 3) float32, triangles (M, 3) uint32, and
    optional per-vertex colours (N, 3) float32 in [0, 1] that multiply the item's colour."""

    vertices: np.ndarray
    normals: np.ndarray
    indices: np.ndarray
    colors: np.ndarray | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "vertices", np.ascontiguousarray(self.vertices, np.float32).reshape(-1, 3))
        object.__setattr__(self, "normals", np.ascontiguousarray(self.normals, np.float32).reshape(-1, 3))
        object.__setattr__(self, "indices", np.ascontiguousarray(self.indices, np.uint32).reshape(-1, 3))
        if self.normals.shape != self.vertices.shape:
            raise ValueError(f"normals {self.normals.shape} do not match vertices {self.vertices.shape}")
        if self.indices.size and int(self.indices.max()) >= len(self.vertices):
            raise ValueError("triangle index out of range")
        if self.colors is not None:
            object.__setattr__(self, "colors", np.ascontiguousarray(self.colors, np.float32).reshape(-1, 3))
            if self.colors.shape != self.vertices.shape:
                raise ValueError(f"colours {self.colors.shape} do not match vertices {self.vertices.shape}")

    @classmethod
    def from_triangles(cls, vertices: np.ndarray, indices: np.ndarray, crease_deg: float = 60.0) -> Mesh:
        """A mesh with area-weighted normals, smooth except across edges sharper than ``crease_deg``.

        A vertex shared by faces that meet at a crease (a cap on a limb, a box edge) is split so each
        side keeps its own normal; without this, caps tilt the normals of the ring they close and
        shading shows a stripe at every seam.
        """
        v, n, f = crease_normals(vertices, indices, crease_deg)
        return cls(v, n, f)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Axis-aligned bounding box (min, max) in the local frame, m."""
        return self.vertices.min(axis=0).astype(float), self.vertices.max(axis=0).astype(float)


def vertex_normals(vertices: np.ndarray, indices: np.ndarray) -> np.ndarray:
    """Area-weighted unit vertex normals (N, 3) of a triangle mesh."""
    v = np.asarray(vertices, float).reshape(-1, 3)
    f = np.asarray(indices, np.int64).reshape(-1, 3)
    face_n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n = np.zeros_like(v)
    for k in range(3):
        np.add.at(n, f[:, k], face_n)
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return n / np.where(length > 0.0, length, 1.0)


def crease_normals(vertices: np.ndarray, indices: np.ndarray,
                   crease_deg: float = 60.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split vertices along creases; returns (vertices, unit normals, triangles).

    Each triangle corner's normal is the area-weighted sum of the normals of the faces around its
    vertex that lie within ``crease_deg`` of the corner's own face; corners of one vertex with the
    same normal share one output vertex.
    """
    v = np.asarray(vertices, float).reshape(-1, 3)
    f = np.asarray(indices, np.int64).reshape(-1, 3)
    if len(f) == 0:
        return v, np.zeros_like(v), f
    area_n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    length = np.linalg.norm(area_n, axis=1, keepdims=True)
    unit_n = area_n / np.where(length > 0.0, length, 1.0)
    corner_vertex = f.reshape(-1)
    corner_face = np.repeat(np.arange(len(f)), 3)
    order = np.argsort(corner_vertex, kind="stable")
    sorted_vertex = corner_vertex[order]
    starts = np.flatnonzero(np.r_[True, sorted_vertex[1:] != sorted_vertex[:-1]])
    sizes = np.diff(np.r_[starts, len(order)])
    group = np.repeat(np.arange(len(starts)), sizes)
    first = starts[group]
    cos_crease = np.cos(np.radians(crease_deg))
    own = unit_n[corner_face[order]]
    acc = np.zeros((len(order), 3))
    for j in range(int(sizes.max())):
        valid = j < sizes[group]
        partner = corner_face[order[np.minimum(first + j, len(order) - 1)]]
        keep = valid & (np.einsum("ij,ij->i", own, unit_n[partner]) >= cos_crease)
        acc[keep] += area_n[partner[keep]]
    norm = np.linalg.norm(acc, axis=1, keepdims=True)
    acc = np.where(norm > 0.0, acc / np.where(norm > 0.0, norm, 1.0), own)
    corner_normal = np.empty_like(acc)
    corner_normal[order] = acc
    key = np.column_stack([corner_vertex, np.round(corner_normal * 1e4).astype(np.int64)])
    _, first_corner, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    return v[corner_vertex[first_corner]], corner_normal[first_corner], inverse.reshape(-1, 3)


def _orient_outward(vertices: np.ndarray, normals: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Flip the triangles whose winding disagrees with their vertex normals."""
    v0, v1, v2 = (vertices[faces[:, k]] for k in range(3))
    geometric = np.cross(v1 - v0, v2 - v0)
    flip = np.einsum("ij,ij->i", geometric, normals[faces].sum(axis=1)) < 0.0
    faces = faces.copy()
    faces[flip] = faces[flip][:, ::-1]
    return faces


def box(size: tuple[float, float, float] = (1.0, 1.0, 1.0)) -> Mesh:
    """Axis-aligned box centred on the origin with flat faces; ``size`` in m."""
    half = 0.5 * np.asarray(size, float)
    verts, norms, faces = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = np.zeros(3)
            n[axis] = sign
            u, w = np.eye(3)[(axis + 1) % 3], np.eye(3)[(axis + 2) % 3]
            base = len(verts)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                verts.append((n + a * u + b * w) * half)
                norms.append(n)
            faces += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    v, n = np.array(verts), np.array(norms)
    return Mesh(v, n, _orient_outward(v, n, np.array(faces)))


def uv_sphere(radius: float = 1.0, rings: int = 12, sectors: int = 20) -> Mesh:
    """Sphere of ``radius`` m centred on the origin, poles on the y axis."""
    theta = np.linspace(0.0, np.pi, rings + 1)[:, None]
    phi = np.linspace(0.0, 2.0 * np.pi, sectors + 1)[None, :]
    n = np.stack([np.sin(theta) * np.sin(phi), np.cos(theta) * np.ones_like(phi),
                  np.sin(theta) * np.cos(phi)], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(rings), np.arange(sectors), indexing="ij")
    a = (i * (sectors + 1) + j).ravel()
    b, c, d = a + sectors + 1, a + 1, a + sectors + 2
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([c, b, d], 1)])
    return Mesh(n * radius, n, _orient_outward(n * radius, n, faces))


def lathe(profile: list[tuple[float, float]], sectors: int = 20) -> Mesh:
    """Surface of revolution about the y axis of a polyline of (radius, y) points, in m.

    Each profile segment gets its own ring of vertices, so corners stay sharp while the surface
    is smooth around the axis.
    """
    phi = np.linspace(0.0, 2.0 * np.pi, sectors + 1)
    ring = np.stack([np.sin(phi), np.zeros_like(phi), np.cos(phi)], axis=1)
    verts, norms, faces = [], [], []
    for (r0, y0), (r1, y1) in zip(profile[:-1], profile[1:]):
        nr, ny = y1 - y0, -(r1 - r0)
        length = np.hypot(nr, ny)
        normal = ring * (nr / length) + np.array([0.0, ny / length, 0.0])
        base = sum(len(v) for v in verts)
        verts += [ring * r0 + [0.0, y0, 0.0], ring * r1 + [0.0, y1, 0.0]]
        norms += [normal, normal]
        j = np.arange(sectors)
        a, b = base + j, base + sectors + 1 + j
        faces.append(np.concatenate([np.stack([a, b, a + 1], 1), np.stack([a + 1, b, b + 1], 1)]))
    v, n = np.concatenate(verts), np.concatenate(norms)
    return Mesh(v, n, _orient_outward(v, n, np.concatenate(faces)))


def cylinder(radius: float = 1.0, height: float = 1.0, sectors: int = 20) -> Mesh:
    """Capped cylinder along +y from y = 0 to y = ``height``; sizes in m."""
    return lathe([(0.0, 0.0), (radius, 0.0), (radius, height), (0.0, height)], sectors)


def cone(radius: float = 1.0, height: float = 1.0, sectors: int = 20) -> Mesh:
    """Cone along +y, base disc at y = 0, apex at y = ``height``; sizes in m."""
    return lathe([(0.0, 0.0), (radius, 0.0), (0.0, height)], sectors)


def arrow(length: float = 1.0, shaft_radius: float = 0.03, head_radius: float = 0.08,
          head_length: float = 0.25, sectors: int = 16) -> Mesh:
    """Arrow along +y from the origin to its tip at y = ``length``; sizes in m."""
    neck = length - head_length
    return lathe([(0.0, 0.0), (shaft_radius, 0.0), (shaft_radius, neck), (head_radius, neck),
                  (0.0, length)], sectors)
