"""The bounded Gauss-Newton subproblem: a convex QP over the box and the linear rows.

``min_d  c.d + d.H d / 2   subject to   l <= d <= u,  A d <= r``, with ``H = J^T J + lambda I``
(``J`` m x n, ``lambda > 0``), ``l <= 0 <= u`` and ``r >= 0`` (the current point is feasible).
Solves with ``H`` restricted to the free variables go through Woodbury's identity, an m x m
Cholesky factor (m residuals, usually far fewer than n variables).

Solved by projected Newton iterations (Bertsekas 1982, "Projected Newton methods for optimization
problems with simple constraints", SIAM J. Control Optim. 20(2):221-246; Nocedal & Wright 2006,
§16.7 gradient projection): each iteration splits the variables into those held at a bound (at the
bound with the gradient pushing outward) and the free ones, takes the Newton step of the free ones
(with the working rows held as equalities, Rosen's projection), and searches along its projection
onto the box. One projection can bind *and* free many bounds at once, and all of this happens on
the quadratic model: no forward kinematics is spent on finding the active set. Rows are few (joint
groups' cuts) and are handled as an active set: a step is cut at the first inactive row it meets,
that row joins the working set, and a row whose multiplier turns negative leaves it.
"""

from __future__ import annotations

import numpy as np

from jackpy.compiled import AVAILABLE, kernel

try:  # numpy.linalg.inv's own kernel, without its per-call checks (the matrix is positive definite)
    from numpy.linalg import _umath_linalg

    def _inv(M: np.ndarray) -> np.ndarray:
        return _umath_linalg.inv(M, signature="d->d")
except (ImportError, AttributeError):  # pragma: no cover
    _inv = np.linalg.inv

#: a variable this close to a bound (scaled units) counts as at the bound
AT_BOUND = 1e-12
#: Armijo constant of the projected search on the model
SIGMA = 1e-4
#: a row may exceed its bound by this much (rounding), as the solver's feasibility test allows
ROW_TOL = 1e-13


class _Hessian:
    """``H = J^T J + lambda I``: products, and solves on a subset of the variables (Woodbury)."""

    def __init__(self, J: np.ndarray, lam: float) -> None:
        self.J, self.lam = J, lam

    def dot(self, d: np.ndarray) -> np.ndarray:
        return self.J.T @ (self.J @ d) + self.lam * d

    def factor(self, free: np.ndarray) -> None:
        """Prepare solves with ``H[free][:, free]``: ``(lambda I + J_f J_f^T)^-1``, m x m."""
        Jf = self.J[:, free]
        K = Jf @ Jf.T
        K.flat[::K.shape[0] + 1] += self.lam
        self.Jf, self.Kinv = Jf, _inv(K)

    def solve(self, V: np.ndarray) -> np.ndarray:
        """``H_ff^-1 V`` for a vector or a column block on the free variables."""
        Jf = self.Jf
        return (V - Jf.T @ (self.Kinv @ (Jf @ V))) / self.lam


def _model(H: _Hessian, c: np.ndarray, d: np.ndarray) -> float:
    return float(c @ d + 0.5 * d @ H.dot(d))


