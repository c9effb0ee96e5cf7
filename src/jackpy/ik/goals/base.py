"""The goal interface: a residual vector and its Jacobian from one forward pass.

Every potential of book §3.5 is a squared norm, ``P = |f|^2``, so a goal returns its residual ``f``
(world frame, metres or orientation units) and ``df/dq`` restricted to the columns the solver
moves. The problem multiplies both by ``sqrt(weight)``; the gradient of the weighted sum is then
``2 J^T f`` and ``2 J^T J`` is its Gauss-Newton matrix. End-effector quantities come from
:class:`Context` (the figure-dependent module), potentials from the goal (the figure-free module).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.errors import FigureError

if TYPE_CHECKING:
    from jackpy.peabody.kinematics import FKResult, Kinematics
    from jackpy.peabody.model import Figure

#: a goal's chain: ``None`` (every joint from the root), a starting joint, or an explicit joint set
Chain = str | Sequence[str] | None

EPS = 1e-12


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product of (n,3) arrays without ``np.cross`` overhead."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


class Context:
    """End-effector module: site transforms and Jacobians (world frame) from one FK pass.

    ``cols`` are the DOF indices (into ``q``) the solver moves; every Jacobian has one column per
    entry of ``cols`` (rotations in radians, translations in metres).
    """

    def __init__(self, kin: Kinematics, fk: FKResult, cols: np.ndarray) -> None:
        self.kin, self.fk, self.cols = kin, fk, cols
        sign = kin.dof_sign[cols].astype(float)[:, None]
        axes = fk.dof_axes[cols] * sign
        # d(point p)/dq = a x p - a x o = -[p]x a + (o x a); translations: a; d(vector v)/dq = -[v]x a
        self._ang = axes.T.copy()
        self._mom = _cross(fk.dof_origins[cols], axes).T
        if kin.trans_dofs.size:
            t = np.isin(cols, kin.trans_dofs)
            self._mom[:, t] = self._ang[:, t]
            self._ang[:, t] = 0.0
        self._com: tuple[np.ndarray, np.ndarray] | None = None

    def site(self, seg: int, location: np.ndarray) -> np.ndarray:
        """World 4x4 transform of a site at ``location`` on segment ``seg``."""
        return self.fk.segments[seg] @ location

    def point_jacobian(self, seg: int, point: np.ndarray) -> np.ndarray:
        """d(world point fixed on ``seg``)/dq over ``cols``, (3, ncols)."""
        return (self._mom - _skew(point) @ self._ang) * self.kin.seg_moved_by_dof[seg, self.cols]

    def vector_jacobian(self, seg: int, v: np.ndarray) -> np.ndarray:
        """d(world direction fixed on ``seg``)/dq over ``cols``, (3, ncols): ``u x v`` (3.8)."""
        return (_skew(v) @ self._ang) * -1.0 * self.kin.seg_moved_by_dof[seg, self.cols]

    def com(self) -> tuple[np.ndarray, np.ndarray]:
        """World centre of mass (3,) and its Jacobian over ``cols`` (3, ncols); computed once."""
        if self._com is None:
            kin, fk = self.kin, self.fk
            self._com = (kin.centre_of_mass(fk), kin.com_jacobian(fk)[:, self.cols])
        return self._com


@dataclass
class GoalEval:
    """A goal's residual ``f`` (m,), Jacobian ``J`` (m, ncols) and its error in metres and degrees."""

    f: np.ndarray
    J: np.ndarray
    metres: float = 0.0
    degrees: float = 0.0


class Goal:
    """Base of every goal. ``weight`` multiplies the potential; ``name`` labels it in results."""

    weight: float
    name: str

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
    """A goal on an end-effector site ``"segment.site"`` moved by ``chain`` (see :data:`Chain`)."""

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
    return float(np.degrees(2.0 * np.arctan2(np.linalg.norm(a - b), np.linalg.norm(a + b))))


def unit_factor(degrees: float, length: float = 1.0) -> float:
    """Orientation unit factor ``c_d`` (3.11): ``degrees`` of misalignment cost as much as ``length`` metres."""
    return float(length / np.radians(degrees))
