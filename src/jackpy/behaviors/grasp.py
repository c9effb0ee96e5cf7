"""Kinematic grasp with Jack's five grip types ([SH4] §4.2.7; behaviors.md §2.13).

Steps: (1) the grasp location is the object's grip site; (2) a per-grip distance offset places the
palm centre; (3) the hand is preshaped; (4) the palm is moved to the site (the hands behavior does
this through the arm pass, :meth:`Grasp.palm_goal` gives the goal); (5) each digit closes, proximal
joint first, until one of the segments it moves touches the object, then the next joint closes.

Contact is tested on points sampled along each digit segment (base to child joint), each a ball of
the digit's radius, against the object's exact signed distance (box or cylinder), which is at
least as tight as the bounding-box test of the book. The contact angle of every joint is found by a
coarse scan then bisection, so the residual penetration is below ``tolerance``.

Grip types ([proposal]; the book names them but gives no poses):

=============  ==============  ================================================  ==============
grip           digits          preshape                                          palm offset
=============  ==============  ================================================  ==============
power          all five        fingers straight, thumb opposed                   object radius
precision      thumb, index    fingertips, others curled away                    radius + 6 cm
disc           all five        fingers spread over a flat disc face              half thickness
small disc     thumb+2         as disc, three digits                             half thickness
tripod         thumb+2         thumb, index, middle tips meet                    radius + 5 cm
=============  ==============  ================================================  ==============
"""

from __future__ import annotations

from dataclasses import dataclass, field
import numpy as np

from jackpy.behaviors.anatomy import HandSpec
from jackpy.behaviors.base import param
from jackpy.peabody.model import Figure
from jackpy.peabody.transforms import rigid_inverse

GRIPS = ("power", "precision", "disc", "small disc", "tripod")


@dataclass
class GraspObject:
    """A graspable solid: ``shape`` "box" (``size`` = full x, y, z extents) or "cylinder" (``size`` =
    (diameter, length along local y, unused)); ``pose`` its world 4x4; ``grip_site`` the grasp site
    in its frame: origin where the palm centre should be aimed, local -z pointing from the palm
    into the object, local y along the object's long axis."""

    name: str
    shape: str
    size: tuple[float, float, float]
    pose: np.ndarray = field(default_factory=lambda: np.eye(4))
    grip_site: np.ndarray = field(default_factory=lambda: np.eye(4))

    def signed_distance(self, points: np.ndarray) -> np.ndarray:
        """Signed distance (m, negative inside) of world points (n,3)."""
        inv = rigid_inverse(self.pose)
        p = points @ inv[:3, :3].T + inv[:3, 3]
        if self.shape == "box":
            q = np.abs(p) - 0.5 * np.asarray(self.size)
            outside = np.linalg.norm(np.maximum(q, 0.0), axis=1)
            return outside + np.minimum(q.max(axis=1), 0.0)
        if self.shape == "cylinder":
            r, h = 0.5 * self.size[0], 0.5 * self.size[1]
            dr = np.hypot(p[:, 0], p[:, 2]) - r
            dy = np.abs(p[:, 1]) - h
            q = np.stack([dr, dy], axis=1)
            return np.linalg.norm(np.maximum(q, 0.0), axis=1) + np.minimum(q.max(axis=1), 0.0)
        raise ValueError(f"unknown shape {self.shape!r}")

    @property
    def half_depth(self) -> float:
        """Half the object's extent along the grip site's -z (m): where its surface is."""
        if self.shape == "cylinder":
            return 0.5 * self.size[0]
        axis = np.abs(self.grip_site[:3, 2])
        return float(0.5 * np.asarray(self.size) @ axis)


@dataclass(frozen=True)
class GripType:
    """Digits that close (0 = thumb), preshape as a fraction of each joint's closing range, spread
    of the first joint of the fingers (rad), and the palm's distance (m) beyond the object's surface."""

    digits: tuple[int, ...]
    preshape: float
    tuck: float
    standoff: float


GRIP_TYPES: dict[str, GripType] = {
    "power": GripType((0, 1, 2, 3, 4), 0.0, 0.0, 0.004),
    "precision": GripType((0, 1), 0.15, 0.9, 0.06),
    "disc": GripType((0, 1, 2, 3, 4), 0.1, 0.0, 0.035),
    "small disc": GripType((0, 1, 2), 0.1, 0.9, 0.04),
    "tripod": GripType((0, 1, 2), 0.2, 0.9, 0.05),
}


@dataclass
class GraspParams:
    grip: str = param("power", "grip type", "", None, GRIPS)
    tolerance: float = param(0.001, "largest penetration accepted when a digit stops", "mm", (1e-4, 0.01))
    scan_step: float = param(np.radians(5.0), "coarse closing step before bisection", "deg",
                             (np.radians(0.5), np.radians(20.0)))


@dataclass
class GraspResult:
    """Contact report: per digit, the smallest clearance (m, negative = penetration) to the object."""

    grip: str
    clearance: dict[str, float]

    @property
    def max_penetration(self) -> float:
        return max(0.0, -min(self.clearance.values()))


def _limit_towards(figure: Figure, joint: str, k: int, sign: float) -> float:
    d = figure.joint(joint).dofs[k]
    return d.upper if sign > 0 else d.lower


