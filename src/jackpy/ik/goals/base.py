"""The goal interface: a residual vector and its Jacobian from one forward pass.

Every potential of book §3.5 is a squared norm, ``P = |f|^2``, so a goal returns its residual ``f``
(world frame, metres or orientation units) and ``df/dq`` restricted to the columns the solver
moves. The problem multiplies both by ``sqrt(weight)``; the gradient of the weighted sum is then
``2 J^T f`` and ``2 J^T J`` is its Gauss-Newton matrix. End-effector quantities come from
:class:`Context` (the figure-dependent module), potentials from the goal (the figure-free module).

Goal types register themselves: a class that sets ``kind`` (a stable name used in files) is
entered in :data:`GOAL_TYPES` when it is defined. ``targets`` and ``params`` name its editable
attributes (constructor arguments of the same names); :meth:`Goal.to_dict` and
:meth:`Goal.from_dict` write and read them. A :class:`SiteGoal` kind can also be placed by the
workbench's operator: :meth:`SiteGoal.placement` is the world frame a new goal takes at a site so
that it holds, and :meth:`SiteGoal.set_frame` moves its targets with a world frame.
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from jackpy.errors import FigureError
from jackpy.compiled import kernel  # the one numba switch (JACKPY_NO_JIT) and the kernels registry

if TYPE_CHECKING:
    from jackpy.peabody.kinematics import FKResult, Kinematics
    from jackpy.peabody.model import Figure

#: a goal's chain: ``None`` (every joint from the root), a starting joint, or an explicit joint set
Chain = str | Sequence[str] | None

EPS = 1e-12

GOAL_TYPES: dict[str, type[Goal]] = {}
"""Every goal class by its ``kind``, filled as the classes are defined (see :meth:`Goal.__init_subclass__`)."""


#: ``LC9 @ v`` is the cross-product matrix ``[v]x`` of a 3-vector, flattened row-major
_LC9 = np.array([[0, 0, 0], [0, 0, -1], [0, 1, 0],
                 [0, 0, 1], [0, 0, 0], [-1, 0, 0],
                 [0, -1, 0], [1, 0, 0], [0, 0, 0]], dtype=float)


def _site_rows(mom, ang, moved, vectors, weights, point, out):  # pragma: no cover - compiled
    """Rows ``w_k d(v_k)/dq = w_k (a x v_k)`` (plus ``w_0 m`` for a point) into ``out`` (3k, ncols),
    the columns masked by ``moved`` (the DOFs that move the segment): :meth:`Context.stacked_jacobian`
    as one loop."""
    nc = ang.shape[1]
    for j in range(vectors.shape[0]):
        v0, v1, v2 = vectors[j, 0], vectors[j, 1], vectors[j, 2]
        w = weights[j]
        add = point and j == 0
        for c in range(nc):
            m = moved[c] * w
            a0, a1, a2 = ang[0, c], ang[1, c], ang[2, c]
            r0, r1, r2 = a1 * v2 - a2 * v1, a2 * v0 - a0 * v2, a0 * v1 - a1 * v0
            if add:
                r0, r1, r2 = r0 + mom[0, c], r1 + mom[1, c], r2 + mom[2, c]
            out[3 * j, c], out[3 * j + 1, c], out[3 * j + 2, c] = m * r0, m * r1, m * r2


_site_rows_compiled = kernel(_site_rows, "(f8[:, ::1], f8[:, ::1], f8[::1], f8[:, ::1], f8[::1], b1, f8[:, ::1])")
from jackpy.ik.goals.kernels import com_rows as _com_rows_compiled  # noqa: E402
from jackpy.ik.goals.kernels import twist as _twist_compiled  # noqa: E402


def skews(vectors: np.ndarray) -> np.ndarray:
    """Stacked cross-product matrices ``[v_k]x`` of the rows of ``vectors`` (k,3), as (3k, 3)."""
    v = np.asarray(vectors, dtype=float).reshape(-1, 3)
    return (v @ _LC9.T).reshape(-1, 3)


class Columns:
    """Constants of a set of solver columns (DOF indices into ``q``) on one :class:`Kinematics`:
    the DOF signs, which columns translate, and ``moved[s, c]`` (float) = column ``c`` moves
    segment ``s``. Made once per compiled problem and shared by every :class:`Context` on it."""

    def __init__(self, kin: Kinematics, cols: np.ndarray) -> None:
        self.kin, self.cols = kin, np.asarray(cols, dtype=int)
        self.sign = kin.dof_sign[self.cols].astype(float)
        self.trans = np.flatnonzero(np.isin(self.cols, kin.trans_dofs))
        self.is_trans = np.isin(self.cols, kin.trans_dofs)
        self.moved = np.ascontiguousarray(kin.seg_moved_by_dof[:, self.cols], dtype=float)
        #: mass (kg) each column moves, and the figure's
        self.mass_moved = np.ascontiguousarray(kin.mass @ self.moved, dtype=float)
        self.total_mass = float(kin.mass.sum())


_ONE = np.ones(1)


class Context:
    """End-effector module: site transforms and Jacobians (world frame) from one FK pass.

    ``cols`` are the DOF indices (into ``q``) the solver moves; every Jacobian has one column per
    entry of ``cols`` (rotations in radians, translations in metres). ``columns`` are their
    precomputed :class:`Columns` (made here when not given).

    Per segment the Jacobian is a *twist*: moment rows ``m = o x a`` and angular rows ``a`` (3, ncols),
    masked to the DOFs that move the segment (cached per segment). Then ``d(point p)/dq = m - [p]x a``
    and ``d(direction v)/dq = -[v]x a``: any number of points and directions of one segment are one
    small product with stacked ``[.]x`` matrices (:func:`skews`).
    """

    #: site rows, the twist and the hot goals (:mod:`.kernels`) by compiled loops (numba installed
    #: and not ``JACKPY_NO_JIT``); ``False`` on an instance or the class selects the numpy reference
    compiled: bool = _site_rows_compiled is not None

    def __init__(self, kin: Kinematics, fk: FKResult, cols: np.ndarray, columns: Columns | None = None) -> None:
        if columns is None or columns.kin is not kin:
            columns = Columns(kin, cols)
        self.kin, self.fk, self.cols, self.columns = kin, fk, columns.cols, columns
        self._twists: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self._com: tuple[np.ndarray, np.ndarray] | None = None
        if self.compiled:
            n = self.cols.size
            self._ang, self._mom = np.empty((3, n)), np.empty((3, n))
            _twist_compiled(fk.dof_axes, fk.dof_origins, self.cols, columns.sign, columns.is_trans,
                            self._mom, self._ang)
            return
        a = fk.dof_axes[self.cols].T * columns.sign  # (3, ncols) signed world axes
        o = fk.dof_origins[self.cols].T
        # d(point p)/dq = a x p - a x o = -[p]x a + (o x a); translations: a; d(vector v)/dq = -[v]x a
        mom = np.empty_like(a)
        mom[0] = o[1] * a[2] - o[2] * a[1]
        mom[1] = o[2] * a[0] - o[0] * a[2]
        mom[2] = o[0] * a[1] - o[1] * a[0]
        if columns.trans.size:
            t = columns.trans
            mom[:, t] = a[:, t]
            a[:, t] = 0.0
        self._ang, self._mom = np.ascontiguousarray(a), np.ascontiguousarray(mom)

    def site(self, seg: int, location: np.ndarray) -> np.ndarray:
        """World 4x4 transform of a site at ``location`` on segment ``seg``."""
        return self.fk.segments[seg] @ location

    def twist(self, seg: int) -> tuple[np.ndarray, np.ndarray]:
        """(moment rows, angular rows), each (3, ncols), of the DOFs that move segment ``seg``."""
        tw = self._twists.get(seg)
        if tw is None:
            m = self.columns.moved[seg]
            tw = self._twists[seg] = (self._mom * m, self._ang * m)
        return tw

    def point_jacobian(self, seg: int, point: np.ndarray) -> np.ndarray:
        """d(world point fixed on ``seg``)/dq over ``cols``, (3, ncols)."""
        if self.compiled:
            return self.stacked_jacobian(seg, point, _ONE, point=True)
        mom, ang = self.twist(seg)
        return mom - skews(point) @ ang

    def stacked_jacobian(self, seg: int, vectors: np.ndarray, weights: np.ndarray,
                         point: bool = False) -> np.ndarray:
        """Rows ``w_k d(v_k)/dq`` (3k, ncols) for directions ``v_k`` (rows of ``vectors``) fixed on
        ``seg``, in one product; with ``point`` the first row of ``vectors`` is a point instead.

        With numba (:attr:`compiled`) one compiled loop over the unmasked twist, else the numpy
        products over the segment's masked twist (the reference the tests compare against)."""
        if self.compiled:
            v = np.ascontiguousarray(vectors, dtype=float).reshape(-1, 3)
            out = np.empty((3 * v.shape[0], self._ang.shape[1]))
            _site_rows_compiled(self._mom, self._ang, self.columns.moved[seg], v,
                                np.ascontiguousarray(weights, dtype=float).reshape(-1), point, out)
            return out
        mom, ang = self.twist(seg)
        w = np.asarray(weights, dtype=float)
        J = (skews(vectors) * np.repeat(-w, 3)[:, None]) @ ang
        if point:
            J[:3] += w[0] * mom
        return J

    def com(self) -> tuple[np.ndarray, np.ndarray]:
        """World centre of mass (3,) and its Jacobian over ``cols`` (3, ncols); computed once."""
        if self._com is None:
            total = self.columns.total_mass
            if self.compiled and total > 0:  # only the solver's columns, one loop (kernels.py)
                mc = self.kin.mass[:, None] * self.kin.segment_coms(self.fk)
                J = np.empty((3, self.cols.size))
                _com_rows_compiled(self.columns.moved, mc, self.columns.mass_moved, total, self._mom,
                                   self._ang, J)
                self._com = (mc.sum(axis=0) / total, J)
            else:
                c, J = self.kin.com_and_jacobian(self.fk)
                self._com = (c, J[:, self.cols])
        return self._com


