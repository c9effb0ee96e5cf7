"""The condition monitor of strength-guided motion (book §5.3.3; spec C13): the state of the lifting
chain at a posture.

For variables ``x`` (:class:`jackpy.peabody.groups.VariableMap`: free DOFs, then group angles) it
reports the grip's world position and its Jacobian over the active variables, the static joint
torques (gravity on every segment and the load's weight at the grip, as
:func:`jackpy.analysis.statics.joint_torques` computes them, for the chain's DOFs only; figure
rooted at the pelvis, so every DOF carries what lies above or beyond it) and, for every
*monitored* DOF, the torque ratio ``r_i = |tau_i| / tau_max,i(theta)`` (book eq. 5.19) against the
strength of the muscle group that must act (:mod:`jackpy.body.strength`, the sign of the torque picks
the flexor or extensor curve). Discomfort is ``max_i r_i``, comfort ``1 - discomfort`` (§5.3.2).

Monitored DOFs: the arm's shoulder and elbow and every vertebral joint (the "whole body" that holds
the load: with the pelvis as root the legs carry nothing here). The clavicle and shoulder-tilt DOFs
are mechanism DOFs of the shoulder-complex driver (they follow its elevation angle) and the wrist,
forearm and fingers hold the grip rigidly; none of them is monitored (decision, docs/lifting.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.analysis.statics import GRAVITY, Load
from jackpy.body import strength as body_strength
from jackpy.body.human import body_spec
from jackpy.body.skeleton import dof_names_of
from jackpy.peabody.groups import VariableMap
from jackpy.peabody.model import Figure

#: power of the smooth maximum of the ratios whose gradient the strategies follow
SOFT_MAX_POWER = 12.0
#: virtual displacement (rad) of each active variable when measuring how the ratios change (§5.3.4)
VIRTUAL_DISPLACEMENT = 1e-4


@dataclass
class ChainState:
    """The monitor's report at one posture; world metres, N·m, radians."""

    x: np.ndarray            # (nx,) all variables
    q: np.ndarray            # (ndof,) joint displacements
    hand: np.ndarray         # (3,) grip position
    jacobian: np.ndarray     # (3, n_active) d hand / d x_active
    torques: np.ndarray      # (ndof,) static joint torques of the chain's DOFs (0 elsewhere)
    ratios: np.ndarray       # (n_monitored,) |tau| / strength of the acting group
    strengths: np.ndarray    # (n_monitored,) strength of the acting group

    @property
    def discomfort(self) -> float:
        """``max_i r_i`` (book §5.3.2)."""
        return float(self.ratios.max())

    @property
    def soft_discomfort(self) -> float:
        """A smooth maximum of the ratios, ``(sum r_i^p)^(1/p)``, p = :data:`SOFT_MAX_POWER`."""
        return soft_max(self.ratios)


