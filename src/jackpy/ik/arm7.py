"""Closed-form IK of the 7-DOF arm (Tolani; quarterly report App. A with the digest's corrections).

The chain, shoulder frame to wrist frame (column vectors, metres):

    Rz(t1) Rx(t2) Rz(t3) . T1 . Ry(t4) . T2 . Ry(t5) Rx(t6) Rz(t7),   T1 = Trans(-a3, 0, d3), T2 = Trans(0, 0, a4)

The redundancy is the **swivel angle** ``phi`` of the elbow about the shoulder-wrist axis (Tolani's
later parameterisation, not the report's wrist lock). For a wrist frame ``T`` and a swivel:

1. elbow ``t4`` from the shoulder-wrist distance (law of cosines as the trig primitive P1:
   ``d3 cos t4 - a3 sin t4 = (|p|^2 - l^2 - a4^2) / (2 a4)``, two roots);
2. the elbow point on its circle about the shoulder-wrist axis at ``phi`` (``phi = 0`` towards the
   shoulder frame's +x projected off the axis, or +y when that is degenerate);
3. the shoulder rotation taking (upper-arm vector, shoulder-wrist vector) onto (elbow point, wrist
   point), split into Z-X-Z angles (two branches ``+-t2``; at ``t2 = 0`` or ``pi``: ``t3 = 0`` and the
   **corrected** ``t1 = atan2(r21, r11)``, not the printed ``atan2(r21, -r11)``);
4. the wrist rotation ``(R_shoulder Ry(t4))^T R`` split into Y-X-Z angles (two branches).

Up to 8 solutions per swivel, each checked by forward kinematics and filtered by joint limits
(angles are shifted by 2 pi where that brings them inside). Vectorised over swivel angles.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from jackpy.peabody.model import Dof, Figure, Joint, Segment
from jackpy.peabody.transforms import rigid_inverse, translation

if TYPE_CHECKING:
    from jackpy.ik.goals.base import Goal
    from jackpy.ik.problem import Compiled

X, Y, Z = np.eye(3)
#: the figure's q order of each of the three joints' DOFs, as Tolani's t1..t7 (see :func:`arm7_figure`)
Q_OF_THETA = np.array([2, 1, 0, 3, 6, 5, 4])


def _rot(axis: int, t: np.ndarray) -> np.ndarray:
    """Batched rotation matrices (..., 3, 3) about x (0), y (1) or z (2)."""
    t = np.asarray(t, dtype=float)
    c, s = np.cos(t), np.sin(t)
    i, j = ((1, 2), (2, 0), (0, 1))[axis]
    m = np.zeros(t.shape + (3, 3))
    m[..., axis, axis] = 1.0
    m[..., i, i] = c
    m[..., j, j] = c
    m[..., i, j] = -s
    m[..., j, i] = s
    return m


def _rmul(a: np.ndarray, m: np.ndarray) -> np.ndarray:
    """``a @ m`` for a stack of 3x3 matrices ``a`` (..., 3, 3) and one matrix (3, k) or vector (3,).

    One product over the stacked rows instead of one per matrix (numpy's batched ``matmul`` is slow on
    3x3 blocks); the same dot products, so the same result.
    """
    return (a.reshape(-1, 3) @ m).reshape(a.shape[:-1] + m.shape[1:])


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product over the last axis (numpy's ``cross`` costs more than the arithmetic here)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a1 * b2 - a2 * b1
    out[..., 1] = a2 * b0 - a0 * b2
    out[..., 2] = a0 * b1 - a1 * b0
    return out


@dataclass
class Arm7:
    """Geometry (metres) and limits (radians, ``t1..t7`` order) of the 7-DOF arm."""

    a3: float = 0.0049
    d3: float = 0.328
    a4: float = 0.2593
    lower: np.ndarray = field(default_factory=lambda: np.radians([-180, -180, -180, 0, -90, -80, -180.0]))
    upper: np.ndarray = field(default_factory=lambda: np.radians([180, 180, 180, 150, 90, 80, 180.0]))

    def fk(self, theta: np.ndarray) -> np.ndarray:
        """Wrist frame(s) in the shoulder frame, (..., 4, 4), for angles (..., 7)."""
        t = np.asarray(theta, dtype=float)
        R3 = _rot(2, t[..., 0]) @ _rot(0, t[..., 1]) @ _rot(2, t[..., 2])
        R4 = R3 @ _rot(1, t[..., 3])
        p = _rmul(R3, np.array([-self.a3, 0.0, self.d3])) + _rmul(R4, np.array([0.0, 0.0, self.a4]))
        out = np.zeros(t.shape[:-1] + (4, 4))
        out[..., :3, :3] = R4 @ _rot(1, t[..., 4]) @ _rot(0, t[..., 5]) @ _rot(2, t[..., 6])
        out[..., :3, 3] = p
        out[..., 3, 3] = 1.0
        return out

    def _reference(self, n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        ref = X if np.linalg.norm(_cross(n, X)) > 1e-6 else Y
        u = ref - (ref @ n) * n
        u /= np.linalg.norm(u)
        return u, _cross(n, u)

    def swivel(self, theta: np.ndarray) -> float:
        """Swivel angle (radians) of the posture ``theta``."""
        t = np.asarray(theta, dtype=float)
        R3 = _rot(2, t[0]) @ _rot(0, t[1]) @ _rot(2, t[2])
        e = R3 @ np.array([-self.a3, 0.0, self.d3])
        p = e + (R3 @ _rot(1, t[3])) @ np.array([0.0, 0.0, self.a4])  # the wrist point, as in fk
        n = p / np.linalg.norm(p)
        u, v = self._reference(n)
        return float(np.arctan2(e @ v, e @ u))

    def solve(self, target: np.ndarray, swivel: float | np.ndarray, limits: bool = True,
              tol: float = 1e-9) -> np.ndarray:
        """All solutions (k, 7) for the wrist frame ``target`` (shoulder frame) at the swivel angle(s).

        Each reproduces ``target`` by :meth:`fk` to ``tol``; with ``limits`` only those inside the
        joint limits are returned. Empty when the wrist is out of reach.
        """
        T = np.asarray(target, dtype=float)
        phi = np.atleast_1d(np.asarray(swivel, dtype=float))
        p, R = T[:3, 3], T[:3, :3]
        dist = float(np.linalg.norm(p))
        l2 = self.a3 ** 2 + self.d3 ** 2
        k = (dist ** 2 - l2 - self.a4 ** 2) / (2.0 * self.a4)
        disc = l2 - k * k
        if disc < 0.0 or dist < 1e-12:
            return np.zeros((0, 7))
        base = np.arctan2(-self.a3, self.d3)
        n = p / dist
        u, v = self._reference(n)
        b2 = np.cos(phi)[:, None] * u + np.sin(phi)[:, None] * v  # elbow direction off the axis (K,3)
        B = np.stack([np.broadcast_to(n, b2.shape), b2, _cross(n, b2)], axis=-1)  # world triads (K,3,3)
        e_loc = np.array([-self.a3, 0.0, self.d3])
        # both elbow roots and both shoulder branches in one batch (K per block), blocks in the order
        # (root, shoulder branch); the wrist's two branches then split each block
        t1s, t2s, t3s, t4s = [], [], [], []
        for t4 in {base + np.arctan2(np.sqrt(disc), k), base - np.arctan2(np.sqrt(disc), k)}:
            w_loc = e_loc + self.a4 * np.array([np.sin(t4), 0.0, np.cos(t4)])
            a1 = w_loc / np.linalg.norm(w_loc)
            a2 = e_loc - (e_loc @ a1) * a1
            if np.linalg.norm(a2) < 1e-12:
                a2 = _cross(a1, Y if abs(a1[1]) < 0.9 else X)
            a2 /= np.linalg.norm(a2)
            A = np.stack([a1, a2, _cross(a1, a2)], axis=-1)
            Rs = _rmul(B, A.T)  # (K,3,3)
            for t1, t2, t3 in _zxz(Rs):
                t1s.append(t1)
                t2s.append(t2)
                t3s.append(t3)
                t4s.append(np.full_like(t1, t4))
        raw = np.stack([np.concatenate(t) for t in (t1s, t2s, t3s, t4s)], axis=-1)  # (blocks*K, 4)
        block = np.repeat(np.arange(len(t1s)), phi.size)
        head, keep = self._wrap(raw, slice(0, 4), limits)
        if keep is not None:  # rows whose shoulder or elbow is out of limits need no wrist
            raw, head, block = raw[keep], head[keep], block[keep]
        t1, t2, t3, t4 = raw.T  # the wrist from the angles as decomposed, before wrapping
        Rw = _rmul(np.swapaxes(_rot(2, t1) @ _rot(0, t2) @ _rot(2, t3) @ _rot(1, t4), -1, -2), R)
        parts, keys = [], []
        for branch, w in enumerate(_yxz(Rw)):
            wrist, keep = self._wrap(np.stack(w, axis=-1), slice(4, 7), limits)
            rows = np.concatenate([head, wrist], axis=-1)
            parts.append(rows if keep is None else rows[keep])
            keys.append(2 * block + branch if keep is None else 2 * block[keep] + branch)
        # the order of the unbatched loops: elbow root, shoulder branch, wrist branch, swivel
        out = np.concatenate(parts)[np.argsort(np.concatenate(keys), kind="stable")]
        err = np.abs(self.fk(out) - T).max(axis=(1, 2)) if out.size else np.zeros(0)
        return out[err <= tol]

    def _wrap(self, cols: np.ndarray, which: slice, limits: bool) -> tuple[np.ndarray, np.ndarray | None]:
        """Angles ``cols`` (rows of joints ``which``) into (-pi, pi], shifted by 2 pi where that brings
        them inside the limits; with ``limits`` also the mask of the rows inside them (else None)."""
        out = (cols + np.pi) % (2 * np.pi) - np.pi
        if not limits:
            return out, None
        lower, upper = self.lower[which], self.upper[which]
        for shift in (2 * np.pi, -2 * np.pi):
            moved = out + shift
            fits = (moved >= lower) & (moved <= upper) & ~((out >= lower) & (out <= upper))
            out = np.where(fits, moved, out)
        return out, np.all((out >= lower - 1e-12) & (out <= upper + 1e-12), axis=1)

    def nearest(self, target: np.ndarray, theta: np.ndarray, samples: int = 72) -> np.ndarray | None:
        """The in-limit solution closest to ``theta`` over the posture's swivel and ``samples`` others."""
        phis = np.concatenate([[self.swivel(theta)], np.linspace(-np.pi, np.pi, samples, endpoint=False)])
        sols = self.solve(target, phis)
        if not sols.size:
            return None
        return sols[int(np.argmin(np.sum((sols - theta) ** 2, axis=1)))]


