"""Forward kinematics, site Jacobians and centre of mass over a flattened, rooted tree.

The figure's joints form a tree; rooting it at the root site's segment gives each other segment a
parent and a joint to it, traversed either *down* (the joint's from-site is on the parent) or *up*.
With ``L(s)`` a site's location in its segment and ``D`` a joint's displacement transform:

- down: ``W(child) = W(parent) @ L(from) @ D @ L(to)^-1``
- up:   ``W(child) = W(parent) @ L(to) @ D^-1 @ L(from)^-1``
- root: ``W(root segment) = location @ L(root site)^-1``

Everything is flattened once into arrays (rebuilt only when topology or root changes). A forward
pass is a fixed number of batched numpy operations: vectorised Rodrigues for all DOFs, a product of
the (at most three) DOF transforms of every joint, then composition along the tree by pointer
jumping (``ceil(log2(depth))`` batched matrix products), so there is no Python loop per joint or DOF.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.errors import FigureError
from jackpy.peabody.kinematics_jit import forward_kernel
from jackpy.peabody.transforms import rigid_inverse

if TYPE_CHECKING:
    from jackpy.peabody.model import Figure

MAX_JOINT_DOFS = 3


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product of (n,3) arrays (``np.cross`` has a large fixed overhead)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


@dataclass
class FKResult:
    """World transforms from one forward pass.

    ``segments`` (nseg,4,4) in :attr:`Kinematics.segment_names` order; ``dof_axes`` and
    ``dof_origins`` (ndof,3) the world axis and a point on it of every DOF in ``q`` order.
    """

    segments: np.ndarray
    dof_axes: np.ndarray
    dof_origins: np.ndarray


class Kinematics:
    """The flattened rooted tree of a figure; call :meth:`forward` with displacements ``q``."""

    def __init__(self, figure: Figure) -> None:
        figure.validate(check_limits=False)
        self.figure_name = figure.name
        self.segment_names: list[str] = []
        self.segment_index: dict[str, int] = {}
        joints = list(figure.joints.values())
        self.joint_names = [j.name for j in joints]
        self.ndof = sum(j.ndof for j in joints)
        nj = len(joints)
        for j in joints:
            if j.ndof > MAX_JOINT_DOFS:
                raise FigureError(f"figure {figure.name!r}: joint {j.name!r} has {j.ndof} DOFs; at most "
                                  f"{MAX_JOINT_DOFS} per joint (chain joints for more)")

        # --- breadth-first order from the root segment ---------------------------------------
        root = figure.root_segment()
        by_seg: dict[str, list[int]] = {s: [] for s in figure.segments}
        for ji, j in enumerate(joints):
            by_seg[j.from_seg].append(ji)
            by_seg[j.to_seg].append(ji)
        parent: list[int] = []
        parent_joint: list[int] = []
        direction: list[int] = []
        order = deque([root])
        seen = {root}
        while order:
            s = order.popleft()
            self.segment_index[s] = len(self.segment_names)
            self.segment_names.append(s)
            for ji in by_seg[s]:
                j = joints[ji]
                other = j.to_seg if j.from_seg == s else j.from_seg
                if other in seen:
                    continue
                seen.add(other)
                order.append(other)
        nseg = len(self.segment_names)
        parent = [-1] * nseg
        parent_joint = [-1] * nseg
        direction = [0] * nseg
        for ji, j in enumerate(joints):
            a, b = self.segment_index[j.from_seg], self.segment_index[j.to_seg]
            if a < b:  # BFS order: the parent comes first
                parent[b], parent_joint[b], direction[b] = a, ji, 1
            else:
                parent[a], parent_joint[a], direction[a] = b, ji, -1
        self.parent = np.array(parent)
        self.parent_joint = np.array(parent_joint)
        self.direction = np.array(direction)

        # --- per-joint data -------------------------------------------------------------------
        self.L_from = np.array([figure.site_location(j.from_seg, j.from_site) for j in joints]).reshape(nj, 4, 4)
        self.L_to = np.array([figure.site_location(j.to_seg, j.to_site) for j in joints]).reshape(nj, 4, 4)
        self.L_from_inv = rigid_inverse(self.L_from) if nj else self.L_from
        self.L_to_inv = rigid_inverse(self.L_to) if nj else self.L_to
        self.joint_from_seg = np.array([self.segment_index[j.from_seg] for j in joints], dtype=int)
        self.joint_direction = np.zeros(nj, dtype=int)
        for s in range(nseg):
            if parent_joint[s] >= 0:
                self.joint_direction[parent_joint[s]] = direction[s]

        # DOF slots: joint ji's DOFs stored proximal-first (reverse of type order) in slots 0..2.
        axes, kinds, slot, dof_joint = [], [], [], []
        for ji, j in enumerate(joints):
            for k, d in enumerate(j.dofs):
                axes.append(d.axis)
                kinds.append(d.kind)
                slot.append(ji * MAX_JOINT_DOFS + (j.ndof - 1 - k))
                dof_joint.append(ji)
        self.dof_axis = np.array(axes, dtype=float).reshape(-1, 3)
        kinds_arr = np.array(kinds)
        self.rot_dofs = np.flatnonzero(kinds_arr == "R")
        self.trans_dofs = np.flatnonzero(kinds_arr == "T")
        self.dof_slot = np.array(slot, dtype=int)
        self.dof_joint = np.array(dof_joint, dtype=int)
        self.dof_sign = self.joint_direction[self.dof_joint] if nj else np.zeros(0, dtype=int)
        self.njoints = nj

        # --- pointer-jumping schedule ------------------------------------------------------------
        anc = self.parent.copy()
        anc[0] = 0
        done = np.zeros(nseg, dtype=bool)
        done[0] = True
        self.jump_steps: list[tuple[np.ndarray, np.ndarray]] = []
        while not done.all():
            idx = np.flatnonzero(~done)
            src = anc[idx]
            self.jump_steps.append((idx, src))
            new_done = done.copy()
            new_done[idx] = done[src]
            anc[idx] = anc[src]
            done = new_done
        # Breadth-first order sorts segments by depth, and after k steps exactly those deeper than
        # 2^k - 1 are unfinished: each step's ``idx`` is a suffix ``start:``.
        self._jumps = [(int(idx[0]), src) for idx, src in self.jump_steps]
        assert all(np.array_equal(idx, np.arange(idx[0], nseg)) for idx, _ in self.jump_steps)
        self.down_seg = np.flatnonzero(self.direction == 1)
        self.up_seg = np.flatnonzero(self.direction == -1)

        # --- ancestry: which DOFs move which segment -------------------------------------------
        # moves[s, i] is True when DOF i lies on the path from the root to segment s.
        seg_moves = np.zeros((nseg, max(nj, 1)), dtype=bool)
        for s in range(1, nseg):
            seg_moves[s] = seg_moves[self.parent[s]]
            seg_moves[s, self.parent_joint[s]] = True
        self.seg_moved_by_dof = seg_moves[:, self.dof_joint] if nj else np.zeros((nseg, 0), dtype=bool)

        # root and mass data
        self.root_site_inv = rigid_inverse(figure.root_site_location())
        segs = [figure.segments[n] for n in self.segment_names]
        self.mass = np.array([s.mass for s in segs], dtype=float)
        self.com_local = np.array([s.com for s in segs], dtype=float).reshape(nseg, 3)
        self._com_h = np.concatenate([self.com_local, np.ones((nseg, 1))], axis=1)[:, :, None]
        self._moved_f = self.seg_moved_by_dof.T.astype(float)  # (ndof, nseg)
        self._m_moved = self._moved_f @ self.mass  # mass moved by each DOF
        self._build_traversal(nseg, nj, joints)

    def _build_traversal(self, nseg: int, nj: int, joints: list) -> None:
        """Per-segment form of the forward pass (see :meth:`forward`).

        Every non-root segment ``s`` gets ``local(s) = P(s) @ S0 @ S1 @ S2 @ Q(s)`` with ``P, Q`` the
        constant site transforms of its parent joint (down: ``L(from)``, ``L(to)^-1``; up: ``L(to)``,
        ``L(from)^-1``) and ``S0..S2`` the joint's DOF transforms in *traversal* order: proximal-first
        going down; for a joint traversed up, ``D^-1`` = the inverse DOF transforms in type order,
        i.e. each DOF with its axis negated. So every DOF is one rotation (or translation) about a
        signed constant axis in a fixed slot ``(t, s)``; unused slots hold the identity.
        """
        P = np.broadcast_to(np.eye(4), (nseg, 4, 4)).copy()
        Q = P.copy()
        for s in range(1, nseg):
            j = self.parent_joint[s]
            if self.direction[s] == 1:
                P[s], Q[s] = self.L_from[j], self.L_to_inv[j]
            else:
                P[s], Q[s] = self.L_to[j], self.L_from_inv[j]
        self._P, self._Q = P, Q
        child = np.zeros(max(nj, 1), dtype=int)
        for s in range(1, nseg):
            child[self.parent_joint[s]] = s
        ndof = self.ndof
        t_slot = np.zeros(ndof, dtype=int)  # traversal slot of each DOF
        start = 0
        for ji, j in enumerate(joints):
            for k in range(j.ndof):
                t_slot[start + k] = (j.ndof - 1 - k) if self.joint_direction[ji] == 1 else k
            start += j.ndof
        seg_of_dof = child[self.dof_joint] if ndof else np.zeros(0, dtype=int)
        self._dof_seg = seg_of_dof
        self._dof_pos = t_slot * nseg + seg_of_dof  # flat index into the (3, nseg) slot grid
        # The DOF's frame (a point on its axis, its axis) is the prefix product before its own
        # transform going down, after it going up (the joint's from-site side): L_k = P S0 .. S_{k-1}.
        up = self.dof_sign < 0
        self._dof_frame = (t_slot + up) * nseg + seg_of_dof  # flat index into (4, nseg) prefixes
        self._dof_parent = self.parent[seg_of_dof] if ndof else np.zeros(0, dtype=int)
        signed = self.dof_axis * self.dof_sign[:, None]
        ra = signed[self.rot_dofs]
        x, y, z = ra[:, 0], ra[:, 1], ra[:, 2]
        zero = np.zeros_like(x)
        self._rot_K = np.stack([zero, -z, y, z, zero, -x, -y, x, zero], axis=1).reshape(-1, 3, 3)
        self._rot_outer = ra[:, :, None] * ra[:, None, :]
        self._rot_rest = np.eye(3) - self._rot_outer
        self._rot_pos = self._dof_pos[self.rot_dofs]
        self._trans_axis = signed[self.trans_dofs]
        self._trans_pos = self._dof_pos[self.trans_dofs]
        # (axis, 0; 0, 1) per DOF: one product with a frame gives its axis and origin
        ad = np.zeros((ndof, 4, 2))
        ad[:, :3, 0] = self.dof_axis
        ad[:, 3, 1] = 1.0
        self._axis_origin = ad
        self._slots_eye = np.broadcast_to(np.eye(4), (MAX_JOINT_DOFS * nseg, 4, 4)).copy()
        # the compiled loop's tables (kinematics_jit): per segment its DOFs in traversal order
        slot_dof = np.lexsort((t_slot, seg_of_dof)) if ndof else np.zeros(0, dtype=int)
        counts = np.bincount(seg_of_dof, minlength=nseg) if ndof else np.zeros(nseg, dtype=int)
        starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
        self._jit_tables = (self.parent.astype(np.int64), np.ascontiguousarray(P), np.ascontiguousarray(Q),
                            starts.astype(np.int64), counts.astype(np.int64), slot_dof.astype(np.int64),
                            np.isin(slot_dof, self.rot_dofs), np.ascontiguousarray(signed[slot_dof]),
                            self.dof_sign[slot_dof] < 0, np.ascontiguousarray(self.dof_axis))
        self.use_jit = forward_kernel is not None

    # ----- forward -----------------------------------------------------------------------------
    def forward(self, q: np.ndarray, location: np.ndarray) -> FKResult:
        """World transforms of every segment for displacements ``q`` and root-site ``location``.

        Vectorised Rodrigues for all rotational DOFs at once (signed axes, constant parts
        precomputed) into a slot grid ``S[t, s]``; the prefix products ``L_{k+1} = L_k @ S_k``
        (``L_0 = P``) are three batched products, ``local = L_3 @ Q`` a fourth; pointer jumping turns
        local into world transforms. Each DOF's world axis and point are one gather of its prefix
        and its parent's world transform and two small products. Nothing is shared between calls
        (thread-safe); the returned arrays are fresh.
        """
        q = np.asarray(q, dtype=float)
        nseg = len(self.segment_names)
        if self.njoints == 0:
            W = np.empty((nseg, 4, 4))
            W[0] = location @ self.root_site_inv
            return FKResult(W, np.zeros((0, 3)), np.zeros((0, 3)))
        if self.use_jit:
            W = np.empty((nseg, 4, 4))
            axes, origins = np.empty((self.ndof, 3)), np.empty((self.ndof, 3))
            # contiguous float64 always: one compiled specialisation, never a new one per caller
            forward_kernel(np.ascontiguousarray(q), np.ascontiguousarray(location, dtype=float),
                           self.root_site_inv, *self._jit_tables,
                           W, axes, origins)
            return FKResult(W, axes, origins)
        return self.forward_numpy(q, location)

    def forward_numpy(self, q: np.ndarray, location: np.ndarray) -> FKResult:
        """:meth:`forward` by batched numpy operations (the reference of the compiled loop)."""
        q = np.asarray(q, dtype=float)
        nseg = len(self.segment_names)
        S = self._slots_eye.copy()
        if self._rot_pos.size:
            a = q[self.rot_dofs]
            c = np.cos(a)[:, None, None]
            s = np.sin(a)[:, None, None]
            S[self._rot_pos, :3, :3] = self._rot_outer + c * self._rot_rest + s * self._rot_K
        if self._trans_pos.size:
            S[self._trans_pos, :3, 3] = self._trans_axis * q[self.trans_dofs, None]
        S = S.reshape(MAX_JOINT_DOFS, nseg, 4, 4)
        L = np.empty((MAX_JOINT_DOFS + 1, nseg, 4, 4))
        L[0] = self._P
        np.matmul(L[0], S[0], out=L[1])
        np.matmul(L[1], S[1], out=L[2])
        np.matmul(L[2], S[2], out=L[3])
        W = np.matmul(L[3], self._Q)
        W[0] = location @ self.root_site_inv
        for start, src in self._jumps:  # breadth-first order: the unfinished segments are a suffix
            np.matmul(W[src], W[start:], out=W[start:])
        ao = W[self._dof_parent] @ (L.reshape(-1, 4, 4)[self._dof_frame] @ self._axis_origin)
        return FKResult(W, ao[:, :3, 0], ao[:, :3, 1])

    # ----- Jacobians -----------------------------------------------------------------------------
    def point_jacobian(self, fk: FKResult, seg: int, point: np.ndarray) -> np.ndarray:
        """d(world point fixed on segment ``seg``)/dq, (3, ndof). ``point`` is in world coordinates."""
        moved = self.seg_moved_by_dof[seg]
        return self._point_jac(fk, moved, point)

    def _point_jac(self, fk: FKResult, moved: np.ndarray, point: np.ndarray) -> np.ndarray:
        sign = self.dof_sign * moved
        lin = _cross(fk.dof_axes, point - fk.dof_origins)
        if self.trans_dofs.size:
            lin[self.trans_dofs] = fk.dof_axes[self.trans_dofs]
        return (lin * sign[:, None]).T

    def rotation_jacobian(self, fk: FKResult, seg: int) -> np.ndarray:
        """Angular velocity of segment ``seg`` per unit dq, world frame, (3, ndof)."""
        sign = self.dof_sign * self.seg_moved_by_dof[seg]
        ang = fk.dof_axes * sign[:, None]
        if self.trans_dofs.size:
            ang[self.trans_dofs] = 0.0
        return ang.T

    def site_jacobian(self, fk: FKResult, seg: int, site_location: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(world site transform, 6 x ndof Jacobian: rows 0-2 linear, 3-5 angular velocity)."""
        w = fk.segments[seg] @ site_location
        jp = self.point_jacobian(fk, seg, w[:3, 3])
        jr = self.rotation_jacobian(fk, seg)
        return w, np.vstack([jp, jr])

    # ----- centre of mass ----------------------------------------------------------------------
    def centre_of_mass(self, fk: FKResult) -> np.ndarray:
        """World centre of mass (metres); the root origin if the figure has no mass."""
        total = self.mass.sum()
        if total <= 0:
            return fk.segments[0][:3, 3].copy()
        c = self.segment_coms(fk)
        return (self.mass[:, None] * c).sum(axis=0) / total

    def segment_coms(self, fk: FKResult) -> np.ndarray:
        """World centre of mass of every segment (nseg,3)."""
        return (fk.segments[:, :3, :] @ self._com_h)[:, :, 0]

    def com_jacobian(self, fk: FKResult) -> np.ndarray:
        """d(centre of mass)/dq (3, ndof), vectorised over all DOFs."""
        total = self.mass.sum()
        if total <= 0 or self.ndof == 0:
            return np.zeros((3, self.ndof))
        return self.com_and_jacobian(fk)[1]

    def com_and_jacobian(self, fk: FKResult) -> tuple[np.ndarray, np.ndarray]:
        """World centre of mass (3,) and d(centre of mass)/dq (3, ndof) from one pass over the segments."""
        total = self.mass.sum()
        if total <= 0 or self.ndof == 0:
            return self.centre_of_mass(fk), np.zeros((3, self.ndof))
        mc = self.mass[:, None] * self.segment_coms(fk)
        com = mc.sum(axis=0) / total
        m_moved = self._m_moved  # (ndof,)
        mc_moved = self._moved_f @ mc  # (ndof,3): mass-weighted COMs moved by each DOF
        lin = _cross(fk.dof_axes, mc_moved - m_moved[:, None] * fk.dof_origins)
        if self.trans_dofs.size:
            lin[self.trans_dofs] = fk.dof_axes[self.trans_dofs] * m_moved[self.trans_dofs, None]
        return com, (lin * self.dof_sign[:, None]).T / total