@dataclass
class GoalEval:
    """A goal's residual ``f`` (m,), Jacobian ``J`` (m, ncols) and its error in metres and degrees."""

    f: np.ndarray
    J: np.ndarray
    metres: float = 0.0
    degrees: float = 0.0


class Goal:
    """Base of every goal. ``weight`` multiplies the potential; ``name`` labels it in results.

    Subclasses that set ``kind`` register themselves in :data:`GOAL_TYPES`. ``targets``: the
    attributes holding world targets (points, normals, frames; metres); ``params``: the other
    editable attributes. Both are constructor arguments of the same names.
    """

    kind: ClassVar[str] = ""
    targets: ClassVar[tuple[str, ...]] = ()
    params: ClassVar[tuple[str, ...]] = ()
    weight: float
    name: str

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        kind = cls.__dict__.get("kind")
        if not kind:
            return
        old = GOAL_TYPES.get(kind)
        if old is not None and (old.__module__, old.__qualname__) != (cls.__module__, cls.__qualname__):
            raise TypeError(f"goal kind {kind!r} is already {old.__module__}.{old.__qualname__}")
        GOAL_TYPES[kind] = cls

    # ----- files ------------------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """``{"kind", "name", "weight", targets..., params...}`` as JSON values (arrays as lists)."""
        out: dict[str, Any] = {"kind": self.kind, "name": self.name, "weight": float(self.weight)}
        for attr in self.targets + self.params:
            out[attr] = _json_value(getattr(self, attr))
        return out

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Goal:
        """The goal written by :meth:`to_dict` (of this class, or of the class its ``kind`` names)."""
        kind = d.get("kind", cls.kind)
        if kind != cls.kind:
            if kind not in GOAL_TYPES:
                raise ValueError(f"unknown goal kind {kind!r}; known: {', '.join(sorted(GOAL_TYPES))}")
            return GOAL_TYPES[kind].from_dict(d)
        names = set(inspect.signature(cls.__init__).parameters) - {"self"}
        return cls(**{k: v for k, v in d.items() if k in names})

    def bind(self, figure: Figure) -> None:
        """Resolve names against ``figure`` (called when the problem is compiled)."""
        raise NotImplementedError

    def chain_mask(self) -> np.ndarray:
        """Boolean mask over ``q``: the DOFs this goal may move (after :meth:`bind`)."""
        raise NotImplementedError

    def evaluate(self, ctx: Context) -> GoalEval:
        """Residual and Jacobian at the posture of ``ctx``."""
        raise NotImplementedError

    def potential(self, ctx: Context) -> float:
        """Unweighted potential ``P = |f|^2``."""
        f = self.evaluate(ctx).f
        return float(f @ f)

    def leaves(self) -> list[Goal]:
        """The goal itself, or for combinations every goal inside it."""
        return [self]


