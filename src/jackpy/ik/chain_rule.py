"""The chain rule from the goals' rows over the DOF columns to the scaled variables ``z``, as one
compiled loop (numba, cached on disk), when numba is there.

:meth:`jackpy.ik.problem.Compiled._to_z` in plain loops: the free variables' columns are scaled
copies of their DOF columns; each joint group's variables are its member DOFs' columns times the
driver's Jacobian (already restricted to the used angles and scaled). The numpy form, a product per
group into slices of the output, stays the reference (equal to 1e-13 in
``tests/ik/test_ik_chain_rule.py``); on the standard human (24 rows, 5 groups) it cost ~15 us an
evaluation in numpy's per-call overhead, the loop ~2 us.
"""

from __future__ import annotations

from jackpy.compiled import kernel  # the one numba switch (JACKPY_NO_JIT) and the kernels registry


def _to_z(Jc, nf, free_scale, blocks, stack, out):  # pragma: no cover - compiled
    """``out[:, :nf] = Jc[:, :nf] * free_scale``; per block ``(lo_r, hi_r, lo_c, hi_c, at)``
    ``out[:, lo_c:hi_c] = Jc[:, lo_r:hi_r] @ stack[at:at + hi_r - lo_r, :hi_c - lo_c]``."""
    m = Jc.shape[0]
    for i in range(m):
        for c in range(nf):
            out[i, c] = Jc[i, c] * free_scale[c]
    for b in range(blocks.shape[0]):
        lo_r, hi_r, lo_c, hi_c, at = blocks[b, 0], blocks[b, 1], blocks[b, 2], blocks[b, 3], blocks[b, 4]
        for i in range(m):
            for j in range(hi_c - lo_c):
                s = 0.0
                for r in range(hi_r - lo_r):
                    s += Jc[i, lo_r + r] * stack[at + r, j]
                out[i, lo_c + j] = s


to_z = kernel(_to_z, "(f8[:, ::1], i8, f8[::1], i8[:, ::1], f8[:, ::1], f8[:, ::1])")
