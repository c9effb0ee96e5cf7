"""Compiled loops for the hot goals (numba, cached on disk): the solver columns' twist
(:class:`~jackpy.ik.goals.base.Context`), the frame goal (:class:`PositionOrientation`) and the aim
goal (:class:`Aim`), each residual, Jacobian and error in one call, and the centre of mass's
Jacobian over the columns (:meth:`Context.com`).

Same arithmetic as the numpy forms in those classes (the reference the tests compare against, to
1e-13; ``Context.compiled = False`` selects it): on the 91-variable human a goal's numpy form is some
thirty small array operations, 43 us per evaluation, the loop 6 us (call included). World frame, metres,
radians; rows and columns as in :meth:`Context.stacked_jacobian`.
"""

from __future__ import annotations

import math

import numpy as np

from jackpy.compiled import AVAILABLE, kernel  # the one numba switch (JACKPY_NO_JIT) and the kernels registry


def _twist(axes, origins, cols, sign, trans, mom, ang):  # pragma: no cover - compiled
    """Signed world axes ``a`` and moments ``o x a`` (translations: ``a`` and 0) of the DOFs
    ``cols`` into ``ang``/``mom`` (3, ncols)."""
    for c in range(cols.shape[0]):
        k = cols[c]
        s = sign[c]
        a0, a1, a2 = axes[k, 0] * s, axes[k, 1] * s, axes[k, 2] * s
        if trans[c]:
            mom[0, c], mom[1, c], mom[2, c] = a0, a1, a2
            ang[0, c], ang[1, c], ang[2, c] = 0.0, 0.0, 0.0
        else:
            o0, o1, o2 = origins[k, 0], origins[k, 1], origins[k, 2]
            mom[0, c], mom[1, c], mom[2, c] = o1 * a2 - o2 * a1, o2 * a0 - o0 * a2, o0 * a1 - o1 * a0
            ang[0, c], ang[1, c], ang[2, c] = a0, a1, a2


def _site(T, loc, w):  # pragma: no cover - compiled
    """``w = (T @ loc)[:3]`` for 4x4 ``T``, ``loc``."""
    for i in range(3):
        for j in range(4):
            s = 0.0
            for k in range(4):
                s += T[i, k] * loc[k, j]
            w[i, j] = s


def _rows(mom, ang, moved, v0, v1, v2, wt, point, J, r0w):  # pragma: no cover - compiled
    """Rows ``r0w..r0w+2`` of ``J``: ``wt (a x v)`` (plus ``wt m`` for a point), masked by ``moved``."""
    for c in range(ang.shape[1]):
        m = moved[c] * wt
        a0, a1, a2 = ang[0, c], ang[1, c], ang[2, c]
        r0, r1, r2 = a1 * v2 - a2 * v1, a2 * v0 - a0 * v2, a0 * v1 - a1 * v0
        if point:
            r0, r1, r2 = r0 + mom[0, c], r1 + mom[1, c], r2 + mom[2, c]
        J[r0w, c], J[r0w + 1, c], J[r0w + 2, c] = m * r0, m * r1, m * r2


def _angle(a0, a1, a2, b0, b1, b2):  # pragma: no cover - compiled
    """Angle between unit vectors (degrees), as :func:`~jackpy.ik.goals.base.angle_deg`."""
    d = math.sqrt((a0 - b0) ** 2 + (a1 - b1) ** 2 + (a2 - b2) ** 2)
    s = math.sqrt((a0 + b0) ** 2 + (a1 + b1) ** 2 + (a2 + b2) ** 2)
    return math.degrees(2.0 * math.atan2(d, s))


def _frame_goal(T, loc, target, wp, wx, wy, cx, cy, mom, ang, moved, f, J):  # pragma: no cover
    """:meth:`PositionOrientation.evaluate`: rows position, x axis, y axis (weights ``wp, wx, wy``)
    into ``f`` (9,) and ``J`` (9, ncols); returns (metres, degrees)."""
    w = np.empty((3, 4))
    _site(T, loc, w)
    col = (3, 0, 1)
    wts = (wp, wx, wy)
    for r in range(3):
        k, wt = col[r], wts[r]
        for i in range(3):
            f[3 * r + i] = (w[i, k] - target[i, k]) * wt
        _rows(mom, ang, moved, w[0, k], w[1, k], w[2, k], wt, r == 0, J, 3 * r)
    d0, d1, d2 = w[0, 3] - target[0, 3], w[1, 3] - target[1, 3], w[2, 3] - target[2, 3]
    metres = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
    if cx > 0 and cy > 0:
        tr = 0.0
        for i in range(3):
            for j in range(3):
                tr += target[i, j] * w[i, j]
        degrees = math.degrees(math.acos(min(max((tr - 1.0) / 2.0, -1.0), 1.0)))
    elif cx > 0:
        degrees = _angle(w[0, 0], w[1, 0], w[2, 0], target[0, 0], target[1, 0], target[2, 0])
    elif cy > 0:
        degrees = _angle(w[0, 1], w[1, 1], w[2, 1], target[0, 1], target[1, 1], target[2, 1])
    else:
        degrees = 0.0
    return metres, degrees