class SiteGoal(Goal):
    """A goal on an end-effector site ``"segment.site"`` moved by ``chain`` (see :data:`Chain`).

    Subclasses that the operator can place implement :meth:`set_frame` (and :meth:`placement`
    when a new goal should not sit at the site's own frame)."""

    def __init__(self, site: str, chain: Chain = None, weight: float = 1.0, name: str | None = None) -> None:
        if "." not in site:
            raise FigureError(f"end-effector site must be 'segment.site', not {site!r}")
        self.site_name = site
        self.chain = chain
        self.weight = float(weight)
        self.name = name or f"{type(self).__name__}({site})"
        self.seg = -1
        self.location = np.eye(4)
        self._mask = np.zeros(0, dtype=bool)

    def bind(self, figure: Figure) -> None:
        seg_name, site = self.site_name.split(".", 1)
        kin = figure.kinematics()
        self.location = figure.site_location(seg_name, site)
        self.seg = kin.segment_index[seg_name]
        self._mask = chain_mask(figure, self.seg, self.chain)

    def chain_mask(self) -> np.ndarray:
        return self._mask

    # ----- the workbench's operator -----------------------------------------------------------------
    def set_frame(self, frame: np.ndarray) -> None:
        """Move the targets with the world 4x4 ``frame`` the operator gives (see each kind)."""
        raise NotImplementedError(f"a {type(self).__name__} goal cannot be placed by a frame")

    @classmethod
    def placement(cls, site_world: np.ndarray, params: dict[str, Any]) -> np.ndarray:
        """The world frame a new goal of this kind takes on a site at ``site_world`` so that it holds
        (default: the site's own frame)."""
        return np.array(site_world, dtype=float)

    @classmethod
    def check_param(cls, name: str, value: Any) -> Any:
        """A parameter value as the goal stores it (arrays as floats; subclasses normalise more)."""
        return np.array(value, dtype=float) if isinstance(value, (tuple, list)) else value

    @classmethod
    def at_frame(cls, site: str, frame: np.ndarray, chain: Chain = None, weight: float = 1.0,
                 name: str | None = None, **params: Any) -> SiteGoal:
        """A goal of this kind on ``site`` with its targets set from the world ``frame`` and its
        parameters at their defaults unless given."""
        goal = cls.__new__(cls)
        SiteGoal.__init__(goal, site, chain, weight, name)
        for pname, p in inspect.signature(cls.__init__).parameters.items():
            if pname in cls.params:
                value = params.pop(pname, p.default)
                if value is inspect.Parameter.empty:
                    raise TypeError(f"{cls.__name__}: parameter {pname!r} has no default")
                setattr(goal, pname, cls.check_param(pname, value))
        if params:
            raise TypeError(f"{cls.__name__} has no parameters {sorted(params)}")
        goal.set_frame(frame)
        return goal

    def to_dict(self) -> dict[str, Any]:
        out = super().to_dict()
        out["site"] = self.site_name
        out["chain"] = self.chain if self.chain is None or isinstance(self.chain, str) else list(self.chain)
        return out


