"""Joint groups (dependent joints), book §2.2.5, and the map from free variables to displacements.

A :class:`JointGroup` drives its member joints from a few *group angles* ``theta`` through a
*driver*; the group angles are limited by a box and by linear inequalities ``A @ theta <= b``
(eq. 2.1). A driver may add a non-convex limit as *pieces* (its ``limit_pieces``): the angles must
then also meet every row of at least one piece. Member joint angles are hidden outside the group: the IK and the UI move the group
angles. :class:`VariableMap` turns a figure with groups into one vector of free variables ``x``
(ungrouped DOFs, then each group's angles) with ``q(x)``, ``dq/dx`` and the linear constraints.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Protocol, Union

import numpy as np

from jackpy.errors import FigureError

if TYPE_CHECKING:
    from jackpy.peabody.model import Figure


class Driver(Protocol):
    """Maps group angles (n,) to the concatenated member displacements (m,).

    A driver may also have ``batch(thetas)``: (N, n) group angles -> (N, m) displacements, row ``i``
    equal to ``driver(thetas[i])``, vectorised (the workspace sampler uses it; :func:`driver_batch`
    falls back to one call per row when it is missing).
    """

    def __call__(self, theta: np.ndarray) -> np.ndarray: ...

    def jacobian(self, theta: np.ndarray) -> np.ndarray:
        """d(member displacements)/d(theta), (m, n)."""
        ...


#: a convex piece of a non-convex group limit: rows ``A`` (r, n) and bounds ``b`` (r,), radians
LimitPiece = tuple[np.ndarray, np.ndarray]


#: a driver parameter as a file can hold it
DriverParam = Union[float, int, bool, str]

#: driver kinds a Peabody file can name (``driver = KIND(key = value, ...)``): kind -> a function
#: building the driver from its parameters (``cls.from_dict``). Modules outside peabody register
#: their kinds with :func:`register_driver` when imported (``jackpy.body`` registers ``spine`` and
#: ``shoulder``). A :class:`LinearDriver` needs no kind: it is written as ``driver = matrix(...)``.
DRIVER_KINDS: dict[str, Callable[[dict[str, DriverParam]], "Driver"]] = {}


#: driver kinds registered by importing a module, imported when a file first names the kind; the
#: application layer fills it (the commands add the standard human's ``spine`` and ``shoulder``),
#: so peabody itself imports nothing above it and pays nothing for files without such groups
DRIVER_MODULES: dict[str, str] = {}


def known_driver(kind: str) -> bool:
    """True when ``kind`` is registered, importing its module from :data:`DRIVER_MODULES` if needed."""
    if kind not in DRIVER_KINDS and kind in DRIVER_MODULES:
        import importlib

        importlib.import_module(DRIVER_MODULES[kind])
    return kind in DRIVER_KINDS


def register_driver(kind: str, from_dict: Callable[[dict[str, DriverParam]], "Driver"]) -> None:
    """Make driver ``kind`` readable from Peabody files; its class must have ``kind`` and
    ``to_dict()`` (parameters of the types in :data:`DriverParam`) so the writer can write it."""
    DRIVER_KINDS[kind] = from_dict


def driver_kind(driver: object) -> str | None:
    """The registered kind of ``driver`` (``None`` when it has no file form)."""
    kind = getattr(driver, "kind", None)
    return kind if isinstance(kind, str) and kind in DRIVER_KINDS and hasattr(driver, "to_dict") else None


def make_driver(kind: str, params: dict[str, DriverParam]) -> "Driver":
    """A driver of a registered ``kind`` from its parameters; KeyError for an unknown kind,
    FigureError/ValueError/TypeError for bad parameters (the reader adds the position)."""
    return DRIVER_KINDS[kind](params)


@dataclass
class LinearDriver:
    """Member displacements ``matrix @ theta + offset``."""

    matrix: np.ndarray
    offset: np.ndarray | None = None

    def __post_init__(self) -> None:
        self.matrix = np.atleast_2d(np.asarray(self.matrix, dtype=float))
        self.offset = (np.zeros(self.matrix.shape[0]) if self.offset is None
                       else np.asarray(self.offset, dtype=float).reshape(-1))

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        return self.matrix @ theta + self.offset

    def batch(self, thetas: np.ndarray) -> np.ndarray:
        """(N, n) group angles -> (N, m) member displacements."""
        return np.atleast_2d(np.asarray(thetas, dtype=float)) @ self.matrix.T + self.offset

    def jacobian(self, theta: np.ndarray) -> np.ndarray:
        return self.matrix



def driver_batch(driver: Driver, thetas: np.ndarray) -> np.ndarray:
    """Member displacements (N, m) for group angles ``thetas`` (N, n): the driver's own ``batch``
    when it has one, else one call per row."""
    thetas = np.atleast_2d(np.asarray(thetas, dtype=float))
    batch = getattr(driver, "batch", None)
    if batch is not None:
        return np.asarray(batch(thetas), dtype=float)
    return np.array([np.asarray(driver(t), dtype=float) for t in thetas]).reshape(len(thetas), -1)


@dataclass
class JointGroup:
    """Joints moved as one unit by ``driver`` from ``angles`` (radians/metres).

    ``lower``/``upper`` bound each group angle; ``A @ angles <= b`` adds linear limits. ``pieces``
    (taken from the driver's ``limit_pieces`` when it has them, so a file's ``driver = KIND()`` brings
    them back) make the limit non-convex: the angles must also meet one piece's rows. Every piece has
    the same number of rows; :meth:`rows_at` gives the static rows plus the piece chosen at given
    angles, the convex set the IK projects onto for one solve (re-chosen at the next).
    """

    name: str
    joints: list[str]
    angle_names: list[str]
    driver: Driver
    lower: np.ndarray
    upper: np.ndarray
    A: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    b: np.ndarray = field(default_factory=lambda: np.zeros(0))
    angles: np.ndarray = field(default_factory=lambda: np.zeros(0))
    pieces: list[LimitPiece] = field(default_factory=list)

    def __post_init__(self) -> None:
        n = len(self.angle_names)
        if not self.pieces:
            self.pieces = list(getattr(self.driver, "limit_pieces", ()))
        self.pieces = [(np.asarray(a, dtype=float).reshape(-1, n), np.asarray(b, dtype=float).reshape(-1))
                       for a, b in self.pieces]
        if len({a.shape[0] for a, _ in self.pieces}) > 1 or any(a.shape[0] != b.size for a, b in self.pieces):
            raise FigureError(f"group {self.name!r}: limit pieces need the same number of rows and bounds")
        # per piece, per row: (coefficients / norm, bound / norm) as floats (piece_at runs every solve)
        self._piece_rows = [[(tuple((r / np.linalg.norm(r)).tolist()), float(c / np.linalg.norm(r)))
                             for r, c in zip(a, b)] for a, b in self.pieces]
        self.lower = np.asarray(self.lower, dtype=float).reshape(n)
        self.upper = np.asarray(self.upper, dtype=float).reshape(n)
        self.A = np.asarray(self.A, dtype=float).reshape(-1, n)
        self.b = np.asarray(self.b, dtype=float).reshape(-1)
        if self.A.shape[0] != self.b.size:
            raise FigureError(f"group {self.name!r}: A has {self.A.shape[0]} rows but b has {self.b.size}")
        a = np.asarray(self.angles, dtype=float).reshape(-1)
        self.angles = np.zeros(n) if a.size == 0 else a.reshape(n)

    @property
    def nangles(self) -> int:
        return len(self.angle_names)

    def feasible_rows(self, thetas: np.ndarray, tol: float = 1e-9) -> np.ndarray:
        """Boolean (N,): which rows of ``thetas`` (N, n) respect the box and the linear limits."""
        thetas = np.atleast_2d(np.asarray(thetas, dtype=float))
        ok = np.all((thetas >= self.lower - tol) & (thetas <= self.upper + tol), axis=1)
        if self.A.size:
            ok &= np.all(thetas @ self.A.T <= self.b + tol, axis=1)
        if self.pieces:
            ok &= np.any([np.all(thetas @ a.T <= b + tol, axis=1) for a, b in self.pieces], axis=0)
        return ok

    def is_feasible(self, theta: np.ndarray, tol: float = 1e-9) -> bool:
        """True when ``theta`` respects the box, the linear limits and one limit piece."""
        return bool(self.feasible_rows(np.asarray(theta, dtype=float).reshape(1, -1), tol)[0])

    def piece_at(self, theta: np.ndarray) -> int:
        """Index of the limit piece for angles ``theta``: the one whose nearest row is farthest away
        (largest slack over the row norms; the least violated when outside all). -1 without pieces."""
        if not self.pieces:
            return -1
        t = np.asarray(theta, dtype=float).tolist()
        slack = [min(c - sum(x * y for x, y in zip(r, t)) for r, c in rows) for rows in self._piece_rows]
        return slack.index(max(slack))

    def rows_at(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The convex limit at ``theta``: static rows ``A``, ``b`` plus those of :meth:`piece_at`."""
        k = self.piece_at(theta)
        if k < 0:
            return self.A, self.b
        a, b = self.pieces[k]
        return np.vstack([self.A, a]), np.concatenate([self.b, b])

    def set_angles(self, figure: Figure, theta: np.ndarray) -> None:
        """Set the group angles and drive the member joints; infeasible angles raise FigureError."""
        theta = np.asarray(theta, dtype=float).reshape(self.nangles)
        if not self.is_feasible(theta):
            raise FigureError(f"group {self.name!r}: angles {np.degrees(theta).round(3).tolist()} deg "
                              "violate the group's limits")
        self.angles = theta.copy()
        self.apply(figure)

    def apply(self, figure: Figure) -> None:
        """Write the driver's member displacements into the figure's joints."""
        values = np.asarray(self.driver(self.angles), dtype=float)
        start = 0
        for jn in self.joints:
            j = figure.joint(jn)
            j.displacement = values[start:start + j.ndof].copy()
            start += j.ndof
        if start != values.size:
            raise FigureError(f"group {self.name!r}: driver gives {values.size} values for {start} member DOFs")