def bounded_step(J: np.ndarray, lam: float, c: np.ndarray, lower: np.ndarray, upper: np.ndarray,
                 A: np.ndarray | None = None, r: np.ndarray | None = None, *,
                 held: np.ndarray | None = None, max_iterations: int = 100,
                 tol: float = 1e-12, compiled: bool = True) -> tuple[np.ndarray, np.ndarray, int]:
    """(the minimiser ``d``, the bounds held at it, inner iterations) of the QP above.

    Every iterate is feasible. ``held``: a guess of the variables held at a bound (the previous
    step's; those not at a bound are ignored), a warm start of the search. ``tol`` is relative to
    ``max |c|``: multipliers above ``-tol max|c|`` count as non-negative. Without rows the search
    runs as one compiled loop when numba is installed (``compiled=False``: the numpy reference).
    With rows the compiled box minimiser is tried first: when it meets every row it is also the
    minimiser with them (the QP is strictly convex and the rows only cut its feasible set), so the
    row-aware numpy search runs only when a row actually binds.
    """
    n = c.size
    d = np.zeros(n)
    if n == 0:
        return d, np.zeros(0, dtype=bool), 0
    rows_on = A is not None and A.shape[0] > 0
    if rows_on:  # the start d = 0 is feasible: a slack rounded below zero is zero (else the final
        r = np.maximum(np.asarray(r, dtype=float), 0.0)  # shrink's factor r / Ad turns negative)
    if compiled and _box_step_compiled is not None:
        h = np.zeros(n, dtype=bool) if held is None else np.array(held, dtype=bool)
        box = _box_step_compiled(np.ascontiguousarray(J, dtype=float), float(lam),
                                 np.ascontiguousarray(c, dtype=float), np.ascontiguousarray(lower, dtype=float),
                                 np.ascontiguousarray(upper, dtype=float), h, max_iterations, tol)
        if not rows_on or np.all(A @ box[0] <= r + ROW_TOL):
            return box
        h = np.zeros(n, dtype=bool) if held is None else np.array(held, dtype=bool)
        return _row_step_compiled(np.ascontiguousarray(J, dtype=float), float(lam),
                                  np.ascontiguousarray(c, dtype=float), np.ascontiguousarray(lower, dtype=float),
                                  np.ascontiguousarray(upper, dtype=float), A.astype(float, order="C"),
                                  np.ascontiguousarray(r, dtype=float), h, max_iterations, tol)
    H = _Hessian(J, lam)
    fixed = upper - lower <= AT_BOUND
    at_lo, at_hi = lower >= -AT_BOUND, upper <= AT_BOUND
    held = fixed | (at_lo & (c > 0)) | (at_hi & (c < 0)) | (
        (at_lo | at_hi) & held if held is not None else False)
    working: list[int] = []
    eps = tol * max(float(np.max(np.abs(c))), 1e-300)
    it = 0
    on_face = False  # d is the exact minimiser on the current face (a full, unclipped Newton step)
    for it in range(1, max_iterations + 1):
        grad = H.dot(d) + c
        free = np.flatnonzero(~held)
        s = np.zeros(n)
        nu = np.zeros(len(working))
        if free.size and not on_face:
            H.factor(free)
            sf = -H.solve(grad[free])
            if working:
                Aw = A[working][:, free]
                HA = H.solve(Aw.T)
                nu = np.linalg.lstsq(Aw @ HA, Aw @ sf, rcond=1e-12)[0]
                sf = sf - HA @ nu
                sf = sf - Aw.T @ np.linalg.lstsq(Aw @ Aw.T, Aw @ sf, rcond=1e-12)[0]  # exactly on the rows
            s[free] = sf
        decrease = -float(grad @ s)  # twice the model decrease of the full step, up to rows' share
        if on_face or decrease <= 1e-15 * (1.0 + abs(_model(H, c, d))) or float(np.max(np.abs(s))) <= 1e-15:
            on_face = False
            # a minimiser on the current face: release every bound and the worst row with a wrong multiplier
            eff = grad + (A[working].T @ nu if working else 0.0)
            at_lo = d <= lower + AT_BOUND
            wrong = held & ~fixed & np.where(at_lo, eff < -eps, eff > eps)
            if wrong.any():
                held &= ~wrong
                continue
            if working and float(np.min(nu)) < -eps:
                working.pop(int(np.argmin(nu)))
                continue
            break
        if not working:  # gradient projection: bind (and keep free) many bounds in one step
            q0 = _model(H, c, d)
            alpha = 1.0
            for _ in range(20):
                trial = np.minimum(np.maximum(d + alpha * s, lower), upper)
                if (not rows_on or np.all(A @ trial <= r + ROW_TOL)) and \
                        _model(H, c, trial) <= q0 + SIGMA * float(grad @ (trial - d)):
                    hit = ((trial <= lower + AT_BOUND) & (s < 0)) | ((trial >= upper - AT_BOUND) & (s > 0))
                    on_face = alpha == 1.0 and not hit.any()
                    d = trial
                    held |= hit
                    break
                alpha *= 0.5
            else:
                alpha = 0.0
            if alpha > 0.0:
                continue
        # one constraint at a time: the largest feasible step along s, the blocking bound or row joins
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(s > 0, (upper - d) / s, np.where(s < 0, (lower - d) / s, np.inf))
        var = int(np.argmin(ratio))
        a, row = min(1.0, max(float(ratio[var]), 0.0)), -1
        if rows_on:
            inactive = np.ones(A.shape[0], dtype=bool)
            inactive[working] = False
            idx = np.flatnonzero(inactive)
            if idx.size:
                As = A[idx] @ s
                pos = As > 1e-15
                if pos.any():
                    rr = np.full(idx.size, np.inf)
                    rr[pos] = np.maximum(r[idx][pos] - A[idx][pos] @ d, 0.0) / As[pos]
                    k = int(np.argmin(rr))
                    if rr[k] < a:
                        a, row = float(rr[k]), int(idx[k])
        d = np.minimum(np.maximum(d + a * s, lower), upper)
        if row >= 0:
            working.append(row)
        elif a < 1.0:
            held[var] = True
            d[var] = upper[var] if s[var] > 0 else lower[var]
    if rows_on:  # rounding along the working rows: shrink toward the feasible start d = 0
        Ad = A @ d
        over = Ad > r + ROW_TOL
        if over.any():
            d = d * float(np.min(np.where(over, r / np.where(over, Ad, 1.0), 1.0)))
    return d, held, it


