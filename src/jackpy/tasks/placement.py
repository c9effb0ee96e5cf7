"""Preposition resolution ([SH6] §6.2.3; digest §5.5): ``on(X, Y)`` and ``in(X, Y)`` to a concrete
world pose of X, or a :class:`~jackpy.tasks.semantics.TaskError` saying why not.

on: Y's support surfaces (horizontal, normal up, within 10°), X's self-supporting faces (KB salience
first, then the least rotation from X's current orientation); X turned so that face points down,
yaw kept, its lowest point on the surface plane; placed at ``at`` or the surface centre; the
footprint must lie inside the surface polygon and not overlap objects already resting there (free-p).
in: Y must have a container, normally oriented (its up within 30° of world up), and X's upright
extents must fit inside the interior ("does not fit" otherwise); X then rests on the interior floor.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from jackpy.tasks.semantics import TaskError

if TYPE_CHECKING:
    from jackpy.tasks.kb import KnowledgeBase

UP = np.array([0.0, 1.0, 0.0])
COS_HORIZONTAL = np.cos(np.radians(10.0))
COS_UPRIGHT = np.cos(np.radians(30.0))


def _rotation_between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The smallest rotation taking unit vector a to unit vector b."""
    a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
    v, c = np.cross(a, b), float(a @ b)
    if c < -1 + 1e-9:
        axis = np.cross(a, [1.0, 0, 0]) if abs(a[0]) < 0.9 else np.cross(a, [0, 0, 1.0])
        axis /= np.linalg.norm(axis)
        return 2 * np.outer(axis, axis) - np.eye(3)
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k / (1 + c)


