"""The forward pass as one compiled loop over the segments (numba, cached on disk), when numba is there.

Same arithmetic as :meth:`jackpy.peabody.kinematics.Kinematics.forward` (the numpy reference the tests
compare against), written as a loop in breadth-first order: ``M = W(parent) @ P(s)``, then per DOF of
the segment's joint in traversal order its world axis and point (the frame before its transform
going down, after it going up) and ``M = M @ S``, finally ``W(s) = M @ Q(s)``. numpy's per-call
overhead dominates the batched form on figures of ~100 segments; the loop has none.

``JACKPY_NO_JIT=1`` in the environment turns the kernel off (the numpy path is then used); the
switch and the kernels' registry are :mod:`jackpy.compiled`.
"""

from __future__ import annotations

import numpy as np

from jackpy.compiled import AVAILABLE, kernel  # noqa: F401 - AVAILABLE: whether forward_kernel is compiled


def _forward(q, location, root_inv, parent, P, Q, seg_start, seg_count, slot_dof, slot_rot, slot_axis,
             slot_up, dof_axis, W, axes, origins):  # pragma: no cover - compiled
    nseg = parent.shape[0]
    M = np.empty((4, 4))
    T = np.empty((4, 4))
    S = np.empty((4, 4))
    for i in range(4):
        for j in range(4):
            acc = 0.0
            for k in range(4):
                acc += location[i, k] * root_inv[k, j]
            W[0, i, j] = acc
    for s in range(1, nseg):
        p = parent[s]
        for i in range(4):
            for j in range(4):
                acc = 0.0
                for k in range(4):
                    acc += W[p, i, k] * P[s, k, j]
                M[i, j] = acc
        for t in range(seg_start[s], seg_start[s] + seg_count[s]):
            d = slot_dof[t]
            ax, ay, az = slot_axis[t, 0], slot_axis[t, 1], slot_axis[t, 2]
            v = q[d]
            for i in range(4):
                for j in range(4):
                    S[i, j] = 1.0 if i == j else 0.0
            if slot_rot[t]:
                c, sn = np.cos(v), np.sin(v)
                C = 1.0 - c
                S[0, 0] = c + ax * ax * C
                S[0, 1] = ax * ay * C - az * sn
                S[0, 2] = ax * az * C + ay * sn
                S[1, 0] = ay * ax * C + az * sn
                S[1, 1] = c + ay * ay * C
                S[1, 2] = ay * az * C - ax * sn
                S[2, 0] = az * ax * C - ay * sn
                S[2, 1] = az * ay * C + ax * sn
                S[2, 2] = c + az * az * C
            else:
                S[0, 3] = ax * v
                S[1, 3] = ay * v
                S[2, 3] = az * v
            if not slot_up[t]:  # going down the DOF's frame is the one before its transform
                for i in range(3):
                    axes[d, i] = M[i, 0] * dof_axis[d, 0] + M[i, 1] * dof_axis[d, 1] + M[i, 2] * dof_axis[d, 2]
                    origins[d, i] = M[i, 3]
            for i in range(4):
                for j in range(4):
                    acc = 0.0
                    for k in range(4):
                        acc += M[i, k] * S[k, j]
                    T[i, j] = acc
            for i in range(4):
                for j in range(4):
                    M[i, j] = T[i, j]
            if slot_up[t]:
                for i in range(3):
                    axes[d, i] = M[i, 0] * dof_axis[d, 0] + M[i, 1] * dof_axis[d, 1] + M[i, 2] * dof_axis[d, 2]
                    origins[d, i] = M[i, 3]
        for i in range(4):
            for j in range(4):
                acc = 0.0
                for k in range(4):
                    acc += M[i, k] * Q[s, k, j]
                W[s, i, j] = acc


forward_kernel = kernel(_forward, "(f8[::1], f8[:, ::1], f8[:, ::1], i8[::1], f8[:, :, ::1], f8[:, :, ::1], i8[::1], i8[::1], i8[::1], b1[::1], f8[:, ::1], b1[::1], f8[:, ::1], f8[:, :, ::1], f8[:, ::1], f8[:, ::1])")
