"""The flexible torso as one joint group: three torso angles spread over the 18 vertebral joints.

Monheit's spine model (book §2.3, §4.2.3; behaviors.md §2.6). Each axis (flexion about x, lateral bend
about z, axial twist about y) is distributed independently. With ``M = target - sum(current)``:

* bending (toward the limits): ``P = M / (sum(limit) - sum(current))``,
  ``w_i = p_i(P) * r_i(P) * (limit_i - j_i)``;
* unbending (toward rest): ``P = M / (sum(rest) - sum(current))``, ``w_i = p_i r_i (rest_i - j_i)``;
* ``j_i* = j_i + M * w_i / sum(w)``, so the sum hits the target exactly; a joint that would pass its
  limit is clamped there and its excess goes to the others (so every joint stays within its limits).

The participation and resistance weights are a **[proposal]** (the book gives only their behaviour):
``p_i = P + (1 - P) exp(-|i - initiator| / spread)`` (most motion at the initiator, all joints equal at a
full bend) and ``r_i = 1 - resistance * (1 - P) * s_i`` where ``s_i = 1`` beyond the resistor (away from
the initiator) and ``exp(-|i - resistor| / spread)`` between them, so resistance never freezes a joint.
Joints outside ``[bottom, top]`` do not move. Joint indices run from 0 (``l5_s1``) to 17 (``c7_t1``).

The group driver evaluates the model from the rest pose (rest angles are zero), so it is a pure
function of the torso angles; its Jacobian is a central difference (the model is piecewise smooth).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.body.limits import spine_levels
from jackpy.errors import FigureError
from jackpy.peabody.groups import JointGroup

#: group angle names in order, and each one's DOF index inside a vertebral joint's type
SPINE_ANGLES = ("flexion", "lateral", "axial")
#: vertebral joint type order: R(axial y) * R(lateral -z) * R(flexion x); flexion acts first
SPINE_DOFS = ("axial", "lateral", "flexion")
SPINE_AXES = {"axial": (0.0, 1.0, 0.0), "lateral": (0.0, 0.0, -1.0), "flexion": (1.0, 0.0, 0.0)}
_DOF_INDEX = {a: SPINE_DOFS.index(a) for a in SPINE_ANGLES}


def distribute(current: np.ndarray, rest: np.ndarray, lower: np.ndarray, upper: np.ndarray, target: float,
               participation: SpineWeights) -> np.ndarray:
    """One axis of Monheit's model: new joint angles (n,) whose sum is ``target`` (radians).

    ``target`` is clamped to what the active joints can reach. Inactive joints keep ``current``.
    """
    cur = np.asarray(current, dtype=float)
    active = participation.active(cur.size)
    lo, hi = np.where(active, lower, cur), np.where(active, upper, cur)
    target = float(np.clip(target, lo.sum(), hi.sum()))
    m = target - cur.sum()
    if abs(m) < 1e-15:
        return cur.copy()
    rest_gap = float(np.where(active, rest, cur).sum() - cur.sum())
    unbending = rest_gap * m > 0 and abs(m) <= abs(rest_gap)
    goal = np.where(active, rest, cur) if unbending else (hi if m > 0 else lo)
    room = goal - cur
    p = min(max(m / room.sum(), 0.0), 1.0) if abs(room.sum()) > 1e-15 else 1.0
    w = participation.weights(cur.size, p) * room
    out = cur.copy()
    free = active & (np.abs(room) > 1e-15)
    for _ in range(cur.size + 1):  # water-filling: clamp overflowing joints, give their excess to the rest
        if abs(m) < 1e-15 or not free.any():
            break
        wf = np.where(free, w, 0.0)
        if abs(wf.sum()) < 1e-300:
            wf = np.where(free, goal - out, 0.0)
        step = m * wf / wf.sum()
        new = out + step
        over = free & ((new - goal) * np.sign(m) > 0)
        if not over.any():
            out = new
            break
        m -= float((goal[over] - out[over]).sum())
        out[over] = goal[over]
        free &= ~over
    return out


@dataclass
class SpineWeights:
    """Monheit parameters: joint range ``[bottom, top]``, ``initiator``, ``resistor`` and ``resistance``.

    Indices are vertebral joints from 0 (``l5_s1``) to 17 (``c7_t1``); ``resistance`` in [0, 1];
    ``spread`` (joints) sets how fast participation falls off; ``resistor=None`` means no resistor.
    """

    bottom: int = 0
    top: int = 17
    initiator: int = 0
    resistor: int | None = None
    resistance: float = 0.0
    spread: float = 4.0

    def __post_init__(self) -> None:
        if not (0 <= self.bottom <= self.top <= 17 and self.bottom <= self.initiator <= self.top):
            raise FigureError(f"spine: need 0 <= bottom <= initiator <= top <= 17, got bottom={self.bottom} "
                              f"initiator={self.initiator} top={self.top}")
        if not 0.0 <= self.resistance <= 1.0:
            raise FigureError(f"spine: resistance must be in [0, 1], not {self.resistance}")

    def active(self, n: int) -> np.ndarray:
        i = np.arange(n)
        return (i >= self.bottom) & (i <= self.top)

    def weights(self, n: int, p: float) -> np.ndarray:
        """``p_i * r_i`` for global participation ``p`` in [0, 1]."""
        i = np.arange(n)
        part = p + (1.0 - p) * np.exp(-np.abs(i - self.initiator) / self.spread)
        if self.resistor is None or self.resistance == 0.0:
            return part
        side = np.sign(self.resistor - self.initiator) or 1
        beyond = (i - self.resistor) * side >= 0
        s = np.where(beyond, 1.0, np.exp(-np.abs(i - self.resistor) / self.spread))
        return part * (1.0 - self.resistance * (1.0 - p) * s)


#: preset flavours (book §4.2.3)
BEND_FROM_WAIST = SpineWeights(initiator=0)
CURL_FROM_NECK = SpineWeights(initiator=17)


class SpineDriver:
    """Group driver: torso angles (flexion, lateral, axial) radians -> 18 x 3 vertebral displacements."""

    def __init__(self, weights: SpineWeights | None = None, zero_interpolation: bool = True) -> None:
        levels = spine_levels()
        self.weights = weights or SpineWeights()
        self.zero_interpolation = zero_interpolation
        self.lower = np.array([[lv["limits"][d][0] for d in SPINE_DOFS] for lv in levels])
        self.upper = np.array([[lv["limits"][d][1] for d in SPINE_DOFS] for lv in levels])
        self.rest = np.zeros_like(self.lower)

    def group_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """Box limits of the torso angles: the sums of the active joints' limits (radians)."""
        act = self.weights.active(len(self.lower))
        lo = np.array([self.lower[act, _DOF_INDEX[a]].sum() for a in SPINE_ANGLES])
        hi = np.array([self.upper[act, _DOF_INDEX[a]].sum() for a in SPINE_ANGLES])
        return lo, hi

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        out = self.rest.copy()
        for a, t in zip(SPINE_ANGLES, np.asarray(theta, dtype=float)):
            k = _DOF_INDEX[a]
            lo, hi, rest = self.lower[:, k], self.upper[:, k], self.rest[:, k]
            if self.zero_interpolation:
                out[:, k] = distribute(rest, rest, lo, hi, t, self.weights)
            else:  # between the limits only: every active joint at the same fraction of its range
                act = self.weights.active(len(lo))
                span = np.where(act, hi - lo, 0.0)
                u = np.clip((t - np.where(act, lo, rest).sum()) / span.sum(), 0.0, 1.0)
                out[:, k] = np.where(act, lo + u * span, rest)
        return out.reshape(-1)

    def jacobian(self, theta: np.ndarray, h: float = 1e-7) -> np.ndarray:
        theta = np.asarray(theta, dtype=float)
        cols = []
        for k in range(theta.size):
            e = np.zeros_like(theta)
            e[k] = h
            cols.append((self(theta + e) - self(theta - e)) / (2 * h))
        return np.stack(cols, axis=1)


def spine_group(weights: SpineWeights | None = None, zero_interpolation: bool = True) -> JointGroup:
    """The ``spine`` joint group over the 18 vertebral joints (bottom to top)."""
    driver = SpineDriver(weights, zero_interpolation)
    lo, hi = driver.group_limits()
    joints = [str(lv["joint"]) for lv in spine_levels()]
    return JointGroup("spine", joints, list(SPINE_ANGLES), driver, lo, hi)
