"""Kinematic grasp with Jack's five grip types ([SH4] §4.2.7; behaviors.md §2.13).

Steps: (1) the grasp location is the object's grip site; (2) a per-grip distance offset places the
palm centre; (3) the hand is preshaped; (4) the palm is moved to the site (the hands behavior does
this through the arm pass, :meth:`Grasp.palm_goal` gives the goal); (5) each digit closes, proximal
joint first, until one of the segments it moves touches the object, then the next joint closes.

Contact is tested on points sampled along each digit segment (base to child joint), each a ball of
the digit's radius, against the object's exact signed distance (box or cylinder), which is at
least as tight as the bounding-box test of the book. The contact angle of every joint is found by a
coarse scan then bisection, so the residual penetration is below ``tolerance``.

A digit whose preshape already penetrates the object (a tucked one too) first opens, proximal
joint first, until it is clear. The thumb closes by a grip-specific sequence of its CMC abduction,
CMC flexion, MCP and IP DOFs (:func:`thumb_plan`): in *opposition* (power, precision, tripod) it
swings out of the palm, across, then curls; *laterally* (disc, small disc) it starts abducted
40° beside the object and curls across it (MCP, IP, then CMC flexion).

Grip types ([proposal]; the book names them but gives no poses; tuned on the standard human so
that every contacting digit ends within 1 mm of the object, see tests/behaviors/test_behaviors_grasp.py):

=============  ==============  ===============================================  ==================
grip           digits          preshape (thumb CMC abduction, flexion)          palm centre
=============  ==============  ===============================================  ==================
power          all five        fingers straight, thumb 0°, 15° (thenar on it)   12 mm off surface
precision      thumb, index    fingers 15 %, others tucked, thumb 20°, 0°       7.5 cm off, 2 cm thumbwards
disc           all five        fingers 10 %, thumb lateral 40°, 0°              3.5 cm off the face
small disc     thumb+2         as disc, three digits, object 5 mm thumbwards    3.5 cm off the face
tripod         thumb+2         fingers 20 %, others tucked, thumb 20°, 0°       7.5 cm off, 2 cm thumbwards
=============  ==============  ===============================================  ==================
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
        if self.shape == "cylinder":  # radius across the axis, half the length along it
            c = min(abs(float(self.grip_site[1, 2])), 1.0)
            return 0.5 * self.size[0] * float(np.sqrt(1.0 - c * c)) + 0.5 * self.size[1] * c
        axis = np.abs(self.grip_site[:3, 2])
        return float(0.5 * np.asarray(self.size) @ axis)


@dataclass(frozen=True)
class GripType:
    """One grip ([proposal]; the book gives no poses).

    ``digits`` close (0 = thumb); the fingers' preshape is ``preshape`` of each joint's closing
    range, the digits that do not close are tucked by ``tuck`` of it. The palm centre is placed
    ``standoff`` (m) beyond the object's surface, the object ``along`` (m) further along the fingers
    and ``across`` (m) towards the thumb than the palm centre. The thumb is preshaped at CMC
    ``thumb_cmc`` (abduction, flexion; rad, clipped to the limits) with MCP and IP at ``preshape``,
    and closes by ``thumb_close``: (``"cmc"`` / ``"mcp"`` / ``"ip"``, DOF index, closing sign), in
    order. ``thumb_mode`` names the kind: "opposition" (the thumb swings out of the palm plane and
    its pad faces the fingers) or "lateral" (the thumb stays beside the palm and closes across it).
    """

    digits: tuple[int, ...]
    preshape: float
    tuck: float
    standoff: float
    along: float = 0.0
    across: float = 0.0
    thumb_cmc: tuple[float, float] = (0.0, 0.0)
    thumb_close: tuple[tuple[str, int, float], ...] = (("cmc", 0, 1.0), ("mcp", 0, 1.0), ("ip", 0, 1.0))
    thumb_mode: str = "opposition"


_D = np.radians
#: opposition: the thumb swings out of the palm (CMC abduction), then across (CMC flexion), then curls
OPPOSE = (("cmc", 0, 1.0), ("cmc", 1, 1.0), ("mcp", 0, 1.0), ("ip", 0, 1.0))
#: lateral: the thumb, already out of the palm plane, curls across (MCP, IP), then the CMC flexes across
LATERAL = (("mcp", 0, 1.0), ("ip", 0, 1.0), ("cmc", 1, 1.0))

GRIP_TYPES: dict[str, GripType] = {
    # the thenar eminence (thumb metacarpal) rests on the handle, so the palm centre stays 12 mm off it
    "power": GripType((0, 1, 2, 3, 4), 0.0, 0.0, 0.012, thumb_cmc=(0.0, _D(15.0)), thumb_close=OPPOSE),
    "precision": GripType((0, 1), 0.15, 0.9, 0.075, across=0.02, thumb_cmc=(_D(20.0), 0.0), thumb_close=OPPOSE),
    "disc": GripType((0, 1, 2, 3, 4), 0.1, 0.0, 0.035, thumb_cmc=(_D(40.0), 0.0), thumb_close=LATERAL,
                     thumb_mode="lateral"),
    # retuned to the ANSUR II hand (issue 19): contacts within 1 mm for male P50, female P5 and P50; the
    # male P95's index stops 10 mm short of a 3 cm disc (the offsets are absolute, not scaled to the hand)
    "small disc": GripType((0, 1, 2), 0.1, 0.9, 0.035, across=0.005, thumb_cmc=(_D(40.0), 0.0), thumb_close=LATERAL,
                           thumb_mode="lateral"),
    "tripod": GripType((0, 1, 2), 0.2, 0.9, 0.075, across=0.02, thumb_cmc=(_D(20.0), 0.0), thumb_close=OPPOSE),
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
    contacts: tuple[str, ...] = ()

    @property
    def contact_clearance(self) -> dict[str, float]:
        """Clearance of the digits that close onto the object (the grip's contacts)."""
        return {k: v for k, v in self.clearance.items() if k in self.contacts}

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

    def moving(self, digit_index: int, joint: str) -> list[str]:
        """The digit's segments that ``joint`` moves (its child segment and the distal ones)."""
        segs = self.hand.digits[digit_index].segments
        return segs[segs.index(self.figure.joint(joint).to_seg):]

    def _sweep(self, q: np.ndarray, i: int, limit: float, test, p: GraspParams) -> tuple[np.ndarray, bool]:
        """Move ``q[i]`` towards ``limit`` until ``test(q)`` (a clearance) turns negative: coarse scan,
        then bisection to within ``p.tolerance`` of contact. Returns the new ``q`` and whether it hit."""
        a = q[i]
        step = p.scan_step * np.sign(limit - a) if limit != a else 0.0
        hit = None
        while step and abs(limit - a) > 1e-12:
            b = a + step if abs(step) < abs(limit - a) else limit
            q[i] = b
            if test(q) < 0:
                hit = (a, b)
                break
            a = b
        if hit is None:
            q[i] = limit
            return q, False
        lo, hi = hit
        best = lo
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            q[i] = mid
            c = test(q)
            if -p.tolerance <= c <= 0:
                best = mid
                break
            if c < 0:
                hi = mid
            else:
                lo = best = mid
            if abs(hi - lo) < 1e-7:
                break
        q[i] = best
        return q, True

    def close_digit(self, q: np.ndarray, digit_index: int, p: GraspParams,
                    plan: list[tuple[str, int, float]] | None = None) -> np.ndarray:
        """Close one digit joint by joint (``plan``, by default its flexion DOFs proximal to distal)
        until one of the segments the joint moves touches the object; returns the new ``q``."""
        digit = self.hand.digits[digit_index]
        q = q.copy()
        for joint, dof, sign in plan if plan is not None else digit.flex:
            moving = self.moving(digit_index, joint)
            i = self.slices[joint] + dof
            if self.clearance(q, moving, digit.radius) < 0:
                continue
            limit = _limit_towards(self.figure, joint, dof, sign)
            q, _ = self._sweep(q, i, limit, lambda x, mv=moving: self.clearance(x, mv, digit.radius), p)
        return q

    def open_digit(self, q: np.ndarray, digit_index: int, p: GraspParams,
                   plan: list[tuple[str, int, float]] | None = None) -> np.ndarray:
        """A digit whose preshape already penetrates the object opens, proximal joint first, just
        until it is clear (the closing then starts from contact)."""
        digit = self.hand.digits[digit_index]
        q = q.copy()

        def clear(x: np.ndarray) -> float:
            return self.clearance(x, digit.segments, digit.radius)

        for joint, dof, sign in plan if plan is not None else digit.flex:
            if clear(q) >= -p.tolerance:
                break
            i = self.slices[joint] + dof
            limit = _limit_towards(self.figure, joint, dof, -sign)
            # opening: sweep until the digit is clear, i.e. until -clearance turns negative
            q, _ = self._sweep(q, i, limit, lambda x: -clear(x) - p.tolerance, p)
        return q


def thumb_plan(figure: Figure, hand: HandSpec, grip: str | None) -> list[tuple[str, int, float]]:
    """The thumb's closing sequence for ``grip`` (None: every thumb DOF, proximal first, as used to
    open it) as (joint, DOF index, closing sign). It needs the
    standard human's thumb (CMC with abduction and flexion, MCP, IP); other thumbs (the synthetic
    test figures) close by their flexion DOFs."""
    thumb = hand.digits[0]
    joints = [j for j, _d, _s in thumb.flex]
    if len(joints) != 3 or not joints[0].endswith("thumb_cmc") or figure.joint(joints[0]).ndof < 2:
        return list(thumb.flex)
    names = dict(zip(("cmc", "mcp", "ip"), joints))
    seq = OPPOSE if grip is None else GRIP_TYPES[grip].thumb_close
    return [(names[j], d, s) for j, d, s in seq]


def preshape(figure: Figure, hand: HandSpec, grip: str) -> None:
    """Open the hand to ``grip``'s starting pose: closing digits open by their preshape fraction,
    the others tucked (closed by ``tuck`` of their range) out of the way; the thumb's CMC is set to
    the grip's abduction and flexion."""
    g = GRIP_TYPES[grip]
    for d, digit in enumerate(hand.digits):
        frac = g.preshape if d in g.digits else g.tuck
        for joint, dof, sign in digit.flex:
            jt = figure.joint(joint)
            limit = _limit_towards(figure, joint, dof, sign)
            rest = float(np.clip(0.0, jt.dofs[dof].lower, jt.dofs[dof].upper))
            jt.displacement[dof] = rest + frac * (limit - rest)
    cmc = figure.joint(hand.digits[0].flex[0][0])
    if cmc.name.endswith("thumb_cmc") and cmc.ndof >= 2:
        cmc.displacement[:2] = np.clip(g.thumb_cmc, cmc.lower[:2], cmc.upper[:2])


def close_fingers(figure: Figure, hand: HandSpec, obj: GraspObject, params: GraspParams | None = None) -> GraspResult:
    """Close the grip's digits onto ``obj`` (the palm already placed); sets the figure's joints.

    A digit that penetrates the object after the preshape (a tucked one too) first opens until it
    is clear. The report has every digit's clearance, closing or not."""
    p = params or GraspParams()
    g = GRIP_TYPES[p.grip]
    closer = FingerCloser(figure, hand, obj)
    q = figure.q
    for d in range(len(hand.digits)):
        plan = thumb_plan(figure, hand, p.grip) if d == 0 else None
        q = closer.open_digit(q, d, p, thumb_plan(figure, hand, None) if d == 0 else None)
        if d in g.digits:
            q = closer.close_digit(q, d, p, plan)
    figure.q = q
    clear = {hand.digits[d].name: closer.clearance(q, hand.digits[d].segments, hand.digits[d].radius)
             for d in range(len(hand.digits))}
    return GraspResult(p.grip, clear, tuple(hand.digits[d].name for d in g.digits))


def palm_goal(hand: HandSpec, palm_location: np.ndarray, obj: GraspObject, grip: str) -> np.ndarray:
    """World pose (4x4) for the palm site of ``hand`` (``palm_location`` its 4x4 in its segment):
    ``standoff`` beyond the object's surface along the grip site's +z, moved ``along`` back against
    the fingers and ``across`` away from the thumb side (so the object lies that far distal and
    thumbwards of the palm centre), the palm facing the object (palm normal along the site's -z)
    and the fingers along the site's +x, round the long axis."""
    g = GRIP_TYPES[grip]
    site = obj.pose @ obj.grip_site
    r = site[:3, :3]
    loc = palm_location[:3, :3]
    f_local, n_local = loc.T @ hand.fingers, loc.T @ hand.normal
    world = np.stack([r[:, 0], -r[:, 2], np.cross(r[:, 0], -r[:, 2])], axis=1)
    local = np.stack([f_local, n_local, np.cross(f_local, n_local)], axis=1)
    out = np.eye(4)
    out[:3, :3] = world @ local.T
    out[:3, 3] = (site[:3, 3] + site[:3, 2] * (obj.half_depth + g.standoff) - r[:, 0] * g.along
                  - world[:, 2] * g.across)
    return out
