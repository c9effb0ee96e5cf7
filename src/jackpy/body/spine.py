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
function of the torso angles. The model is piecewise smooth and its Jacobian is analytic: the
derivative of the piece the angles lie in (see :func:`distribute_with_derivative`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.body import spine_kernel
from jackpy.body.limits import spine_levels
from jackpy.errors import FigureError
from jackpy.peabody.groups import JointGroup, register_driver

#: group angle names in order, and each one's DOF index inside a vertebral joint's type
SPINE_ANGLES = ("flexion", "lateral", "axial")
#: vertebral joint type order: R(axial y) * R(lateral -z) * R(flexion x); flexion acts first
SPINE_DOFS = ("axial", "lateral", "flexion")
SPINE_AXES = {"axial": (0.0, 1.0, 0.0), "lateral": (0.0, 0.0, -1.0), "flexion": (1.0, 0.0, 0.0)}
_DOF_INDEX = {a: SPINE_DOFS.index(a) for a in SPINE_ANGLES}
_KERNEL_DOFS = np.array([_DOF_INDEX[a] for a in SPINE_ANGLES])


def distribute(current: np.ndarray, rest: np.ndarray, lower: np.ndarray, upper: np.ndarray, target: float,
               participation: SpineWeights) -> np.ndarray:
    """One axis of Monheit's model: new joint angles (n,) whose sum is ``target`` (radians).

    ``target`` is clamped to what the active joints can reach. Inactive joints keep ``current``.
    """
    return distribute_with_derivative(current, rest, lower, upper, target, participation)[0]


def distribute_with_derivative(current: np.ndarray, rest: np.ndarray, lower: np.ndarray, upper: np.ndarray,
                               target: float, participation: SpineWeights) -> tuple[np.ndarray, np.ndarray]:
    """:func:`distribute` and its derivative with respect to ``target``, both (n,).

    The map is piecewise smooth: the pieces are set by bending or unbending, by the side of the rest
    sum the target lies on, by the clamping of the target and of the global participation ``P`` to
    [0, 1], and by which joints the water-filling clamps at their goal. The derivative is that of the
    piece the target lies in; exactly at the turn between bending up and bending down (``M = 0``) it
    is the mean of the two one-sided derivatives (what a central difference gives). Outside the
    reachable range the target is clamped and the derivative is zero.
    """
    cur = np.asarray(current, dtype=float)
    active = participation.active(cur.size)
    lo, hi = np.where(active, lower, cur), np.where(active, upper, cur)
    lo_sum, hi_sum = lo.sum(), hi.sum()
    dtarget = 1.0 if lo_sum <= target <= hi_sum else 0.0
    target = float(np.clip(target, lo_sum, hi_sum))
    m = target - cur.sum()
    rest_a = np.where(active, rest, cur)
    rest_gap = float(rest_a.sum() - cur.sum())
    if abs(m) < 1e-15:
        if not dtarget:
            return cur.copy(), np.zeros_like(cur)
        # at the kink: mean of the one-sided derivatives (each side may be bending or unbending)
        sides = []
        for sgn in (1.0, -1.0):
            goal = rest_a if (abs(rest_gap) > 1e-15 and rest_gap * sgn > 0) else (hi if sgn > 0 else lo)
            room = goal - cur
            if abs(room.sum()) < 1e-15:
                continue
            free = active & (np.abs(room) > 1e-15)
            w = np.where(free, participation.weights(cur.size, 0.0) * room, 0.0)
            if abs(w.sum()) < 1e-300:
                w = np.where(free, room, 0.0)
            sides.append(w / w.sum())
        d = np.mean(sides, axis=0) if sides else np.zeros_like(cur)
        return cur.copy(), d
    unbending = rest_gap * m > 0 and abs(m) <= abs(rest_gap)
    goal = rest_a if unbending else (hi if m > 0 else lo)
    room = goal - cur
    room_sum = room.sum()
    if abs(room_sum) > 1e-15:
        p_raw = m / room_sum
        p = min(max(p_raw, 0.0), 1.0)
        dp = dtarget / room_sum if 0.0 < p_raw < 1.0 else 0.0
    else:
        p, dp = 1.0, 0.0
    w = participation.weights(cur.size, p) * room
    dw = participation.weights_dp(cur.size, p) * room * dp
    out = cur.copy()
    d = np.zeros_like(cur)
    dm = dtarget  # d(remaining M)/d(target): clamped joints take fixed amounts
    free = active & (np.abs(room) > 1e-15)
    for _ in range(cur.size + 1):  # water-filling: clamp overflowing joints, give their excess to the rest
        if abs(m) < 1e-15 or not free.any():
            break
        wf = np.where(free, w, 0.0)
        dwf = np.where(free, dw, 0.0)
        if abs(wf.sum()) < 1e-300:
            wf = np.where(free, goal - out, 0.0)
            dwf = np.zeros_like(cur)
        s, ds = wf.sum(), dwf.sum()
        step = m * wf / s
        new = out + step
        over = free & ((new - goal) * np.sign(m) > 0)
        if not over.any():
            out = new
            d = d + dm * wf / s + m * (dwf * s - wf * ds) / (s * s)
            break
        m -= float((goal[over] - out[over]).sum())
        out[over] = goal[over]
        free &= ~over
    return out, d


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

    def weights_dp(self, n: int, p: float) -> np.ndarray:
        """d(``p_i * r_i``)/dP, the derivative of :meth:`weights`."""
        i = np.arange(n)
        e = np.exp(-np.abs(i - self.initiator) / self.spread)
        part, dpart = p + (1.0 - p) * e, 1.0 - e
        if self.resistor is None or self.resistance == 0.0:
            return dpart
        side = np.sign(self.resistor - self.initiator) or 1
        beyond = (i - self.resistor) * side >= 0
        s = np.where(beyond, 1.0, np.exp(-np.abs(i - self.resistor) / self.spread))
        r = 1.0 - self.resistance * (1.0 - p) * s
        return dpart * r + part * self.resistance * s


#: preset flavours (book §4.2.3)
BEND_FROM_WAIST = SpineWeights(initiator=0)
CURL_FROM_NECK = SpineWeights(initiator=17)


class SpineDriver:
    """Group driver: torso angles (flexion, lateral, axial) radians -> 18 x 3 vertebral displacements."""

    #: the driver kind in Peabody files (``driver = spine(...)``; jackpy.peabody.groups registry)
    kind = "spine"

    def to_dict(self) -> dict[str, float | int | bool]:
        """The parameters that rebuild this driver (:meth:`from_dict`); no resistor when absent."""
        w = self.weights
        out: dict[str, float | int | bool] = {"bottom": w.bottom, "top": w.top, "initiator": w.initiator,
                                              "resistance": float(w.resistance), "spread": float(w.spread),
                                              "zero_interpolation": bool(self.zero_interpolation)}
        if w.resistor is not None:
            out["resistor"] = w.resistor
        return out

    @classmethod
    def from_dict(cls, d: dict) -> SpineDriver:
        """The driver of :meth:`to_dict`'s parameters; FigureError/ValueError for bad ones."""
        unknown = set(d) - {"bottom", "top", "initiator", "resistor", "resistance", "spread", "zero_interpolation"}
        if unknown:
            raise ValueError(f"unknown spine parameters {sorted(unknown)}")

        def index(name: str, default: int) -> int:
            v = d.get(name, default)
            if isinstance(v, bool) or float(v) != int(v):
                raise ValueError(f"{name} must be a vertebral joint index, not {v!r}")
            return int(v)

        resistor = index("resistor", -1) if "resistor" in d else None
        spread = float(d.get("spread", 4.0))
        if not spread > 0:
            raise ValueError(f"spread must be positive, not {spread}")
        weights = SpineWeights(index("bottom", 0), index("top", 17), index("initiator", 0), resistor,
                               float(d.get("resistance", 0.0)), spread)
        return cls(weights, bool(d.get("zero_interpolation", True)))

    def __init__(self, weights: SpineWeights | None = None, zero_interpolation: bool = True) -> None:
        levels = spine_levels()
        self.weights = weights or SpineWeights()
        self.zero_interpolation = zero_interpolation
        self.lower = np.array([[lv["limits"][d][0] for d in SPINE_DOFS] for lv in levels])
        self.upper = np.array([[lv["limits"][d][1] for d in SPINE_DOFS] for lv in levels])
        self.rest = np.zeros_like(self.lower)
        self._cache: tuple | None = None  # (key, displacements, jacobian) of the last evaluation

    def group_limits(self) -> tuple[np.ndarray, np.ndarray]:
        """Box limits of the torso angles: the sums of the active joints' limits (radians)."""
        act = self.weights.active(len(self.lower))
        lo = np.array([self.lower[act, _DOF_INDEX[a]].sum() for a in SPINE_ANGLES])
        hi = np.array([self.upper[act, _DOF_INDEX[a]].sum() for a in SPINE_ANGLES])
        return lo, hi

    def evaluate(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Member displacements (54,) and their analytic Jacobian (54, 3) at ``theta``.

        Each torso angle drives only its own DOF of every vertebra, so column ``a`` is non-zero only
        in the rows of that DOF; it is the derivative of the active piece of the model
        (:func:`distribute_with_derivative`). The last evaluation is kept: the IK asks for the value
        and the Jacobian at the same angles.
        """
        theta = np.asarray(theta, dtype=float)
        w = self.weights
        key = (theta.tobytes(), w.bottom, w.top, w.initiator, w.resistor, w.resistance, w.spread,
               self.zero_interpolation)
        cached = self._cache  # one read: the entry is replaced whole, never edited
        if cached is not None and cached[0] == key:
            return cached[1].copy(), cached[2].copy()
        if self.zero_interpolation and spine_kernel.AVAILABLE:  # the same model as one compiled loop
            o3, j3 = spine_kernel.spine_distribution(theta, self.rest, self.lower, self.upper, _KERNEL_DOFS,
                                                     w.bottom, w.top, w.initiator, w.spread, w.resistor,
                                                     w.resistance)
            out, jac = o3.reshape(-1), j3.reshape(-1, len(SPINE_ANGLES))
            self._cache = (key, out, jac)
            return out.copy(), jac.copy()
        out = self.rest.copy()
        jac = np.zeros(out.shape + (len(SPINE_ANGLES),))
        for c, (a, t) in enumerate(zip(SPINE_ANGLES, np.asarray(theta, dtype=float))):
            k = _DOF_INDEX[a]
            lo, hi, rest = self.lower[:, k], self.upper[:, k], self.rest[:, k]
            if self.zero_interpolation:
                out[:, k], jac[:, k, c] = distribute_with_derivative(rest, rest, lo, hi, t, self.weights)
            else:  # between the limits only: every active joint at the same fraction of its range
                act = self.weights.active(len(lo))
                span = np.where(act, hi - lo, 0.0)
                u_raw = (t - np.where(act, lo, rest).sum()) / span.sum()
                u = min(max(u_raw, 0.0), 1.0)
                out[:, k] = np.where(act, lo + u * span, rest)
                jac[:, k, c] = span / span.sum() if 0.0 <= u_raw <= 1.0 else 0.0
        out, jac = out.reshape(-1), jac.reshape(-1, len(SPINE_ANGLES))
        self._cache = (key, out, jac)
        return out.copy(), jac.copy()

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        return self.evaluate(theta)[0]

    def jacobian(self, theta: np.ndarray) -> np.ndarray:
        """Analytic d(member displacements)/d(torso angles), (54, 3)."""
        return self.evaluate(theta)[1]

    def numerical_jacobian(self, theta: np.ndarray, h: float = 1e-7) -> np.ndarray:
        """Central-difference Jacobian (for tests)."""
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


register_driver(SpineDriver.kind, SpineDriver.from_dict)