def _triple(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Row-wise ``(a x b) · c`` for (n, 3) ``a``, ``b`` and one (3,) ``c``."""
    return (c[0] * (a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1]) + c[1] * (a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2])
            + c[2] * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]))


def soft_max(r: np.ndarray) -> float:
    """``(sum r_i^p)^(1/p)``: within ``n^(1/p)`` of the maximum, and smooth."""
    top = float(np.max(r))
    if top <= 0.0:
        return 0.0
    return top * float(np.sum((r / top) ** SOFT_MAX_POWER) ** (1.0 / SOFT_MAX_POWER))


class LiftingMonitor:
    """Torques, strengths and ratios of one figure lifting ``load_kg`` at ``hand_segment.hand_site``.

    ``figure`` is read (variables, kinematics, body specification) but never posed: every query
    takes the variables explicitly. ``monitored_joints`` names the joints whose DOFs count;
    ``chain_variables`` (:class:`VariableMap` indices) those that may ever move: their DOFs' torques
    are computed too (for the work of a step). Torques are those of
    :func:`jackpy.analysis.statics.joint_torques` restricted to these DOFs (the same sums over the
    segments beyond each DOF, evaluated for these columns only).
    """

    def __init__(self, figure: Figure, hand_segment: str, hand_site: str, load_kg: float,
                 monitored_joints: list[str], chain_variables: list[int] | None = None) -> None:
        self.figure = figure
        self.kin = kin = figure.kinematics()
        self.vmap = VariableMap(figure)
        self.hand_seg = kin.segment_index[hand_segment]
        self.hand_point = figure.site_location(hand_segment, hand_site)[:3, 3].copy()
        self.load = Load(hand_segment, self.hand_point, load_kg * GRAVITY)
        names = figure.dof_names()
        self.monitored = np.array([names.index(f"{jn}[{k}]") for jn in monitored_joints
                                   for k in range(figure.joint(jn).ndof)], dtype=int)
        self.monitored_names = [names[i] for i in self.monitored]
        dq = self.vmap.dq_dx(self.vmap.x())
        moving = np.flatnonzero(np.abs(dq[:, list(chain_variables or [])]).sum(axis=1) > 0)
        self.torque_dofs = np.union1d(self.monitored, moving).astype(int)
        if np.isin(self.torque_dofs, kin.trans_dofs).any():
            raise ValueError("the lifting chain must have rotational DOFs only")
        self._mon_in_torque = np.searchsorted(self.torque_dofs, self.monitored)
        td = self.torque_dofs
        self._moved = kin.seg_moved_by_dof[:, td].T.astype(float)  # (n_torque, nseg)
        self._m_moved = self._moved @ kin.mass
        self._load_moved = kin.seg_moved_by_dof[self.hand_seg, td].astype(float)
        self._sign = kin.dof_sign[td].astype(float)
        spec = body_spec(figure)
        self._sex, self._percentile = spec.sex, spec.percentile
        kinds, dofs = [], []
        for jn in monitored_joints:
            for name in dof_names_of(figure.joint(jn)):
                kinds.append(body_strength.strength_kind(jn))
                dofs.append(name)
        self._kinds, self._dofs = kinds, dofs
        peak = np.array([body_strength.torque(k, d, self._sex, self._percentile) for k, d in zip(kinds, dofs)])
        self._toward_lower, self._toward_upper = peak[:, 0], peak[:, 1]
        self._posture_rows = np.array([body_strength.has_posture(k, d) for k, d in zip(kinds, dofs)], dtype=bool)

    # ----- pieces --------------------------------------------------------------------------------
    def strengths(self, q: np.ndarray, torques: np.ndarray) -> np.ndarray:
        """Strength (N·m) of the group that must act at each monitored DOF for ``torques`` (ndof,):
        the toward-upper group for a positive torque, the toward-lower group otherwise; posture
        curves where the data have one."""
        lo, hi = self._toward_lower.copy(), self._toward_upper.copy()
        for k in np.flatnonzero(self._posture_rows):
            lo[k], hi[k] = body_strength.torque(self._kinds[k], self._dofs[k], self._sex, self._percentile,
                                                float(q[self.monitored[k]]))
        return np.where(torques[self.monitored] >= 0.0, hi, lo)

    def torques(self, fk, hand: np.ndarray) -> np.ndarray:
        """Static torques (ndof,) of :attr:`torque_dofs` (0 elsewhere): gravity on the segments beyond
        each DOF and the load at ``hand`` (world m), ``tau = -sign · w x (sum m c - M o) · g - ...``."""
        kin = self.kin
        td = self.torque_dofs
        mc = kin.mass[:, None] * kin.segment_coms(fk)
        axes, origins = fk.dof_axes[td], fk.dof_origins[td]
        lever = self._moved @ mc - self._m_moved[:, None] * origins
        gen = _triple(axes, lever, GRAVITY) + self._load_moved * _triple(axes, hand - origins, self.load.force)
        out = np.zeros(kin.ndof)
        out[td] = -self._sign * gen
        return out

    def _hand(self, fk) -> np.ndarray:
        w = fk.segments[self.hand_seg]
        return w[:3, :3] @ self.hand_point + w[:3, 3]

    def _ratios(self, q: np.ndarray) -> np.ndarray:
        fk = self.kin.forward(q, self.figure.location)
        tau = self.torques(fk, self._hand(fk))
        return np.abs(tau[self.monitored]) / self.strengths(q, tau)

    def _q_moved(self, x: np.ndarray, q: np.ndarray, v: int) -> np.ndarray:
        """``q`` (the displacements of variables ``x`` less the change of variable ``v``) redone for
        variable ``v`` alone."""
        out = q.copy()
        if v < self.vmap.free_dofs.size:
            out[self.vmap.free_dofs[v]] = x[v]
            return out
        for g, idx, sl in self.vmap.group_slices:
            if sl.start <= v < sl.stop:
                out[idx] = g.driver(x[sl])
        return out

    def _chain_dq_dx(self, x: np.ndarray, active: np.ndarray) -> np.ndarray:
        """(ndof, n_active) d q / d x for the active variables only."""
        out = np.zeros((self.kin.ndof, len(active)))
        nfree = self.vmap.free_dofs.size
        for k, v in enumerate(active):
            if v < nfree:
                out[self.vmap.free_dofs[v], k] = 1.0
        for g, idx, sl in self.vmap.group_slices:
            cols = [k for k, v in enumerate(active) if sl.start <= v < sl.stop]
            if cols:
                jac = g.driver.jacobian(x[sl])
                for k in cols:
                    out[idx, k] = jac[:, active[k] - sl.start]
        return out

    # ----- reports -------------------------------------------------------------------------------
    def ratios_at(self, x: np.ndarray) -> np.ndarray:
        """Torque ratios (n_monitored,) at variables ``x``."""
        return self._ratios(self.vmap.q(x))

    def state(self, x: np.ndarray, active: np.ndarray) -> ChainState:
        """The full report at variables ``x`` with active variable indices ``active``."""
        q = self.vmap.q(x)
        fk = self.kin.forward(q, self.figure.location)
        hand = self._hand(fk)
        jac = self.kin.point_jacobian(fk, self.hand_seg, hand) @ self._chain_dq_dx(x, active)
        tau = self.torques(fk, hand)
        s = self.strengths(q, tau)
        return ChainState(x.copy(), q, hand, jac, tau, np.abs(tau[self.monitored]) / s, s)

    def ratio_gradient(self, state: ChainState, active: np.ndarray) -> np.ndarray:
        """d(soft discomfort)/d x_active (n_active,), by a virtual displacement of each active
        variable in turn (book §5.3.4, Reducing Moment)."""
        base = state.soft_discomfort
        grad = np.zeros(len(active))
        for k, v in enumerate(active):
            x = state.x.copy()
            x[v] += VIRTUAL_DISPLACEMENT
            grad[k] = (soft_max(self._ratios(self._q_moved(x, state.q, int(v)))) - base) / VIRTUAL_DISPLACEMENT
        return grad