def _box_step(J, lam, c, lower, upper, held, max_iterations, tol):  # pragma: no cover - compiled
    """:func:`bounded_step` without rows, as one loop (compiled by numba when it is installed)."""
    m, n = J.shape
    d = np.zeros(n)
    fixed = upper - lower <= AT_BOUND
    for i in range(n):
        at_bound = lower[i] >= -AT_BOUND or upper[i] <= AT_BOUND
        held[i] = fixed[i] or (lower[i] >= -AT_BOUND and c[i] > 0) or (upper[i] <= AT_BOUND and c[i] < 0) \
            or (held[i] and at_bound)
    eps = tol * max(np.max(np.abs(c)), 1e-300)
    on_face = False
    it = 0
    # the factor of the free block, (lambda I + J_f J_f^T) = L L^T, kept while the held set stays
    factored = False
    free = np.nonzero(~held)[0]
    Jf = np.empty((m, 0))
    L = np.empty((m, m))
    while it < max_iterations:
        it += 1
        Jd = J @ d
        grad = J.T @ Jd + lam * d + c
        q0 = c @ d + 0.5 * (Jd @ Jd + lam * (d @ d))
        s = np.zeros(n)
        if not on_face:
            if not factored:
                free = np.nonzero(~held)[0]
                if free.size:
                    Jf = np.ascontiguousarray(J[:, free])
                    K = Jf @ Jf.T
                    for k in range(m):
                        K[k, k] += lam
                    L = np.linalg.cholesky(K)
                factored = True
            if free.size:
                gf = grad[free]
                y = Jf @ gf
                for i in range(m):  # L L^T y' = y: forward, then back substitution
                    v = y[i]
                    for k in range(i):
                        v -= L[i, k] * y[k]
                    y[i] = v / L[i, i]
                for i in range(m - 1, -1, -1):
                    v = y[i]
                    for k in range(i + 1, m):
                        v -= L[k, i] * y[k]
                    y[i] = v / L[i, i]
                sf = -(gf - Jf.T @ y) / lam
                for k in range(free.size):
                    s[free[k]] = sf[k]
        decrease = -(grad @ s)
        if on_face or decrease <= 1e-15 * (1.0 + abs(q0)) or np.max(np.abs(s)) <= 1e-15:
            on_face = False
            wrong = False
            for i in range(n):
                if held[i] and not fixed[i]:
                    at_lo = d[i] <= lower[i] + AT_BOUND
                    if (at_lo and grad[i] < -eps) or (not at_lo and grad[i] > eps):
                        held[i] = False
                        wrong = True
            if wrong:
                factored = False
                continue
            break
        alpha = 1.0
        accepted = False
        for _ in range(20):
            trial = np.minimum(np.maximum(d + alpha * s, lower), upper)
            Jt = J @ trial
            qt = c @ trial + 0.5 * (Jt @ Jt + lam * (trial @ trial))
            if qt <= q0 + SIGMA * (grad @ (trial - d)):
                hit = False
                for i in range(n):
                    if (trial[i] <= lower[i] + AT_BOUND and s[i] < 0) or (trial[i] >= upper[i] - AT_BOUND and s[i] > 0):
                        if not held[i]:
                            held[i] = True
                            factored = False
                        hit = True
                on_face = alpha == 1.0 and not hit
                d = trial
                accepted = True
                break
            alpha *= 0.5
        if accepted:
            continue
        a, var = _box_ratio(d, s, lower, upper)
        d = np.minimum(np.maximum(d + a * s, lower), upper)
        if var >= 0:
            held[var] = True
            factored = False
            d[var] = upper[var] if s[var] > 0 else lower[var]
    return d, held, it


