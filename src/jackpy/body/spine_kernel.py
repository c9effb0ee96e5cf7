"""Monheit's spine distribution with its derivative as one compiled loop (numba, cached on disk).

The same piecewise model and the same derivative of the active piece as
:func:`jackpy.body.spine.distribute_with_derivative` (the numpy reference the tests compare against),
written as plain loops over the vertebral joints and run for all three torso axes in one call. The
IK evaluates the spine driver at new angles on every forward pass; the numpy form spends ~0.1 ms of
per-call overhead per axis on 18-element arrays, the loop none (a few microseconds for all three).

One deliberate difference, at the exact ends of a torso angle's range only: there the reference's
derivative depends on rounding (it may clamp joints by an ulp, or take the outer side of the
participation clamp ``P = 1``, and give zero), which would pin an IK variable that a bounded step
put on its bound; the kernel gives the derivative from inside the range (tested).

``JACKPY_NO_JIT=1`` (or no numba) leaves :data:`AVAILABLE` false and the driver uses the reference.
"""

from __future__ import annotations

import math

import numpy as np

from jackpy.compiled import AVAILABLE, kernel  # the one numba switch (JACKPY_NO_JIT) and the kernels registry
#: a joint overflows its goal only by more than rounding (radians): at the range's ends every joint
#: lands on its limit and the derivative stays the inner one-sided derivative (the reference's strict
#: test can clamp joints by an ulp there and give zero, which would pin an IK variable at its bound)
OVER_TOL = 1e-13


def _weights(n, p, initiator, spread, resistor, resistance, w, dw):  # pragma: no cover - compiled
    """``p_i r_i`` (into ``w``) and its derivative in ``P`` (into ``dw``); ``resistor < 0``: none."""
    side = 1.0
    if resistor >= 0 and resistor != initiator:
        side = 1.0 if resistor > initiator else -1.0
    for i in range(n):
        e = math.exp(-abs(i - initiator) / spread)
        part, dpart = p + (1.0 - p) * e, 1.0 - e
        if resistor < 0 or resistance == 0.0:
            w[i], dw[i] = part, dpart
        else:
            s = 1.0 if (i - resistor) * side >= 0 else math.exp(-abs(i - resistor) / spread)
            r = 1.0 - resistance * (1.0 - p) * s
            w[i], dw[i] = part * r, dpart * r + part * resistance * s