def _cross2(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _hull(points: np.ndarray) -> np.ndarray:
    """Convex hull (counter-clockwise) of 2D points."""
    pts = sorted(set(map(tuple, np.round(points, 9))))
    if len(pts) < 3:
        return np.array(pts)

    def half(ps):
        out = []
        for p in ps:
            while len(out) >= 2 and _cross2(np.subtract(out[-1], out[-2]), np.subtract(p, out[-2])) <= 0:
                out.pop()
            out.append(p)
        return out

    lo, hi = half(pts), half(pts[::-1])
    return np.array(lo[:-1] + hi[:-1])


def _overlap(a: np.ndarray, b: np.ndarray, eps: float = 1e-6) -> bool:
    """Whether two convex polygons overlap (separating axis; touching is not overlap)."""
    for poly in (a, b):
        for i in range(len(poly)):
            e = poly[(i + 1) % len(poly)] - poly[i]
            n = np.array([-e[1], e[0]])
            pa, pb = a @ n, b @ n
            if pa.max() <= pb.min() + eps or pb.max() <= pa.min() + eps:
                return False
    return True


def _inside(points: np.ndarray, poly: np.ndarray) -> bool:
    hull = _hull(poly)
    for i in range(len(hull)):
        e = hull[(i + 1) % len(hull)] - hull[i]
        if np.any(e[0] * (points[:, 1] - hull[i][1]) - e[1] * (points[:, 0] - hull[i][0]) < -1e-9):
            return False
    return True


def _xz(T: np.ndarray, pts: np.ndarray) -> np.ndarray:
    w = pts @ T[:3, :3].T + T[:3, 3]
    return w[:, [0, 2]]


def resting_pose(kb: "KnowledgeBase", obj: str, supporter: str, at: np.ndarray | None = None,
                 near: np.ndarray | None = None, margin_m: float = 0.01) -> tuple[np.ndarray, str]:
    """World 4x4 of ``obj`` resting on ``supporter`` and the name of the face it rests on: at
    ``at``, else at the point of the surface nearest ``near`` (the agent's hand) with the object
    ``margin_m`` inside the edge, else at the surface's centre."""
    env = kb.env
    X, Y = env.figures[obj], env.figures[supporter]
    sy = kb.semantics.get(supporter)
    surfaces = [s for s in (sy.support_surfaces if sy else [])]
    if not surfaces:
        raise TaskError(f"{supporter!r} has no support surface to put {obj!r} on")
    surface = None
    for s in surfaces:
        n = Y.location[:3, :3] @ s["normal"]
        if n @ UP >= COS_HORIZONTAL:
            surface = s
            break
    if surface is None:
        raise TaskError(f"no support surface of {supporter!r} is horizontal with its normal up")
    R_cur = X.location[:3, :3]
    sx = kb.semantics.get(obj)
    faces = list(sx.self_supporting_faces) if sx and sx.self_supporting_faces else []
    if not faces:
        raise TaskError(f"{obj!r} has no self-supporting face (author them or use 'suggest')")
    # KB salience first, then the least rotation from the current orientation
    best = max(faces, key=lambda f: (f["salience"], float((R_cur @ f["normal"]) @ -UP)))
    R = _rotation_between(R_cur @ best["normal"], -UP) @ R_cur
    verts = X.mesh().vertices
    rotated = verts @ R.T
    plane_pt = (Y.location @ np.append(surface["point"], 1.0))[:3]
    centre_local = 0.5 * (rotated.min(0) + rotated.max(0))
    if at is None and near is not None:
        inv = np.linalg.inv(Y.location)
        local = (inv @ np.append(near, 1.0))[:3]
        half = 0.5 * np.ptp(rotated @ Y.location[:3, :3], axis=0)[[0, 2]] + margin_m
        lo, hi = surface["polygon"].min(0) + half, surface["polygon"].max(0) - half
        xz = np.clip(local[[0, 2]], lo, np.maximum(lo, hi))
        at = (Y.location @ np.array([xz[0], surface["point"][1], xz[1], 1.0]))[:3]
    if at is None:
        poly_w = _xz(Y.location, np.column_stack([surface["polygon"][:, 0], np.full(len(surface["polygon"]), surface["point"][1]), surface["polygon"][:, 1]]))
        at = np.array([poly_w[:, 0].mean(), plane_pt[1], poly_w[:, 1].mean()])
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = [at[0] - centre_local[0], plane_pt[1] - rotated[:, 1].min(), at[2] - centre_local[2]]
    foot = _hull(_xz(T, verts))
    poly3 = np.column_stack([surface["polygon"][:, 0], np.full(len(surface["polygon"]), surface["point"][1]),
                             surface["polygon"][:, 1]])
    top = _xz(Y.location, poly3)
    if not _inside(foot, top):
        raise TaskError(f"{obj!r} does not fit on {supporter!r}'s {surface.get('name', 'surface')} there")
    for other, (parent, _) in kb.supported_by.items():
        if parent == supporter and other != obj:
            if _overlap(foot, _hull(_xz(env.figures[other].location, env.figures[other].mesh().vertices))):
                raise TaskError(f"the place on {supporter!r} is not free: {other!r} is there")
    return T, str(best.get("name", "face"))


def container_pose(kb: "KnowledgeBase", obj: str, container: str) -> np.ndarray:
    """World 4x4 of ``obj`` standing upright on the floor of ``container``'s interior."""
    env = kb.env
    X, Y = env.figures[obj], env.figures[container]
    sy = kb.semantics.get(container)
    c = sy.container if sy else None
    if c is None:
        raise TaskError(f"{container!r} is not a container")
    up_w = Y.location[:3, :3] @ c["up"]
    if up_w @ UP < COS_UPRIGHT:
        raise TaskError(f"{container!r} is not normally oriented (upside down or tipped over)")
    inner = c["max"] - c["min"]
    R_cur = X.location[:3, :3]
    ext = np.ptp(X.mesh().vertices @ R_cur.T, axis=0)
    fits = ext[1] <= inner[1] and ((ext[0] <= inner[0] and ext[2] <= inner[2]) or
                                   (ext[2] <= inner[0] and ext[0] <= inner[2]))
    if not fits:
        raise TaskError(f"{obj!r} does not fit in {container!r}: it is {ext[0]*100:.1f} × {ext[1]*100:.1f} × "
                        f"{ext[2]*100:.1f} cm, the interior {inner[0]*100:.1f} × {inner[1]*100:.1f} × {inner[2]*100:.1f} cm")
    floor = (Y.location @ np.append(0.5 * (c["min"] + c["max"]) * [1, 0, 1] + [0, c["min"][1], 0], 1.0))[:3]
    rotated = X.mesh().vertices @ R_cur.T
    centre = 0.5 * (rotated.min(0) + rotated.max(0))
    T = np.eye(4)
    T[:3, :3] = R_cur
    T[:3, 3] = [floor[0] - centre[0], floor[1] - rotated[:, 1].min(), floor[2] - centre[2]]
    return T
