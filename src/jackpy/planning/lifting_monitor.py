"""The condition monitor of strength-guided motion (book §5.3.3; spec C13): the state of the lifting
chain at a posture.

For variables ``x`` (:class:`jackpy.peabody.groups.VariableMap`: free DOFs, then group angles) it
reports the grip's world position and its Jacobian over the active variables, the static joint
torques (gravity on every segment and the load's weight at the grip; :func:`jackpy.analysis.statics.joint_torques`,
figure rooted at the pelvis, so every DOF carries what lies above or beyond it) and, for every
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

from jackpy.analysis.statics import GRAVITY, Load, joint_torques
from jackpy.body import strength as body_strength
from jackpy.body.human import body_spec
from jackpy.body.skeleton import dof_names_of, joint_kind
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
    torques: np.ndarray      # (ndof,) static joint torques
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


def soft_max(r: np.ndarray) -> float:
    """``(sum r_i^p)^(1/p)``: within ``n^(1/p)`` of the maximum, and smooth."""
    top = float(np.max(r))
    if top <= 0.0:
        return 0.0
    return top * float(np.sum((r / top) ** SOFT_MAX_POWER) ** (1.0 / SOFT_MAX_POWER))


class LiftingMonitor:
    """Torques, strengths and ratios of one figure lifting ``load_kg`` at ``hand_segment.hand_site``.

    ``figure`` is read (variables, kinematics, body specification) but never posed: every query
    takes the variables explicitly. ``monitored_joints`` names the joints whose DOFs count.
    """

    def __init__(self, figure: Figure, hand_segment: str, hand_site: str, load_kg: float,
                 monitored_joints: list[str]) -> None:
        self.figure = figure
        self.kin = figure.kinematics()
        self.vmap = VariableMap(figure)
        self.hand_seg = self.kin.segment_index[hand_segment]
        self.hand_point = figure.site_location(hand_segment, hand_site)[:3, 3].copy()
        self.load = Load(hand_segment, self.hand_point, load_kg * GRAVITY)
        names = figure.dof_names()
        self.monitored = np.array([names.index(f"{jn}[{k}]") for jn in monitored_joints
                                   for k in range(figure.joint(jn).ndof)], dtype=int)
        self.monitored_names = [names[i] for i in self.monitored]
        spec = body_spec(figure)
        self._sex, self._percentile = spec.sex, spec.percentile
        kinds, dofs = [], []
        for jn in monitored_joints:
            j = figure.joint(jn)
            for name in dof_names_of(j):
                kinds.append(joint_kind(jn))
                dofs.append(name)
        self._kinds, self._dofs = kinds, dofs
        peak = np.array([body_strength.torque(k, d, self._sex, self._percentile) for k, d in zip(kinds, dofs)])
        self._toward_lower, self._toward_upper = peak[:, 0], peak[:, 1]
        self._posture_rows = np.array([body_strength.has_posture(k, d) for k, d in zip(kinds, dofs)], dtype=bool)

    def strengths(self, q: np.ndarray, torques: np.ndarray) -> np.ndarray:
        """Strength (N·m) of the group that must act at each monitored DOF: the toward-upper group for
        a positive torque, the toward-lower group otherwise; posture curves where the data have one."""
        lo, hi = self._toward_lower.copy(), self._toward_upper.copy()
        for k in np.flatnonzero(self._posture_rows):
            lo[k], hi[k] = body_strength.torque(self._kinds[k], self._dofs[k], self._sex, self._percentile,
                                                float(q[self.monitored[k]]))
        return np.where(torques[self.monitored] >= 0.0, hi, lo)

    def ratios_at(self, x: np.ndarray) -> np.ndarray:
        """Torque ratios (n_monitored,) at variables ``x``."""
        q = self.vmap.q(x)
        fk = self.kin.forward(q, self.figure.location)
        tau = joint_torques(self.figure, [self.load], q=q, fk=fk)
        return np.abs(tau[self.monitored]) / self.strengths(q, tau)

    def state(self, x: np.ndarray, active: np.ndarray) -> ChainState:
        """The full report at variables ``x`` with active variable indices ``active``."""
        q = self.vmap.q(x)
        fk = self.kin.forward(q, self.figure.location)
        w = fk.segments[self.hand_seg]
        hand = w[:3, :3] @ self.hand_point + w[:3, 3]
        jq = self.kin.point_jacobian(fk, self.hand_seg, hand)
        jac = jq @ self.vmap.dq_dx(x)[:, active]
        tau = joint_torques(self.figure, [self.load], q=q, fk=fk)
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
            grad[k] = (soft_max(self.ratios_at(x)) - base) / VIRTUAL_DISPLACEMENT
        return grad