def _distribute(cur, rest, lower, upper, target, bottom, top, initiator, spread, resistor, resistance,
                out, d):  # pragma: no cover - compiled
    """One axis: joint angles whose sum is ``target`` into ``out`` and d(out)/d(target) into ``d``."""
    n = cur.shape[0]
    lo, hi, rest_a = np.empty(n), np.empty(n), np.empty(n)
    active = np.empty(n, dtype=np.bool_)
    lo_sum = hi_sum = rest_sum = cur_sum = 0.0
    for i in range(n):
        act = bottom <= i <= top
        active[i] = act
        lo[i] = lower[i] if act else cur[i]
        hi[i] = upper[i] if act else cur[i]
        rest_a[i] = rest[i] if act else cur[i]
        lo_sum += lo[i]
        hi_sum += hi[i]
        rest_sum += rest_a[i]
        cur_sum += cur[i]
        out[i] = cur[i]
        d[i] = 0.0
    # inclusive to rounding: at a bound (where a bounded IK step puts it) the derivative is the inner one
    dtarget = 1.0 if lo_sum - 1e-12 <= target <= hi_sum + 1e-12 else 0.0
    target = min(max(target, lo_sum), hi_sum)
    m = target - cur_sum
    rest_gap = rest_sum - cur_sum
    w, dw, room = np.empty(n), np.empty(n), np.empty(n)
    if abs(m) < 1e-15:
        if dtarget == 0.0:
            return
        count = 0
        for sgn in (1.0, -1.0):  # at the kink: mean of the one-sided derivatives
            use_rest = abs(rest_gap) > 1e-15 and rest_gap * sgn > 0
            room_sum = 0.0
            for i in range(n):
                goal = rest_a[i] if use_rest else (hi[i] if sgn > 0 else lo[i])
                room[i] = goal - cur[i]
                room_sum += room[i]
            if abs(room_sum) < 1e-15:
                continue
            _weights(n, 0.0, initiator, spread, resistor, resistance, w, dw)
            ws = 0.0
            for i in range(n):
                w[i] = w[i] * room[i] if active[i] and abs(room[i]) > 1e-15 else 0.0
                ws += w[i]
            if abs(ws) < 1e-300:
                ws = 0.0
                for i in range(n):
                    w[i] = room[i] if active[i] and abs(room[i]) > 1e-15 else 0.0
                    ws += w[i]
            for i in range(n):
                d[i] += w[i] / ws
            count += 1
        if count:
            for i in range(n):
                d[i] /= count
        return
    unbending = rest_gap * m > 0 and abs(m) <= abs(rest_gap)
    goal = np.empty(n)
    room_sum = 0.0
    for i in range(n):
        goal[i] = rest_a[i] if unbending else (hi[i] if m > 0 else lo[i])
        room[i] = goal[i] - cur[i]
        room_sum += room[i]
    if abs(room_sum) > 1e-15:
        p_raw = m / room_sum
        p = min(max(p_raw, 0.0), 1.0)
        dp = dtarget / room_sum if 0.0 < p_raw <= 1.0 + 1e-12 else 0.0  # the inner side at P = 1
    else:
        p, dp = 1.0, 0.0
    _weights(n, p, initiator, spread, resistor, resistance, w, dw)
    free = np.empty(n, dtype=np.bool_)
    for i in range(n):
        w[i] *= room[i]
        dw[i] *= room[i] * dp
        free[i] = active[i] and abs(room[i]) > 1e-15
    dm = dtarget  # d(remaining M)/d(target): clamped joints take fixed amounts
    wf, dwf = np.empty(n), np.empty(n)
    for _ in range(n + 1):  # water-filling: clamp overflowing joints, give their excess to the rest
        nfree = 0
        for i in range(n):
            nfree += free[i]
        if abs(m) < 1e-15 or nfree == 0:
            break
        sgn_m = 1.0 if m > 0 else -1.0
        s = ds = 0.0
        for i in range(n):
            wf[i] = w[i] if free[i] else 0.0
            dwf[i] = dw[i] if free[i] else 0.0
            s += wf[i]
            ds += dwf[i]
        if abs(s) < 1e-300:
            s = ds = 0.0
            for i in range(n):
                wf[i] = goal[i] - out[i] if free[i] else 0.0
                dwf[i] = 0.0
                s += wf[i]
        any_over = False
        for i in range(n):
            if free[i] and (out[i] + m * wf[i] / s - goal[i]) * sgn_m > OVER_TOL:
                any_over = True
                break
        if not any_over:
            for i in range(n):
                out[i] += m * wf[i] / s
                d[i] += dm * wf[i] / s + m * (dwf[i] * s - wf[i] * ds) / (s * s)
            break
        taken = 0.0
        for i in range(n):
            if free[i] and (out[i] + m * wf[i] / s - goal[i]) * sgn_m > OVER_TOL:
                taken += goal[i] - out[i]
                out[i] = goal[i]
                free[i] = False
        m -= taken


def _spine(theta, rest, lower, upper, dof_index, bottom, top, initiator, spread, resistor, resistance,
           out, jac):  # pragma: no cover - compiled
    """All three torso axes: ``out`` (n, 3) displacements, ``jac`` (n, 3, 3) their derivative."""
    n = rest.shape[0]
    col, der = np.empty(n), np.empty(n)
    for c in range(theta.shape[0]):
        k = dof_index[c]
        _distribute(rest[:, k].copy(), rest[:, k].copy(), lower[:, k].copy(), upper[:, k].copy(), theta[c],
                    bottom, top, initiator, spread, resistor, resistance, col, der)
        for i in range(n):
            out[i, k] = col[i]
            jac[i, k, c] = der[i]


if AVAILABLE:
    _weights = kernel(_weights, None)
    _distribute = kernel(_distribute, None)
    _spine = kernel(_spine, "(f8[::1], f8[:, ::1], f8[:, ::1], f8[:, ::1], i8[::1], i8, i8, i8, f8, i8, f8, "
                    "f8[:, ::1], f8[:, :, ::1])")


def spine_distribution(theta: np.ndarray, rest: np.ndarray, lower: np.ndarray, upper: np.ndarray,
                       dof_index: np.ndarray, bottom: int, top: int, initiator: int, spread: float,
                       resistor: int | None, resistance: float) -> tuple[np.ndarray, np.ndarray]:
    """Displacements (n, 3) and d/d(theta) (n, 3, 3) of the vertebral joints for torso angles
    ``theta`` (3,) radians, evaluated from ``rest``: axis ``c`` of ``theta`` drives DOF
    ``dof_index[c]`` of every joint; ``lower``/``upper``/``rest`` are (n, 3) radians."""
    out = np.array(rest, dtype=float)
    jac = np.zeros(out.shape + (3,))
    _spine(np.ascontiguousarray(theta, dtype=float), np.ascontiguousarray(rest, dtype=float),
           np.ascontiguousarray(lower, dtype=float), np.ascontiguousarray(upper, dtype=float),
           np.ascontiguousarray(dof_index, dtype=np.int64), int(bottom), int(top), int(initiator),
           float(spread), -1 if resistor is None else int(resistor), float(resistance), out, jac)
    return out, jac