def _aim_goal(T, loc, axis, target, c, mom, ang, moved, f, J):  # pragma: no cover - compiled
    """:meth:`Aim.evaluate` into ``f`` (3,) and ``J`` (3, ncols); returns degrees. Within 1e-9 m of
    the target the residual and Jacobian are zero (no NaN)."""
    w = np.empty((3, 4))
    _site(T, loc, w)
    r0, r1, r2 = w[0, 3], w[1, 3], w[2, 3]
    v0 = w[0, 0] * axis[0] + w[0, 1] * axis[1] + w[0, 2] * axis[2]
    v1 = w[1, 0] * axis[0] + w[1, 1] * axis[1] + w[1, 2] * axis[2]
    v2 = w[2, 0] * axis[0] + w[2, 1] * axis[1] + w[2, 2] * axis[2]
    d0, d1, d2 = target[0] - r0, target[1] - r1, target[2] - r2
    n = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
    if n < 1e-9:
        f[:] = 0.0
        J[:, :] = 0.0
        return 0.0
    u0, u1, u2 = d0 / n, d1 / n, d2 / n
    f[0], f[1], f[2] = c * (u0 - v0), c * (u1 - v1), c * (u2 - v2)
    for k in range(ang.shape[1]):
        m = moved[k]
        a0, a1, a2 = ang[0, k], ang[1, k], ang[2, k]
        # d r/dq (point) and d v/dq (direction), masked
        jr0 = m * (a1 * r2 - a2 * r1 + mom[0, k])
        jr1 = m * (a2 * r0 - a0 * r2 + mom[1, k])
        jr2 = m * (a0 * r1 - a1 * r0 + mom[2, k])
        jv0, jv1, jv2 = m * (a1 * v2 - a2 * v1), m * (a2 * v0 - a0 * v2), m * (a0 * v1 - a1 * v0)
        uj = u0 * jr0 + u1 * jr1 + u2 * jr2
        # J_u = -(J_r - u (u . J_r)) / n
        J[0, k] = c * (-(jr0 - u0 * uj) / n - jv0)
        J[1, k] = c * (-(jr1 - u1 * uj) / n - jv1)
        J[2, k] = c * (-(jr2 - u2 * uj) / n - jv2)
    return _angle(u0, u1, u2, v0, v1, v2)


def _com_rows(moved, mc, mass_moved, total, mom, ang, J):  # pragma: no cover - compiled
    """d(centre of mass)/dq over the columns into ``J`` (3, ncols): per column
    ``(a x sum_s m_s c_s + (o x a) sum_s m_s) / M`` over the segments ``s`` it moves (``mc`` the
    mass-weighted segment centroids (nseg, 3), ``mass_moved`` the mass each column moves)."""
    nseg, nc = moved.shape
    for c in range(nc):
        s0 = s1 = s2 = 0.0
        for s in range(nseg):
            m = moved[s, c]
            if m != 0.0:
                s0 += m * mc[s, 0]
                s1 += m * mc[s, 1]
                s2 += m * mc[s, 2]
        a0, a1, a2 = ang[0, c], ang[1, c], ang[2, c]
        mm = mass_moved[c]
        J[0, c] = (a1 * s2 - a2 * s1 + mom[0, c] * mm) / total
        J[1, c] = (a2 * s0 - a0 * s2 + mom[1, c] * mm) / total
        J[2, c] = (a0 * s1 - a1 * s0 + mom[2, c] * mm) / total


if AVAILABLE:
    _site, _rows, _angle = kernel(_site, None), kernel(_rows, None), kernel(_angle, None)
    twist = kernel(_twist, "(f8[:, ::1], f8[:, ::1], i8[::1], f8[::1], b1[::1], f8[:, ::1], f8[:, ::1])")
    frame_goal = kernel(_frame_goal, "(f8[:, ::1], f8[:, ::1], f8[:, ::1], f8, f8, f8, f8, f8, f8[:, ::1], "
                        "f8[:, ::1], f8[::1], f8[::1], f8[:, ::1])")
    aim_goal = kernel(_aim_goal, "(f8[:, ::1], f8[:, ::1], f8[::1], f8[::1], f8, f8[:, ::1], f8[:, ::1], f8[::1], "
                      "f8[::1], f8[:, ::1])")
    com_rows = kernel(_com_rows, "(f8[:, ::1], f8[:, ::1], f8[::1], f8, f8[:, ::1], f8[:, ::1], f8[:, ::1])")
else:  # pragma: no cover - numba is optional
    twist = frame_goal = aim_goal = com_rows = None