def _zxz(Rs: np.ndarray) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Both Z-X-Z decompositions of rotations (K,3,3); the digest's singular case with the erratum fixed."""
    r33 = np.clip(Rs[:, 2, 2], -1.0, 1.0)
    out = []
    for sign in (1.0, -1.0):
        t2 = sign * np.arccos(r33)
        s2 = np.sin(t2)
        sing = np.abs(s2) < 1e-9
        safe = np.where(sing, 1.0, s2)
        t3 = np.where(sing, 0.0, np.arctan2(Rs[:, 2, 0] / safe, Rs[:, 2, 1] / safe))
        # t2 = 0: R = Rz(t1 + t3); t2 = pi: R = Rz(t1) Rx(pi) Rz(t3); with t3 = 0 both give atan2(r21, r11)
        t1 = np.where(sing, np.arctan2(Rs[:, 1, 0], Rs[:, 0, 0]),
                      np.arctan2(Rs[:, 0, 2] / safe, -Rs[:, 1, 2] / safe))
        out.append((t1, t2, t3))
    return out


def _yxz(M: np.ndarray) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Both Y-X-Z decompositions ``Ry(a) Rx(b) Rz(c)`` of rotations (K,3,3)."""
    sb = np.clip(-M[:, 1, 2], -1.0, 1.0)
    out = []
    for b in (np.arcsin(sb), np.pi - np.arcsin(sb)):
        cb = np.cos(b)
        sing = np.abs(cb) < 1e-9
        safe = np.where(sing, 1.0, cb)
        a = np.where(sing, np.arctan2(-M[:, 2, 0], M[:, 0, 0]), np.arctan2(M[:, 0, 2] / safe, M[:, 2, 2] / safe))
        c = np.where(sing, 0.0, np.arctan2(M[:, 1, 0] / safe, M[:, 1, 1] / safe))
        out.append((a, b, c))
    return out


def arm7_figure(arm: Arm7 | None = None, name: str = "arm7") -> Figure:
    """A figure of the arm: ``base`` (root, site ``shoulder``), ``upperarm``, ``forearm``, ``hand``.

    Joints ``shoulder`` (DOFs z, x, z: ``q = t3, t2, t1``), ``elbow`` (y: ``t4``) and ``wrist``
    (z, x, y: ``q = t7, t6, t5``); ``hand.base`` is the wrist frame. Neutral posture: all zero
    (arm straight along the shoulder frame's +z).
    """
    arm = arm or Arm7()
    f = Figure(name)
    base = f.add_segment(Segment("base", mass=1.0))
    base.add_site("shoulder")
    ua = f.add_segment(Segment("upperarm", mass=2.0, com=np.array([0.0, 0.0, arm.d3 / 2])))
    ua.add_site("base")
    ua.add_site("elbow", translation(-arm.a3, 0.0, arm.d3))
    fa = f.add_segment(Segment("forearm", mass=1.2, com=np.array([0.0, 0.0, arm.a4 / 2])))
    fa.add_site("base")
    fa.add_site("wrist", translation(0.0, 0.0, arm.a4))
    hand = f.add_segment(Segment("hand", mass=0.4))
    hand.add_site("base")
    lo, hi = arm.lower, arm.upper
    f.add_joint(Joint("shoulder", "base", "shoulder", "upperarm", "base",
                      [Dof("R", Z, lo[2], hi[2]), Dof("R", X, lo[1], hi[1]), Dof("R", Z, lo[0], hi[0])]))
    f.add_joint(Joint("elbow", "upperarm", "elbow", "forearm", "base", [Dof("R", Y, lo[3], hi[3])]))
    f.add_joint(Joint("wrist", "forearm", "wrist", "hand", "base",
                      [Dof("R", Z, lo[6], hi[6]), Dof("R", X, lo[5], hi[5]), Dof("R", Y, lo[4], hi[4])]))
    f.root = ("base", "shoulder")
    return f


@dataclass
class ArmChain:
    """A 6-D goal whose chain is exactly an :class:`Arm7` in a figure."""

    arm: Arm7
    goal: Goal
    shoulder: str
    q_index: np.ndarray  # q index of t1..t7
    z_index: np.ndarray  # solver-variable index of t1..t7
    end: np.ndarray  # site frame in the wrist frame

    def seed(self, comp: Compiled, x_base: np.ndarray, z: np.ndarray) -> np.ndarray | None:
        """Scaled variables of the in-limit closed-form solution nearest the current posture."""
        fig = comp.figure
        j = fig.joint(self.shoulder)
        world = fig.site_world(j.from_seg, j.from_site)
        target = rigid_inverse(world) @ self.goal.target @ rigid_inverse(self.end)
        theta = (z * comp.scale)[self.z_index]
        sol = self.arm.nearest(target, theta)
        if sol is None:
            return None
        out = z.copy()
        out[self.z_index] = sol / comp.scale[self.z_index]
        return out


def match_arm(figure: Figure, goal: Goal, cols: np.ndarray) -> ArmChain | None:
    """An :class:`ArmChain` when ``goal`` is a full-weight 6-D goal on exactly an arm7 chain, else None."""
    from jackpy.ik.goals.position_orientation import PositionOrientation

    if not isinstance(goal, PositionOrientation) or cols.size != 7:
        return None
    if not (0.0 < goal.position_weight < 1.0 and goal.cx > 0 and goal.cy > 0):
        return None
    names = list(figure.joints)
    starts = np.cumsum([0] + [figure.joints[n].ndof for n in names])
    jidx = sorted({int(np.searchsorted(starts, c, side="right") - 1) for c in cols})
    if len(jidx) != 3:
        return None
    sh, el, wr = (figure.joints[names[i]] for i in jidx)
    axes = [tuple(np.round(d.axis, 12)) for j in (sh, el, wr) for d in j.dofs]
    want = [tuple(Z), tuple(X), tuple(Z), tuple(Y), tuple(Z), tuple(X), tuple(Y)]
    if axes != want or sh.to_seg != el.from_seg or el.to_seg != wr.from_seg:
        return None
    seg, _ = goal.site_name.split(".", 1)
    if seg != wr.to_seg:
        return None
    loc = figure.site_location
    m1 = rigid_inverse(loc(sh.to_seg, sh.to_site)) @ loc(el.from_seg, el.from_site)
    m2 = rigid_inverse(loc(el.to_seg, el.to_site)) @ loc(wr.from_seg, wr.from_site)
    if not (np.allclose(m1[:3, :3], np.eye(3), atol=1e-12) and np.allclose(m2[:3, :3], np.eye(3), atol=1e-12)
            and abs(m1[1, 3]) < 1e-12 and np.allclose(m2[:3, 3][:2], 0.0, atol=1e-12)):
        return None
    kin = figure.kinematics()
    if np.any(kin.dof_sign[cols] != 1):
        return None
    q_index = np.concatenate([starts[jidx[0]] + np.array([2, 1, 0]), [starts[jidx[1]]],
                              starts[jidx[2]] + np.array([2, 1, 0])])
    lower, upper = figure.lower[q_index], figure.upper[q_index]
    arm = Arm7(-m1[0, 3], m1[2, 3], m2[2, 3], lower, upper)
    z_index = np.array([int(np.flatnonzero(cols == qi)[0]) for qi in q_index])
    end = rigid_inverse(loc(wr.to_seg, wr.to_site)) @ goal.location
    return ArmChain(arm, goal, sh.name, q_index, z_index, end)
