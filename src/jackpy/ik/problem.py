"""An IK problem: a figure, goals at priority levels, locked joints and per-DOF stiffness.

The free variables are those of :class:`~jackpy.peabody.groups.VariableMap` (ungrouped DOFs, then
joint-group angles) that some goal's chain may move, less the locked ones. Following §3.6-E every
goal sees *all* of these variables that move its end effector, so the gradient assembled here is the
exact gradient of the weighted potential over the variables. The solver works in scaled variables
``z = x / s`` (stiffness, §3.8): a DOF with scale ``s < 1`` is reluctant to move, ``s = 0`` locks it.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.errors import FigureError
from jackpy.ik.chain_rule import to_z as _to_z_compiled
from jackpy.ik.goals.base import Columns, Context, Goal, GoalEval
from jackpy.ik.goals.combine import AnyOf
from jackpy.peabody.groups import VariableMap

if TYPE_CHECKING:
    from jackpy.ik.arm7 import ArmChain
    from jackpy.peabody.kinematics import Kinematics
    from jackpy.peabody.model import Figure


class Problem:
    """Goals on one figure. ``add(goal, level)``: level 0 is the highest priority (see :mod:`.priorities`)."""

    def __init__(self, figure: Figure) -> None:
        self.figure = figure
        self._entries: list[tuple[Goal, int]] = []
        self._locked: set[str] = set()
        self._scale: dict[str, np.ndarray] = {}
        self._compiled: Compiled | None = None

    # ----- editing ------------------------------------------------------------------------------
    def add(self, goal: Goal, level: int = 0) -> Goal:
        """Add ``goal`` at priority ``level`` (0 highest; same level = weighted sum); returns it."""
        if level < 0:
            raise ValueError(f"priority level must be >= 0, not {level}")
        self._entries.append((goal, int(level)))
        self._compiled = None
        return goal

    def remove(self, goal: Goal) -> None:
        """Remove ``goal`` (by identity)."""
        self._entries = [(g, lv) for g, lv in self._entries if g is not goal]
        self._compiled = None

    def lock(self, *joints: str) -> None:
        """Remove the DOFs of ``joints`` (or joint-group names) from the variables."""
        for j in joints:
            self._check_name(j)
        self._locked.update(joints)
        self._compiled = None

    def unlock(self, *joints: str) -> None:
        self._locked.difference_update(joints)
        self._compiled = None

    def set_scale(self, joint: str, scale: float | Sequence[float]) -> None:
        """Per-DOF stiffness scale of a joint or joint group (§3.8): 1 normal, 0.5 stiffer, 0 locked.

        One optimisation unit of the DOF is ``scale`` radians (metres); a gradient method moves
        scaled-down DOFs less, so other joints take the motion.
        """
        n = self._check_name(joint)
        s = np.broadcast_to(np.asarray(scale, dtype=float), (n,)).copy()
        if np.any(s < 0) or not np.all(np.isfinite(s)):
            raise ValueError(f"scale of {joint!r} must be finite and >= 0, not {s.tolist()}")
        self._scale[joint] = s
        self._compiled = None

    def invalidate(self) -> None:
        """Recompile on the next solve (after changing a goal's site or chain, or the figure)."""
        self._compiled = None

    @property
    def goals(self) -> list[Goal]:
        return [g for g, _ in self._entries]

    def level_of(self, goal: Goal) -> int:
        for g, lv in self._entries:
            if g is goal:
                return lv
        raise KeyError(goal.name)

    def _check_name(self, name: str) -> int:
        if name in self.figure.groups:
            return self.figure.groups[name].nangles
        return self.figure.joint(name).ndof

    # ----- compiled form ------------------------------------------------------------------------
    def compile(self) -> Compiled:
        """The flattened form the solver uses (cached until the problem or figure topology changes)."""
        kin = self.figure.kinematics()
        if self._compiled is None or self._compiled.kin is not kin:
            if not self._entries:
                raise FigureError("the IK problem has no goals")
            self._compiled = Compiled(self, kin)
        return self._compiled


@dataclass
class Evaluation:
    """Everything from one forward pass at scaled variables ``z``.

    ``levels[k] = (F, J)``: the stacked weighted residuals of level ``k`` and their Jacobian with
    respect to ``z``; the level's potential is ``F.F`` and its gradient ``2 J^T F``.
    """

    z: np.ndarray
    q: np.ndarray
    goal_evals: list[GoalEval]
    levels: dict[int, tuple[np.ndarray, np.ndarray]]
    selection: tuple[int, ...]
    #: the full variables ``x`` of ``z`` and the ``z`` object they were evaluated at (``q`` is the
    #: posture of ``z`` while ``z is evaluated_z``; a solver that snaps ``z`` onto a bound replaces it)
    x: np.ndarray | None = None
    evaluated_z: np.ndarray | None = None

    def posture(self) -> tuple[np.ndarray, np.ndarray] | None:
        """``(x, q)`` of :attr:`z` when this evaluation was made at exactly that ``z``, else ``None``."""
        return (self.x, self.q) if self.x is not None and self.z is self.evaluated_z else None

    def potential(self, level: int) -> float:
        F = self.levels[level][0]
        return float(F @ F)

    def stacked(self, levels: Iterable[int]) -> tuple[np.ndarray, np.ndarray]:
        """Residuals and Jacobians of several levels stacked."""
        parts = [self.levels[k] for k in levels]
        return np.concatenate([p[0] for p in parts]), np.vstack([p[1] for p in parts])


class Compiled:
    """Index maps of a :class:`Problem`: variables, bounds, linear rows and goal evaluation."""

    #: the chain rule to ``z`` by the compiled loop (:mod:`.chain_rule`; ``False``: numpy reference)
    compiled_chain: bool = _to_z_compiled is not None

    def __init__(self, problem: Problem, kin: Kinematics) -> None:
        fig = problem.figure
        self.problem, self.kin, self.figure = problem, kin, fig
        self.entries = list(problem._entries)
        for g, _ in self.entries:
            g.bind(fig)
        self.levels = sorted({lv for _, lv in self.entries})
        self.anyofs = [a for g, _ in self.entries for a in _anyofs(g)]
        vm = VariableMap(fig)
        self.vm = vm
        nfree = vm.free_dofs.size
        chain = np.logical_or.reduce([g.chain_mask() for g, _ in self.entries])
        # per-x: moved by some chain, its scale, locked?
        wanted = np.zeros(vm.nx, dtype=bool)
        scale = np.ones(vm.nx)
        wanted[:nfree] = chain[vm.free_dofs]
        dof_scale = np.ones(fig.ndof)
        dof_locked = np.zeros(fig.ndof, dtype=bool)
        for name in problem._locked:
            if name in fig.joints:
                dof_locked[fig.joint_dof_slice(name)] = True
        for name, s in problem._scale.items():
            if name in fig.joints:
                dof_scale[fig.joint_dof_slice(name)] = s
        scale[:nfree] = dof_scale[vm.free_dofs]
        locked = np.zeros(vm.nx, dtype=bool)
        locked[:nfree] = dof_locked[vm.free_dofs]
        for g, idx, sl in vm.group_slices:
            wanted[sl] = chain[idx].any()
            locked[sl] = dof_locked[idx].any() or g.name in problem._locked
            if g.name in problem._scale:
                scale[sl] = problem._scale[g.name]
        use = wanted & ~locked & (scale > 0)
        self.vidx = np.flatnonzero(use)
        self.nv = self.vidx.size
        self.scale = scale[self.vidx]
        self.lower = vm.lower[self.vidx] / self.scale
        self.upper = vm.upper[self.vidx] / self.scale
        self.n_free_vars = int(np.count_nonzero(self.vidx < nfree))
        free_q = vm.free_dofs[self.vidx[:self.n_free_vars]]
        # groups with at least one variable: (group, member DOFs, x slice, its used angles)
        self.groups = [(g, idx, sl, np.flatnonzero(use[sl])) for g, idx, sl in vm.group_slices
                       if use[sl].any()]
        self.cols = np.concatenate([free_q] + [idx for _, idx, _, _ in self.groups]).astype(int)
        self.free_q = free_q
        self.columns = Columns(kin, self.cols)
        A, b = vm.linear_constraints()
        self.A_x, self.b_x = A, b
        # the rows over z do not change between solves: only their right-hand side does
        A_z = A[:, self.vidx] * self.scale
        self._row_keep = np.any(A_z != 0.0, axis=1)
        self._A_z = A_z[self._row_keep] if A.shape[0] else np.zeros((0, self.nv))
        self._no_rows = np.zeros(0)
        self._A_z.flags.writeable = False  # shared by every solve
        # the chain rule dq/dz, block by block: the free variables' columns are scaled copies; each
        # group's member columns (contiguous in ``cols``) times its driver's Jacobian (per evaluation)
        self._blocks = []
        row = col = self.n_free_vars
        for g, idx, sl, used in self.groups:
            scale_c = self.scale[col:col + used.size]
            # (driver, x slice, used angles or None for all, scale or None for ones, row/column span)
            self._blocks.append((g.driver, sl, None if used.size == sl.stop - sl.start else used,
                                 None if np.all(scale_c == 1.0) else scale_c, row, row + idx.size, col,
                                 col + used.size))
            row += idx.size
            col += used.size
        self._free_scale = np.ascontiguousarray(self.scale[:self.n_free_vars])
        # the compiled chain rule (ik/chain_rule.py): block spans and where each driver's Jacobian
        # sits in one stacked array (member rows x at most 3 used angles)
        spans, at = [], 0
        for b in self._blocks:
            spans.append((b[4], b[5], b[6], b[7], at))
            at += b[5] - b[4]
        self._spans = np.array(spans, dtype=np.int64).reshape(-1, 5)
        self._stack_shape = (at, max([b[7] - b[6] for b in self._blocks], default=0))
        #: (key, Context, chain-rule blocks) of the last evaluation: the posture's geometry does not
        #: depend on the targets, so the next solve's first evaluation (a warm start at the same
        #: posture, new targets) reuses it and evaluates only the goals
        self._geometry: tuple | None = None
        self._level_slots = {lv: [k for k, (_, l) in enumerate(self.entries) if l == lv] for lv in self.levels}
        self.arm: ArmChain | None = None
        if len(self.entries) == 1 and not self.groups:
            from jackpy.ik.arm7 import match_arm

            self.arm = match_arm(fig, self.entries[0][0], self.cols)

    # ----- variables ------------------------------------------------------------------------------
    def start(self, q: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Current full ``x``, scaled variables ``z`` and the linear rows ``A z <= b`` at fixed rest.

        ``q``: the figure's displacements when the caller has them already (saves a walk over joints).
        """
        q = self.figure.q if q is None else q
        x = np.concatenate([q[self.vm.free_dofs]] + [g.angles for g, _, _ in self.vm.group_slices])
        z = x[self.vidx] / self.scale
        if self.vm.has_pieces:  # a non-convex group limit: the rows of its piece at the current angles
            A_x, self.b_x = self.vm.linear_constraints()  # the same arrays while the piece stays
            if A_x is not self.A_x:
                self.A_x, self._A_z = A_x, (A_x[:, self.vidx] * self.scale)[self._row_keep]
        if self.A_x.shape[0]:
            rest = x.copy()
            rest[self.vidx] = 0.0
            b = self.b_x - self.A_x @ rest
            return x, z, self._A_z, b[self._row_keep]
        return x, z, self._A_z, self._no_rows

    def x_of(self, x_base: np.ndarray, z: np.ndarray) -> np.ndarray:
        x = x_base.copy()
        x[self.vidx] = z * self.scale
        return x

    def q_of(self, q_base: np.ndarray, x: np.ndarray) -> np.ndarray:
        q = q_base.copy()
        q[self.free_q] = x[self.vidx[:self.n_free_vars]]
        for g, idx, sl, _ in self.groups:
            q[idx] = g.driver(x[sl])
        return q

    def apply(self, x: np.ndarray, q_base: np.ndarray | None = None, q: np.ndarray | None = None) -> None:
        """Write variables ``x`` into the figure (``q_base``: its displacements, when known; ``q``:
        the displacements of ``x`` when already worked out, e.g. by the evaluation at ``x``)."""
        if q_base is None and q is None:
            self.vm.apply(x)
            return
        self.figure.q = self.q_of(q_base, x) if q is None else q
        for g, _, sl in self.vm.group_slices:
            g.angles = np.array(x[sl], dtype=float)

    # ----- evaluation ------------------------------------------------------------------------------
    def evaluate(self, x_base: np.ndarray, q_base: np.ndarray, z: np.ndarray) -> Evaluation:
        """One forward pass; every goal's residual and Jacobian (over ``z``) from it.

        The goals' Jacobians over the DOF columns are stacked per level and taken to ``z`` once per
        level (:meth:`_to_z`), not goal by goal. The forward pass, the :class:`Context` (with the
        twists and COM it has worked out) and the drivers' Jacobians are kept for the last posture."""
        x = self.x_of(x_base, z)
        q = self.q_of(q_base, x)
        location = self.figure.location
        key = (x.tobytes(), q.tobytes(), location.tobytes())
        geometry = self._geometry
        if geometry is not None and geometry[0] == key:  # a warm start at the last iterate
            ctx, chain = geometry[1], geometry[2]
        else:
            fk = self.kin.forward(q, location)
            ctx = Context(self.kin, fk, self.cols, self.columns)
            chain = self._chain(x)
            self._geometry = (key, ctx, chain)
        evals = [g.evaluate(ctx) for g, _ in self.entries]
        levels = {}
        for lv, slots in self._level_slots.items():
            w = [math.sqrt(self.entries[k][0].weight) for k in slots]
            if len(slots) == 1:
                e = evals[slots[0]]
                F, Jc = w[0] * e.f, w[0] * e.J
            else:  # weights of 1 (the usual) need no product before the copy
                F = np.concatenate([evals[k].f if wk == 1.0 else wk * evals[k].f for wk, k in zip(w, slots)])
                Jc = np.concatenate([evals[k].J if wk == 1.0 else wk * evals[k].J for wk, k in zip(w, slots)])
            levels[lv] = (F, self._to_z(Jc, chain))
        return Evaluation(z, q, evals, levels, tuple(a.selected for a in self.anyofs), x, z)

    def _chain(self, x: np.ndarray) -> tuple[list, np.ndarray | None]:
        """The groups' chain-rule blocks at ``x``: ``[(lo_r, hi_r, lo_c, hi_c, dq/dz block)]`` and,
        for the compiled chain rule, the blocks stacked (``None`` without numba or groups)."""
        blocks = []
        for drv, sl, used, scale, lo_r, hi_r, lo_c, hi_c in self._blocks:
            jac = np.asarray(drv.jacobian(x[sl]), dtype=float)
            if used is not None:
                jac = jac[:, used]
            if scale is not None:
                jac = jac * scale
            blocks.append((lo_r, hi_r, lo_c, hi_c, jac))
        if not blocks or not self.compiled_chain:
            return blocks, None
        stack = np.empty(self._stack_shape)
        for (lo_r, hi_r, lo_c, hi_c, jac), at in zip(blocks, self._spans[:, 4]):
            stack[at:at + hi_r - lo_r, :hi_c - lo_c] = jac
        return blocks, stack

    def _to_z(self, Jc: np.ndarray, chain: tuple[list, np.ndarray | None]) -> np.ndarray:
        """Rows over the DOF columns ``cols`` -> rows over the scaled variables ``z``."""
        blocks, stack = chain
        if not blocks:
            return Jc * self.scale
        out = np.empty((Jc.shape[0], self.nv))
        nf = self.n_free_vars
        if stack is not None:  # one compiled loop (ik/chain_rule.py)
            _to_z_compiled(np.ascontiguousarray(Jc), nf, self._free_scale, self._spans, stack, out)
            return out
        np.multiply(Jc[:, :nf], self._free_scale, out=out[:, :nf])
        for lo_r, hi_r, lo_c, hi_c, jac in blocks:
            np.matmul(Jc[:, lo_r:hi_r], jac, out=out[:, lo_c:hi_c])
        return out


def _anyofs(goal: Goal) -> list[AnyOf]:
    out = [goal] if isinstance(goal, AnyOf) else []
    for sub in getattr(goal, "goals", []):
        out.extend(_anyofs(sub))
    return out