class VariableMap:
    """Free variables of a figure: every DOF not in a group, then each group's angles.

    ``x`` has ``nx`` entries; :meth:`q` gives the joint displacements, :meth:`dq_dx` the chain-rule
    matrix, :attr:`lower`/:attr:`upper` the variable boxes and :meth:`linear_constraints` the
    groups' ``A x <= b`` rows lifted to the full ``x``.
    """

    def __init__(self, figure: Figure) -> None:
        self.figure = figure
        names = figure.dof_names()
        grouped = np.zeros(figure.ndof, dtype=bool)
        self.group_slices: list[tuple[object, np.ndarray, slice]] = []
        for g in figure.groups.values():
            idx = np.concatenate([np.arange(figure.ndof)[figure.joint_dof_slice(jn)] for jn in g.joints])
            grouped[idx] = True
            self.group_slices.append((g, idx, slice(0, 0)))
        self.free_dofs = np.flatnonzero(~grouped)
        nfree = self.free_dofs.size
        start = nfree
        slices = []
        for g, idx, _ in self.group_slices:
            slices.append((g, idx, slice(start, start + g.nangles)))
            start += g.nangles
        self.group_slices = slices
        self.nx = start
        self.names = [names[i] for i in self.free_dofs] + [
            f"{g.name}.{a}" for g, _, _ in slices for a in g.angle_names]
        lo, hi = figure.lower, figure.upper
        self.lower = np.concatenate([lo[self.free_dofs]] + [g.lower for g, _, _ in slices])
        self.upper = np.concatenate([hi[self.free_dofs]] + [g.upper for g, _, _ in slices])
        self._piecewise = [g for g, _, _ in slices if g.pieces]
        self._rows: tuple[tuple[int, ...], tuple[np.ndarray, np.ndarray]] | None = None

    def x(self) -> np.ndarray:
        """Current variables from the figure."""
        q = self.figure.q
        return np.concatenate([q[self.free_dofs]] + [g.angles for g, _, _ in self.group_slices])

    def q(self, x: np.ndarray) -> np.ndarray:
        """Joint displacements for variables ``x``."""
        q = self.figure.q
        q[self.free_dofs] = x[:self.free_dofs.size]
        for g, idx, sl in self.group_slices:
            q[idx] = g.driver(x[sl])
        return q

    def dq_dx(self, x: np.ndarray) -> np.ndarray:
        """(ndof, nx) Jacobian of :meth:`q`."""
        m = np.zeros((self.figure.ndof, self.nx))
        m[self.free_dofs, np.arange(self.free_dofs.size)] = 1.0
        for g, idx, sl in self.group_slices:
            m[np.ix_(idx, np.arange(sl.start, sl.stop))] = g.driver.jacobian(x[sl])
        return m

    @property
    def has_pieces(self) -> bool:
        """True when some group has a non-convex (piecewise) limit: :meth:`linear_constraints`
        then depends on the current group angles."""
        return bool(self._piecewise)

    def linear_constraints(self) -> tuple[np.ndarray, np.ndarray]:
        """All groups' ``A x <= b`` rows over the full variable vector, with each piecewise group's
        piece chosen at its current angles (:meth:`JointGroup.rows_at`). While the chosen pieces stay
        the same, the same (read-only) arrays are returned, so a caller can tell a change by identity."""
        key = tuple(g.piece_at(g.angles) for g in self._piecewise)
        if self._rows is not None and self._rows[0] == key:
            return self._rows[1]
        rows, rhs = [], []
        for g, _, sl in self.group_slices:
            ga, gb = g.rows_at(g.angles)
            if ga.size:
                a = np.zeros((ga.shape[0], self.nx))
                a[:, sl] = ga
                rows.append(a)
                rhs.append(gb)
        out = (np.vstack(rows), np.concatenate(rhs)) if rows else (np.zeros((0, self.nx)), np.zeros(0))
        for arr in out:
            arr.flags.writeable = False
        self._rows = (key, out)
        return out

    def apply(self, x: np.ndarray) -> None:
        """Write variables ``x`` into the figure (free DOFs and group angles)."""
        self.figure.q = self.q(x)
        for g, _, sl in self.group_slices:
            g.angles = np.array(x[sl], dtype=float)