class FingerCloser:
    """FK-only finger closing for one hand of ``figure`` against ``obj``."""

    def __init__(self, figure: Figure, hand: HandSpec, obj: GraspObject) -> None:
        self.figure = figure
        self.hand = hand
        self.obj = obj
        self.kin = figure.kinematics()
        self.slices = {j.name: figure.joint_dof_slice(j.name).start for j in figure.joints.values()}
        self._samples: dict[str, np.ndarray] = {}
        for digit in hand.digits:
            for s in digit.segments:
                self._samples[s] = self._segment_samples(s)

    def _segment_samples(self, seg: str) -> np.ndarray:
        """Local points (n,4) along a digit segment from its base to its far site (or tip)."""
        sites = self.figure.segment(seg).sites
        ends = [s.location[:3, 3] for s in sites.values()]
        far = max(ends, key=lambda v: np.linalg.norm(v))
        t = np.linspace(0.0, 1.0, 5)[:, None]
        pts = t * far
        return np.hstack([pts, np.ones((len(pts), 1))])

    def clearance(self, q: np.ndarray, segments: list[str], radius: float) -> float:
        """Smallest clearance (m) between the given digit segments and the object at ``q``."""
        fk = self.kin.forward(q, self.figure.location)
        pts = np.vstack([(fk.segments[self.kin.segment_index[s]] @ self._samples[s].T).T[:, :3]
                         for s in segments])
        return float(self.obj.signed_distance(pts).min() - radius)

    def close_digit(self, q: np.ndarray, digit_index: int, p: GraspParams) -> np.ndarray:
        """Close one digit joint by joint until contact; returns the new ``q``."""
        digit = self.hand.digits[digit_index]
        q = q.copy()
        for k, (joint, dof, sign) in enumerate(digit.flex):
            moving = digit.segments[k:]
            i = self.slices[joint] + dof
            limit = _limit_towards(self.figure, joint, dof, sign)
            if self.clearance(q, moving, digit.radius) < 0:
                continue
            a = q[i]
            step = p.scan_step * np.sign(limit - a) if limit != a else 0.0
            hit = None
            while step and abs(limit - a) > 1e-12:
                b = a + step if abs(step) < abs(limit - a) else limit
                q[i] = b
                if self.clearance(q, moving, digit.radius) < 0:
                    hit = (a, b)
                    break
                a = b
            if hit is None:
                q[i] = limit
                continue
            lo, hi = hit
            while True:
                mid = 0.5 * (lo + hi)
                q[i] = mid
                c = self.clearance(q, moving, digit.radius)
                if c < 0:
                    hi = mid
                else:
                    lo = mid
                if -p.tolerance <= c <= 0 or abs(hi - lo) < 1e-6:
                    break
            q[i] = lo
        return q


def preshape(figure: Figure, hand: HandSpec, grip: str) -> None:
    """Open the hand to ``grip``'s starting pose: closing digits open by their preshape fraction,
    the others tucked (closed by ``tuck`` of their range) out of the way."""
    g = GRIP_TYPES[grip]
    for d, digit in enumerate(hand.digits):
        frac = g.preshape if d in g.digits else g.tuck
        for joint, dof, sign in digit.flex:
            jt = figure.joint(joint)
            limit = _limit_towards(figure, joint, dof, sign)
            rest = float(np.clip(0.0, jt.dofs[dof].lower, jt.dofs[dof].upper))
            jt.displacement[dof] = rest + frac * (limit - rest)


def close_fingers(figure: Figure, hand: HandSpec, obj: GraspObject, params: GraspParams | None = None) -> GraspResult:
    """Close the grip's digits onto ``obj`` (the palm already placed); sets the figure's joints."""
    p = params or GraspParams()
    g = GRIP_TYPES[p.grip]
    closer = FingerCloser(figure, hand, obj)
    q = figure.q
    for d in g.digits:
        q = closer.close_digit(q, d, p)
    figure.q = q
    clear = {hand.digits[d].name: closer.clearance(q, hand.digits[d].segments, hand.digits[d].radius)
             for d in g.digits}
    return GraspResult(p.grip, clear)


def palm_goal(hand: HandSpec, palm_location: np.ndarray, obj: GraspObject, grip: str) -> np.ndarray:
    """World pose (4x4) for the palm site of ``hand`` (``palm_location`` its 4x4 in its segment):
    on the grip site's +z axis, ``standoff`` beyond the object's surface, the palm facing the object
    (palm normal along the site's -z) and the fingers along the site's +x, round the long axis."""
    g = GRIP_TYPES[grip]
    site = obj.pose @ obj.grip_site
    r = site[:3, :3]
    loc = palm_location[:3, :3]
    f_local, n_local = loc.T @ hand.fingers, loc.T @ hand.normal
    world = np.stack([r[:, 0], -r[:, 2], np.cross(r[:, 0], -r[:, 2])], axis=1)
    local = np.stack([f_local, n_local, np.cross(f_local, n_local)], axis=1)
    out = np.eye(4)
    out[:3, :3] = world @ local.T
    out[:3, 3] = site[:3, 3] + site[:3, 2] * (obj.half_depth + g.standoff)
    return out