def _box_ratio(d, s, lower, upper):  # pragma: no cover - compiled
    """(the largest step ``a`` in [0, 1] with ``d + a s`` inside ``[lower, upper]``, the variable
    that blocks it or -1)."""
    a, var = 1.0, -1
    for i in range(d.shape[0]):
        if s[i] > 0:
            r = (upper[i] - d[i]) / s[i]
        elif s[i] < 0:
            r = (lower[i] - d[i]) / s[i]
        else:
            continue
        if r < a:
            a, var = r, i
    return max(a, 0.0), var


def _solve_free(Jf, L, lam, V):  # pragma: no cover - compiled
    """``H_ff^-1 V`` for a vector ``V`` on the free variables, ``L L^T = lambda I + J_f J_f^T``."""
    m = L.shape[0]
    y = Jf @ V
    for i in range(m):  # forward, then back substitution
        v = y[i]
        for k in range(i):
            v -= L[i, k] * y[k]
        y[i] = v / L[i, i]
    for i in range(m - 1, -1, -1):
        v = y[i]
        for k in range(i + 1, m):
            v -= L[k, i] * y[k]
        y[i] = v / L[i, i]
    return (V - Jf.T @ y) / lam


def _row_step(J, lam, c, lower, upper, A, r, held, max_iterations, tol):  # pragma: no cover - compiled
    """:func:`bounded_step` with rows, the numpy reference's iterations as one loop (compiled by
    numba): the working rows as an ordered index list, the same tests and tolerances."""
    m, n = J.shape
    nr = A.shape[0]
    d = np.zeros(n)
    fixed = upper - lower <= AT_BOUND
    for i in range(n):
        at_bound = lower[i] >= -AT_BOUND or upper[i] <= AT_BOUND
        held[i] = fixed[i] or (lower[i] >= -AT_BOUND and c[i] > 0) or (upper[i] <= AT_BOUND and c[i] < 0) \
            or (held[i] and at_bound)
    work = np.zeros(nr, dtype=np.int64)
    nw = 0
    eps = tol * max(np.max(np.abs(c)), 1e-300)
    on_face = False
    it = 0
    while it < max_iterations:
        it += 1
        Jd = J @ d
        grad = J.T @ Jd + lam * d + c
        q0 = c @ d + 0.5 * (Jd @ Jd + lam * (d @ d))
        free = np.nonzero(~held)[0]
        nf = free.size
        s = np.zeros(n)
        nu = np.zeros(nw)
        if nf and not on_face:
            Jf = np.ascontiguousarray(J[:, free])
            K = Jf @ Jf.T
            for k in range(m):
                K[k, k] += lam
            L = np.linalg.cholesky(K)
            sf = -_solve_free(Jf, L, lam, np.ascontiguousarray(grad[free]))
            if nw:
                Aw = np.empty((nw, nf))
                for a in range(nw):
                    for k in range(nf):
                        Aw[a, k] = A[work[a], free[k]]
                HA = np.empty((nf, nw))
                for a in range(nw):
                    HA[:, a] = _solve_free(Jf, L, lam, np.ascontiguousarray(Aw[a]))
                nu = np.linalg.lstsq(Aw @ HA, Aw @ sf, 1e-12)[0]
                sf = sf - HA @ nu
                sf = sf - np.ascontiguousarray(Aw.T) @ np.linalg.lstsq(Aw @ np.ascontiguousarray(Aw.T), Aw @ sf, 1e-12)[0]
            for k in range(nf):
                s[free[k]] = sf[k]
        decrease = -(grad @ s)
        if on_face or decrease <= 1e-15 * (1.0 + abs(q0)) or np.max(np.abs(s)) <= 1e-15:
            on_face = False
            eff = grad.copy()
            for a in range(nw):
                eff += nu[a] * A[work[a]]
            wrong = False
            for i in range(n):
                if held[i] and not fixed[i]:
                    at_lo = d[i] <= lower[i] + AT_BOUND
                    if (at_lo and eff[i] < -eps) or (not at_lo and eff[i] > eps):
                        held[i] = False
                        wrong = True
            if wrong:
                continue
            if nw:
                k = int(np.argmin(nu))
                if nu[k] < -eps:
                    for a in range(k, nw - 1):
                        work[a] = work[a + 1]
                    nw -= 1
                    continue
            break
        if nw == 0:  # gradient projection: bind (and keep free) many bounds in one step
            alpha = 1.0
            accepted = False
            for _ in range(20):
                trial = np.minimum(np.maximum(d + alpha * s, lower), upper)
                At = A @ trial
                inside = True
                for j in range(nr):
                    if At[j] > r[j] + ROW_TOL:
                        inside = False
                        break
                if inside:
                    Jt = J @ trial
                    qt = c @ trial + 0.5 * (Jt @ Jt + lam * (trial @ trial))
                    if qt <= q0 + SIGMA * (grad @ (trial - d)):
                        hit = False
                        for i in range(n):
                            if (trial[i] <= lower[i] + AT_BOUND and s[i] < 0) or \
                                    (trial[i] >= upper[i] - AT_BOUND and s[i] > 0):
                                held[i] = True
                                hit = True
                        on_face = alpha == 1.0 and not hit
                        d = trial
                        accepted = True
                        break
                alpha *= 0.5
            if accepted:
                continue
        # one constraint at a time: the largest feasible step along s, the blocking bound or row joins
        step, var = _box_ratio(d, s, lower, upper)
        row = -1
        As = A @ s
        Ad = A @ d
        for j in range(nr):
            working = False
            for a in range(nw):
                if work[a] == j:
                    working = True
            if working or As[j] <= 1e-15:
                continue
            ratio = max(r[j] - Ad[j], 0.0) / As[j]
            if ratio < step:
                step, row = ratio, j
        d = np.minimum(np.maximum(d + step * s, lower), upper)
        if row >= 0:
            work[nw] = row
            nw += 1
        elif var >= 0:
            held[var] = True
            d[var] = upper[var] if s[var] > 0 else lower[var]
    Ad = A @ d  # rounding along the working rows: shrink toward the feasible start d = 0
    shrink = 1.0
    for j in range(nr):
        if Ad[j] > r[j] + ROW_TOL:
            shrink = min(shrink, r[j] / Ad[j])
    if shrink < 1.0:
        d = d * shrink
    return d, held, it


if AVAILABLE:
    _box_step_compiled = kernel(_box_step, "(f8[:, ::1], f8, f8[::1], f8[::1], f8[::1], b1[::1], i8, f8)")
    _box_ratio = kernel(_box_ratio, None)  # also the numpy reference's ratio test: compiled when it first runs
    _solve_free = kernel(_solve_free, None)
    _row_step_compiled = kernel(_row_step, "(f8[:, ::1], f8, f8[::1], f8[::1], f8[::1], f8[:, ::1], f8[::1], b1[::1], "
                                "i8, f8)")
else:  # pragma: no cover - numba is optional
    _box_step_compiled = _row_step_compiled = None
