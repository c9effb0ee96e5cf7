"""Transform primitives of the Peabody text format, their units, and the row-vector product rule.

A primitive is ``(name, args)`` with ``args`` in *file* units (centimetres, degrees):

=========== ===================== =============================================================
name        args                  column-vector matrix (metres, radians inside)
=========== ===================== =============================================================
``trans``   x, y, z (cm)          translation by (x, y, z) / 100
``scale``   sx, sy, sz            ``diag(sx, sy, sz, 1)``
``rotx``    angle (deg)           right-handed rotation about x (``roty``, ``rotz`` likewise)
``rot``     ax, ay, az, angle     rotation about the axis (ax, ay, az) by angle degrees
``matrix``  16 numbers            the 4x4 in Peabody's *row-vector* form, row-major, translation
                                  (cm) in the last row; its transpose is the column form
=========== ===================== =============================================================

Product rule. Peabody multiplies row vectors (``p' = p A B``), so the file's ``A * B * C`` is
applied left to right: ``A`` first, then ``B`` about the fixed frame, then ``C``. In our column
convention that is ``C @ B @ A`` (:func:`compose`). Example: ``trans(10cm,0cm,0cm) * rotz(90)``
translates to (0.1, 0, 0) and then rotates that point about the z axis to (0, 0.1, 0).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial.transform import Rotation

from jackpy.peabody.lexer import MAX_MAGNITUDE
from jackpy.peabody.transforms import close, rotation, scaling, translation

Prim = tuple[str, tuple[float, ...]]

#: length units and their size in centimetres (file lengths default to cm)
LENGTH_UNITS = {"cm": 1.0, "mm": 0.1, "m": 100.0, "in": 2.54}
#: angle units and their size in degrees (file angles default to degrees)
ANGLE_UNITS = {"deg": 1.0, "rad": 180.0 / math.pi}
CM = 0.01            # metres per centimetre
DEG = math.pi / 180  # radians per degree
#: argument kinds of each primitive: "L" length, "A" angle, "N" plain number
PRIM_ARGS = {"trans": "LLL", "scale": "NNN", "rotx": "A", "roty": "A", "rotz": "A",
             "rot": "NNNA", "matrix": "N" * 16}
RIGID_PRIMS = ("trans", "rotx", "roty", "rotz", "rot", "matrix")
#: largest entry (5e11) of a composed transform's 3x3 part, and of its translation in cm: the writer's
#: ``scale``, ``rot``, ``trans`` or ``matrix`` form of it then stays within MAX_MAGNITUDE
MAX_LINEAR = MAX_MAGNITUDE / 2
_BOUNDS = np.full((4, 4), MAX_LINEAR)
_BOUNDS[:3, 3] *= CM


def prim_matrix(prim: Prim) -> np.ndarray:
    """The 4x4 column-vector matrix (metres, radians) of one primitive in file units."""
    name, a = prim
    if name == "trans":
        return translation(a[0] * CM, a[1] * CM, a[2] * CM)
    if name == "scale":
        return scaling(*a)
    if name in ("rotx", "roty", "rotz"):
        return rotation(name[-1], a[0] * DEG)
    if name == "rot":
        return rotation(np.array(a[:3]), a[3] * DEG)
    if name == "matrix":
        m = np.array(a, dtype=float).reshape(4, 4).T.copy()
        m[:3, 3] *= CM
        return m
    raise ValueError(f"unknown transform primitive {name!r}")


def _fast_matrix(prim: Prim) -> np.ndarray:
    """:func:`prim_matrix` built in one array construction (the reader calls it per site)."""
    name, a = prim
    if name == "trans":
        return np.array([[1.0, 0, 0, a[0] * CM], [0, 1.0, 0, a[1] * CM], [0, 0, 1.0, a[2] * CM], [0, 0, 0, 1.0]])
    if name in _ROTATIONS:
        r0, r1, r2 = _rotation_rows(prim)
        return np.array([[*r0, 0.0], [*r1, 0.0], [*r2, 0.0], [0.0, 0.0, 0.0, 1.0]])
    return prim_matrix(prim)


def _rotation_rows(prim: Prim) -> tuple[tuple[float, float, float], ...]:
    """The 3x3 rotation of a ``rotx``/``roty``/``rotz``/``rot`` primitive as rows of floats."""
    name, a = prim
    if name == "rot":
        big = max(abs(a[0]), abs(a[1]), abs(a[2]))
        x, y, z = a[0] / big, a[1] / big, a[2] / big
        n = math.sqrt(x * x + y * y + z * z)
        x, y, z = x / n, y / n, z / n
        c, s = math.cos(a[3] * DEG), math.sin(a[3] * DEG)
        C = 1.0 - c
        return ((c + x * x * C, x * y * C - z * s, x * z * C + y * s),
                (y * x * C + z * s, c + y * y * C, y * z * C - x * s),
                (z * x * C - y * s, z * y * C + x * s, c + z * z * C))
    c, s = math.cos(a[0] * DEG), math.sin(a[0] * DEG)
    if name == "rotx":
        return ((1.0, 0.0, 0.0), (0.0, c, -s), (0.0, s, c))
    if name == "roty":
        return ((c, 0.0, s), (0.0, 1.0, 0.0), (-s, 0.0, c))
    return ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0))


_ROTATIONS = frozenset(["rotx", "roty", "rotz", "rot"])


def _is_simple(prims: list[Prim]) -> bool:
    """The writer's (and most files') form ``rot... * trans(...)``, or a lone ``trans(...)``."""
    n = len(prims)
    return 0 < n <= 2 and prims[-1][0] == "trans" and (n == 1 or prims[0][0] in _ROTATIONS)


def _simple_entries(prims: list[Prim]) -> list[float]:
    """The 16 entries, row by row, of the product of :func:`_is_simple` primitives."""
    return rt_entries(prims[0] if len(prims) == 2 else None, prims[-1][1])


def rt_entries(rotation: Prim | None, t: tuple[float, ...]) -> list[float]:
    """The 16 entries, row by row, of ``rotation * trans(t)`` (``t`` in cm; no rotation: none)."""
    r0, r1, r2 = _rotation_rows(rotation) if rotation is not None else _IDENTITY_ROWS
    return [*r0, t[0] * CM, *r1, t[1] * CM, *r2, t[2] * CM, 0.0, 0.0, 0.0, 1.0]


_IDENTITY_ROWS = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def compose(prims: list[Prim]) -> np.ndarray:
    """Column matrix of the file product ``p1 * p2 * ... * pn``, i.e. ``pn @ ... @ p2 @ p1``."""
    if not prims:
        return np.eye(4)
    if _is_simple(prims):  # (one array, no products)
        return np.array(_simple_entries(prims)).reshape(4, 4)
    out = _fast_matrix(prims[0])
    for p in prims[1:]:
        out = _fast_matrix(p) @ out
    return out


def bounded_compose(prims: list[Prim]) -> np.ndarray | None:
    """:func:`compose` of ``prims``, or None when an entry of the product is beyond
    :data:`MAX_LINEAR` (its translation: MAX_LINEAR cm)."""
    m = compose(prims)
    if _is_simple(prims):
        ok = max(abs(v) for v in prims[-1][1]) <= MAX_LINEAR  # (rotation entries are at most 1)
    else:
        ok = bool((np.abs(m) <= _BOUNDS).all())
    return m if ok else None


def bounded_entries(prims: list[Prim]) -> list[float] | None:
    """The 16 entries, row by row, of :func:`bounded_compose` (None likewise), for building many
    matrices in one array."""
    if _is_simple(prims):
        t = prims[-1][1]
        return _simple_entries(prims) if max(abs(t[0]), abs(t[1]), abs(t[2])) <= MAX_LINEAR else None
    m = bounded_compose(prims)
    return None if m is None else m.reshape(-1).tolist()


def is_rigid_prim(prim: Prim) -> bool:
    """True for a rotation or translation primitive, or a ``matrix`` that is one (to 1e-6)."""
    if prim[0] not in RIGID_PRIMS:
        return False
    if prim[0] != "matrix":
        return True
    m = compose([prim])
    r = m[:3, :3]
    return bool(np.all(np.abs(m[3] - (0, 0, 0, 1)) <= 1e-6) and np.all(np.abs(r.T @ r - np.eye(3)) <= 1e-6)
                and np.linalg.det(r) > 0)


def _rotvec(r: np.ndarray) -> np.ndarray:
    """Rotation vector (radians) of the rotation matrix ``r``: closed form (the axis from the
    skew part, the angle by ``atan2``) away from a half turn, where it is well conditioned; scipy's
    quaternion route near one."""
    w = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    sin2 = math.sqrt(float(w @ w))  # 2 sin(angle)
    angle = math.atan2(sin2, float(r[0, 0] + r[1, 1] + r[2, 2]) - 1.0)
    if angle > 3.0:
        return Rotation.from_matrix(r).as_rotvec()
    if sin2 == 0.0:
        return np.zeros(3)
    return w * (angle / sin2)


def _rotation_prims(r: np.ndarray) -> list[Prim]:
    rotvec = _rotvec(r)
    angle = float(np.linalg.norm(rotvec))
    if angle < 1e-15:
        return []
    axis = rotvec / angle
    deg = math.degrees(angle)
    for k, name in enumerate(("rotx", "roty", "rotz")):
        if abs(abs(axis[k]) - 1.0) < 1e-13:
            return [(name, (math.copysign(deg, axis[k]),))]
    return [("rot", (float(axis[0]), float(axis[1]), float(axis[2]), deg))]


def _matrix_prim(m: np.ndarray) -> Prim:
    row = m.copy()
    row[:3, 3] /= CM
    return ("matrix", tuple(float(v) for v in row.T.reshape(-1)))


_LAST_ROW = np.array([0.0, 0.0, 0.0, 1.0])
_EYE3 = np.eye(3)


def decompose(m: np.ndarray, tol: float = 1e-10) -> list[Prim]:
    """File primitives that :func:`compose` back to ``m`` within ``tol`` (metres).

    Rigid: ``rot... * trans(...)``; rotation-scale: ``scale(...) * rot... * trans(...)``; anything
    else a ``matrix(...)``. An identity gives ``[trans(0,0,0)]``.
    """
    m = np.asarray(m, dtype=float)
    prims: list[Prim] | None = None
    if close(m[3], _LAST_ROW, 1e-15):
        lin = m[:3, :3]
        s = np.linalg.norm(lin, axis=0)
        if np.all(s > 1e-12):
            r = lin / s
            if np.linalg.det(r) < 0:
                s[0], r[:, 0] = -s[0], -r[:, 0]
            if close(r.T @ r, _EYE3, 1e-12):
                prims = []
                if not close(s, 1.0, 1e-15):
                    prims.append(("scale", tuple(float(v) for v in s)))
                prims += _rotation_prims(r)
                t = m[:3, 3] / CM
                if np.any(t != 0.0) or not prims:
                    prims.append(("trans", tuple(float(v) for v in t)))
                if not close(compose(prims), m, tol):
                    prims = None
    return prims if prims is not None else [_matrix_prim(m)]


def fmt(v: float) -> str:
    """A float as the shortest text that reads back as the same float (``repr``), no ``-0``;
    a non-finite value raises ValueError (the reader never accepts one)."""
    v = float(v)
    if not math.isfinite(v):
        raise ValueError(f"cannot write the non-finite value {v}")
    if v == 0.0:
        return "0"
    s = repr(v)
    return s[:-2] if s.endswith(".0") else s


def prims_text(prims: list[Prim]) -> str:
    """Peabody text of a primitive product, with units (``rotx(90) * trans(1cm,0cm,2cm)``)."""
    parts = []
    for name, args in prims:
        kinds = PRIM_ARGS[name]
        parts.append(f"{name}(" + ",".join(fmt(a) + ("cm" if k == "L" else "")
                                          for a, k in zip(args, kinds)) + ")")
    return " * ".join(parts)