def _json_value(v: Any) -> Any:
    """A goal attribute as a JSON value: arrays as (nested) lists of floats, numpy scalars as floats."""
    if isinstance(v, np.ndarray):
        return v.astype(float).tolist()
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, (list, tuple)):
        return [_json_value(x) for x in v]
    return v


def chain_mask(figure: Figure, seg: int, chain: Chain) -> np.ndarray:
    """DOFs (mask over ``q``) of ``chain`` for an end effector on segment index ``seg``.

    ``None``: every DOF from the root to the segment. A joint name: the DOFs from that joint to the
    segment (the joint must lie on that path). A sequence of joint names: exactly their DOFs.
    """
    kin = figure.kinematics()
    path = kin.seg_moved_by_dof[seg].copy()
    if chain is None:
        return path
    if isinstance(chain, str):
        joint = figure.joint(chain)
        ji = kin.joint_names.index(joint.name)
        if not np.any(path & (kin.dof_joint == ji)):
            raise FigureError(f"joint {chain!r} is not between the root and segment "
                              f"{kin.segment_names[seg]!r}")
        a, b = kin.segment_index[joint.from_seg], kin.segment_index[joint.to_seg]
        proximal = min(a, b)  # breadth-first order: the parent side comes first
        return path & ~kin.seg_moved_by_dof[proximal]
    mask = np.zeros(kin.ndof, dtype=bool)
    for name in chain:
        mask[figure.joint_dof_slice(name)] = True
    return mask


def unit(v: np.ndarray | Sequence[float], what: str) -> np.ndarray:
    """``v`` as a float unit 3-vector; raises ValueError for a zero vector."""
    a = np.asarray(v, dtype=float).reshape(3)
    n = np.linalg.norm(a)
    if not np.isfinite(n) or n < EPS:
        raise ValueError(f"{what} {tuple(a)} has no direction")
    return a / n


def point3(p: np.ndarray | Sequence[float]) -> np.ndarray:
    """A point as a float (3,) array (a 4x4 gives its origin)."""
    a = np.asarray(p, dtype=float)
    return a[:3, 3].copy() if a.shape == (4, 4) else a.reshape(3).copy()


def rotation3(r: np.ndarray) -> np.ndarray:
    """A 3x3 rotation from a 3x3 or 4x4 array."""
    a = np.asarray(r, dtype=float)
    return a[:3, :3].copy()


def angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    """Angle between unit vectors ``a`` and ``b`` in degrees (robust near 0 and 180)."""
    d, s = a - b, a + b
    return math.degrees(2.0 * math.atan2(math.sqrt(float(d @ d)), math.sqrt(float(s @ s))))


def unit_factor(degrees: float, length: float = 1.0) -> float:
    """Orientation unit factor ``c_d`` (3.11): ``degrees`` of misalignment cost as much as ``length`` metres."""
    return float(length / np.radians(degrees))
