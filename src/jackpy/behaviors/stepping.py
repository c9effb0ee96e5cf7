"""Active stepping: take a step when losing balance (A1) or when the pelvis is twisted (A2)
([SH4] §4.1.3, §4.2.2, §4.2.4, Fig. 4.6; behaviors.md §2.12).

A1 fires when the balance point comes within ``edge_margin`` of the support polygon's perimeter
(or leaves it). Front or back (0 <= x <= 1): the lighter foot steps; beside a foot (x < 0 or
x > 1): that (support) foot steps, the only one that can widen the base on that side. The new
reference point is the stationary foot's reflected through the balance point, ``r' = 2 b - r_other``,
so the balance point lands in the middle of the new polygon ((x, z) = (0.5, 0)); [proposal] the
step is at most ``max_step`` x leg length and keeps at least ``min_width`` between the feet (the
footstep rule :func:`jackpy.locomotion.stepper.constrain_landing`, which the incremental walker
shares). The footstep is obtained through the incremental walker's next-footstep interface: the
decision feeds a :class:`~jackpy.locomotion.stepper.Balance` source and a footsteps-only
:class:`~jackpy.locomotion.stepper.Stepper` from the feet as they stand asks it for the swing foot's
footstep; this behavior then swings the foot.

A2 fires when the pelvis yaw differs from the feet's mean yaw by more than ``twist_threshold``
(about 45°): the lighter foot swings round the other, turned 90° in the twist direction, keeping
the stance width; the pelvis-follows-feet behavior then untwists the pelvis.

A step is a motion primitive in three phases, as a person steps ([SH4] §4.4.6; behaviors.md
§2.12 "step execution"):

1. **weight shift** (``shift_frames``): the figure is rooted through the stance foot and, both feet
   still planted, the COM goal moves from where it is to a point over the stance foot
   (``stance_margin`` inside its footprint, the nearest such point to the balance point);
2. **swing** (``frames``, plus up to ``settle`` frames for the foot to reach the floor): the swing
   foot's goal (full orientation, heel free) follows an arc of peak ``height`` (smoothstep
   progress, yaw interpolated) while the COM stays over the stance foot, the only support;
3. **weight transfer** (``transfer_frames``): the foot is planted again, the balance parameters are
   re-read from the new polygon, and the COM goal moves from the stance foot to the balance point
   in the middle of the new polygon (or to where the user drags it).

The step owns the COM goal from start to end (a COM drag or a lean resumes after it), so the COM
never hangs beyond the single foot that carries it. A refractory period of ``refractory`` frames
follows each step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param
from jackpy.behaviors.feet import FOOT_GOALS, replace_foot_goals
from jackpy.behaviors.hands import turn_towards
from jackpy.behaviors.pelvis import feet_yaw, pelvis_yaw
from jackpy.behaviors.support import convex_hull, floor, signed_distance, wrap
from jackpy.locomotion.stepper import Balance, Stepper
from jackpy.locomotion.walk_path import Footstep
from jackpy.peabody.transforms import rotation_matrix

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame

Y = np.array([0.0, 1.0, 0.0])
OTHER = {"left": "right", "right": "left"}


@dataclass
class SteppingParams:
    on_balance: bool = param(True, "take a step when losing balance (A1)")
    on_twist: bool = param(True, "take a step when the pelvis is twisted (A2)")
    edge_margin: float = param(0.01, "step when the balance point is this close to the polygon edge", "cm",
                               (0.0, 0.1))
    twist_threshold: float = param(np.radians(45.0), "pelvis twist relative to the feet that forces a step",
                                   "deg", (np.radians(10.0), np.radians(90.0)))
    frames: int = param(10, "duration of a step in frames", "", (2, 100))
    height: float = param(0.06, "peak height of the swing foot's arc", "cm", (0.0, 0.3))
    max_step: float = param(0.7, "longest step as a fraction of leg length", "", (0.1, 1.2))
    min_width: float = param(0.12, "least sideways distance between the feet after a step", "cm", (0.0, 0.5))
    refractory: int = param(2, "frames after a step before another may start", "", (0, 100))
    settle: int = param(6, "extra frames a step may take for the foot to reach the floor before it lands",
                        "", (0, 50))
    land_tolerance: float = param(0.001, "distance from its end pose at which the swing foot has landed",
                                  "mm", (1e-4, 0.02))
    shift_frames: int = param(2, "frames to shift the weight over the stance foot before the swing foot lifts",
                              "", (0, 50))
    transfer_frames: int = param(2, "frames to move the weight from the stance foot to the middle of the new "
                                 "support polygon after landing", "", (0, 50))
    peel: float = param(0.4, "part of the swing during which the foot's orientation is free (it peels off "
                        "the floor); then it is carried flat to its landing pose", "", (0.0, 0.9))
    lead: float = param(0.05, "how far beyond the balance point (away from the feet) a balance step centres "
                        "the new support polygon", "cm", (0.0, 0.2))
    stance_margin: float = param(0.02, "how far inside the stance foot's footprint the COM is held during the "
                                 "swing", "cm", (0.0, 0.1))


@dataclass
class Step:
    """A running step: the swing foot's start and end ball-site poses, progress, saved modes."""

    side: str
    kind: str
    start: np.ndarray
    end: np.ndarray
    frames: int
    height: float
    balance_point: np.ndarray
    saved: tuple[str, str]
    turn: float
    origin: np.ndarray
    stance_point: np.ndarray
    peel: float = 0.4
    shift: int = 0
    transfer: int = 0
    k: int = 0
    landed: int = 0

    @property
    def swinging(self) -> bool:
        """Whether the swing foot is off the floor (between lift-off and landing)."""
        return self.k > self.shift and not self.landed


#: rows of the loop's footprint corners (heel, ball, toe tip; two each) that carry the weight of a
#: figure standing on one foot: heel to ball. [proposal] Over the toes alone the stance ankle runs out
#: of dorsiflexion and the COM cannot be held there kinematically.
CARRY_ROWS = slice(0, 4)


def foot_polygon(frame: "Frame", side: str, target: np.ndarray, rows: slice = CARRY_ROWS) -> np.ndarray:
    """Floor polygon (CCW) of the part of foot ``side``'s footprint that can carry the figure
    (heel to ball; ``rows=slice(0, 6)`` for the whole sole) with its ball site at pose ``target``."""
    pts = frame.loop._footprints[side][rows] @ target[:3, :3].T + target[:3, 3]
    return convex_hull(floor(pts))


def carry_polygon(frame: "Frame") -> np.ndarray:
    """Floor polygon of both feet's heel-to-ball regions at their goals: where the COM can go and
    still be carried by one foot once the other lifts. Balance steps fire at its edge."""
    pts = [foot_polygon(frame, s, f.target) for s, f in frame.state.feet.items()]
    return convex_hull(np.vstack(pts))


def point_over_foot(frame: "Frame", side: str, target: np.ndarray, b: np.ndarray, margin: float) -> np.ndarray:
    """The floor point nearest ``b`` that lies at least ``margin`` inside foot ``side``'s footprint
    (Dykstra's projection onto the footprint's edges moved ``margin`` inwards); the foot's
    reference point when the footprint is narrower than that."""
    hull = foot_polygon(frame, side, target)
    ref = frame.loop.foot_reference(side, target)
    b = np.asarray(b, dtype=float)
    if len(hull) < 3 or signed_distance(ref, hull) > -margin:
        return ref
    e = np.roll(hull, -1, axis=0) - hull
    n = np.stack([-e[:, 1], e[:, 0]], axis=1) / np.linalg.norm(e, axis=1)[:, None]  # inward (CCW hull)
    c = (n * hull).sum(axis=1) + margin  # n . p >= c inside the shrunken footprint
    p = b.copy()
    fix = np.zeros((len(hull), 2))
    for _ in range(100):
        moved = 0.0
        for i in range(len(hull)):
            y = p + fix[i]
            q = y + max(0.0, c[i] - n[i] @ y) * n[i]
            fix[i] = y - q
            moved = max(moved, float(np.abs(q - p).max()))
            p = q
        if moved < 1e-7:
            break
    return p


def _below_balance(frame: "Frame", side: str) -> None:
    """Put the swinging foot's goals one priority level below the COM goal: the weight stays over
    the stance sole and the foot takes the path the leg can give it from there (issue 19: with the
    swing foot above the COM, a long step dragged the COM up to 9 cm off the stance foot)."""
    names = {f"{n} {side}" for n in FOOT_GOALS}
    below = frame.com_level + 1
    frame.body[:] = [(g, max(lv, below) if getattr(g, "name", None) in names else lv) for g, lv in frame.body]


def _smooth(u: float) -> float:
    return u * u * (3.0 - 2.0 * u)


def _yaw_rotate(pose: np.ndarray, angle: float) -> np.ndarray:
    out = pose.copy()
    out[:3, :3] = rotation_matrix(Y, angle) @ pose[:3, :3]
    return out


class Stepping(BehaviorBase):
    """Watches the balance point and the pelvis twist; runs one step at a time."""

    name = "stepping"
    order = 50

    def __init__(self, params: SteppingParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or SteppingParams(), enabled)
        self.step: Step | None = None
        self.cooldown = 0

    # ----- planning ----------------------------------------------------------------------------
    def balance_step(self, frame: "Frame") -> Step | None:
        """The A1 step for the current balance point, or None when it is well inside the polygon."""
        st, p = frame.state, self.params
        b = st.balance_point
        # [proposal] at the edge of the feet's heel-to-ball region rather than of the whole sole:
        # the step's weight shift then moves the COM sideways over the stance foot, barely back
        if signed_distance(b, carry_polygon(frame)) < -p.edge_margin:
            return None
        ref = {s: frame.loop.foot_reference(s, f.target) for s, f in st.feet.items()}
        bf = frame.balance_frame()
        facing = bf.facing / max(float(np.linalg.norm(bf.facing)), 1e-12)
        d = b - 0.5 * (ref["left"] + ref["right"])
        along = abs(float(d @ facing))
        across = abs(float(d @ np.array([-facing[1], facing[0]])))
        far = max(ref, key=lambda s: float(np.linalg.norm(b - ref[s])))
        # [proposal] front or back of the feet (the figure's facing, not the balance line's normal,
        # which turns diagonal when the feet are staggered): the foot farther from the balance point
        # (the lighter, trailing one) steps, as in walking; beside the feet: the nearer (support)
        # foot steps outwards, the only one that widens the base on that side
        swing = far if along >= across else OTHER[far]
        other = OTHER[swing]
        # [proposal] the weight is on its way out (the step fires at the heel-to-ball region's edge,
        # short of the toes): the new polygon is centred ``lead`` further on, where it is going
        dn = float(np.linalg.norm(d))
        if dn > 1e-9:
            b = b + p.lead * d / dn
        # the footstep through the incremental walker's next-footstep interface (one stepper for
        # sensor-driven and scripted stepping): the decision feeds a Balance source, the stepper
        # asks it for the swing foot's footstep (landed by the shared rule constrain_landing)
        source = Balance(p.min_width, p.max_step * frame.anatomy.leg_length)
        source.proposed = 2.0 * b - ref[other]
        yaw = {s: frame.loop.foot_yaw(s, st.feet[s].target) for s in (swing, other)}
        standing = [Footstep(float(ref[s][0]), float(ref[s][1]), yaw[s], s) for s in (swing, other)]
        new = Stepper(None, standing, source).next_footstep().point
        d = new - ref[swing]
        end = st.feet[swing].target.copy()
        end[[0, 2], 3] += d
        return self._start(frame, swing, "balance", end, b)

    def twist_step(self, frame: "Frame") -> Step | None:
        """The A2 step when the pelvis is twisted past the threshold, else None."""
        st, a = frame.state, frame.anatomy
        pel = pelvis_yaw(frame, frame.site(a.pelvis, a.pelvis_site)[:3, :3])
        # [proposal] relative to the rooted (stance) foot when there is one: a pivoting free foot
        # turns along with the pelvis, so the mean of the feet would see only half the twist
        ref_yaw = (frame.loop.foot_yaw(st.root, st.feet[st.root].target) if st.root in st.feet
                   else feet_yaw(frame))
        twist = wrap(pel - ref_yaw)
        if abs(twist) <= self.params.twist_threshold or abs(wrap(pel - feet_yaw(frame))) <= self.params.twist_threshold / 2:
            return None  # (the second test: the feet already straddle the pelvis, e.g. after a pivot step)
        x, _ = st.balance
        swing = "right" if x < 0.5 else "left"
        other = OTHER[swing]
        if st.root in st.feet and st.root != OTHER[swing]:
            swing, other = OTHER[st.root], st.root
        turn = float(np.sign(twist)) * np.pi / 2
        ref = {s: frame.loop.foot_reference(s, f.target) for s, f in st.feet.items()}
        off = ref[swing] - ref[other]
        c, s = np.cos(turn), np.sin(turn)
        new_ref = ref[other] + np.array([c * off[0] + s * off[1], -s * off[0] + c * off[1]])
        # the swing foot lands turned 90° from the stance foot (it may have pivoted part-way already)
        have = wrap(frame.loop.foot_yaw(swing, st.feet[swing].target) - frame.loop.foot_yaw(other, st.feet[other].target))
        end = _yaw_rotate(st.feet[swing].target, wrap(turn - have))
        now_ref = frame.loop.foot_reference(swing, end)
        end[[0, 2], 3] += new_ref - now_ref
        return self._start(frame, swing, "twist", end)

    def _start(self, frame: "Frame", swing: str, kind: str, end: np.ndarray,
               centre: np.ndarray | None = None) -> Step:
        st, p = frame.state, self.params
        fs = st.feet[swing]
        stance = OTHER[swing]
        turn = wrap(frame.loop.foot_yaw(swing, end) - frame.loop.foot_yaw(swing, fs.target))
        origin = floor(frame.com) if frame.com_goal is None else floor(frame.com_goal)
        stance_point = point_over_foot(frame, stance, st.feet[stance].target, st.balance_point, p.stance_margin)
        centre = st.balance_point.copy() if centre is None else np.asarray(centre, dtype=float).copy()
        step = Step(swing, kind, fs.target.copy(), end, p.frames, p.height, centre,
                    (fs.mode, fs.heel), turn, origin, stance_point, p.peel, p.shift_frames,
                    p.transfer_frames)
        if st.root != stance:
            # re-rooted after the feet behavior ran this frame: the new root needs no goals, and the
            # former root must be held from this very frame, or it is free for a frame and flies
            frame.set_root(stance)
            replace_foot_goals(frame, stance, hold=False)
            replace_foot_goals(frame, swing, hold=True)
        st.root_claimed = True
        frame.note(f"{kind} step: {swing} foot")
        return step

    # ----- running -----------------------------------------------------------------------------
    def update(self, frame: "Frame") -> None:
        p = self.params
        if self.step is None:
            if self.cooldown > 0:
                self.cooldown -= 1
                return
            if p.on_balance and frame.state.root != "pelvis":
                self.step = self.balance_step(frame)
            if self.step is None and p.on_twist and frame.state.root != "pelvis":
                self.step = self.twist_step(frame)
            if self.step is None:
                return
        self._advance(frame)

    def _advance(self, frame: "Frame") -> None:
        st, s = frame.state, self.step
        # where the balance behavior put the weight this frame (the user's drag, or the stored
        # (x, z) on the feet): the weight goes there once the foot has landed
        wanted = floor(frame.com_goal) if frame.com_goal is not None else st.balance_point
        if st.com_drag is None:
            st.balance_point = s.balance_point
            wanted = s.balance_point
        if s.landed:
            s.landed += 1
            u = _smooth(min(1.0, (s.landed - 1) / max(s.transfer, 1)))
            goal = (1 - u) * s.stance_point + u * wanted
        else:
            s.k += 1
            if s.k <= s.shift:  # weight shift, both feet planted
                goal = s.origin + _smooth(s.k / s.shift) * (s.stance_point - s.origin)
            else:
                j = min(s.k - s.shift, s.frames)  # settling frames hold the end pose
                fs = st.feet[s.side]
                # the foot peels off (orientation free: a trailing foot lifted flat would pull the
                # hip against its extension limit), then is carried in full orientation to land
                fs.mode, fs.heel = ("free" if j <= s.peel * s.frames else "hold"), "free"
                u = _smooth(j / s.frames)
                pose = _yaw_rotate(s.start, s.turn * u)
                pose[:3, 3] = (1 - u) * s.start[:3, 3] + u * s.end[:3, 3] + Y * s.height * np.sin(np.pi * j / s.frames)
                if j < s.frames and fs.mode == "hold":
                    # from the orientation the peeled-off foot has now, turned evenly to the landing
                    # one over the frames left (a goal the leg can follow within a frame)
                    now = frame.site(*frame.anatomy.feet[s.side].ball)[:3, :3]
                    d = pose[:3, :3] @ now.T
                    angle = float(np.arccos(np.clip((np.trace(d) - 1.0) / 2.0, -1.0, 1.0)))
                    pose[:3, :3] = turn_towards(now, pose[:3, :3], angle / (s.frames - j + 1))[0]
                if s.k - s.shift > s.frames and s.kind == "balance":
                    # settling: with the weight held over the stance sole the leg may fall short of
                    # the planned landing; the foot then comes straight down where it is (a
                    # shorter step) instead of snapping the body to the far end pose on landing
                    ball = frame.site(*frame.anatomy.feet[s.side].ball)[:3, 3]
                    s.end[[0, 2], 3] = ball[[0, 2]]
                fs.target = pose if j < s.frames else s.end.copy()
                replace_foot_goals(frame, s.side, hold=True)
                if s.kind == "balance":  # a pivot (twist) step is short and must turn the foot fully
                    _below_balance(frame, s.side)
                goal = s.stance_point
        frame.com_goal = np.array([goal[0], 0.0, goal[1]])

    def finish(self, frame: "Frame") -> None:
        s = self.step
        if s is None:
            return
        st = frame.state
        if s.landed:
            if s.landed > s.transfer:
                self.step = None
                self.cooldown = self.params.refractory
            return
        if s.k - s.shift < s.frames:
            return
        # land only on the floor: the IK may trail the arc's last frames (its budget is per frame),
        # and a foot planted in the air would stay there once it roots the figure
        spec = frame.anatomy.feet[s.side]
        miss = float(np.linalg.norm(frame.site(*spec.ball)[:3, 3] - s.end[:3, 3]))
        if miss > self.params.land_tolerance and s.k - s.shift < s.frames + self.params.settle:
            return
        fs = st.feet[s.side]
        fs.mode, fs.heel = s.saved
        fs.target = s.end.copy()
        st.root_claimed = False
        frame.invalidate_balance()
        st.balance = frame.balance_frame().params(s.balance_point if st.com_drag is None else st.balance_point)
        st.steps_taken += 1
        frame.note(f"{s.kind} step landed: {s.side} foot")
        s.landed = 1
        if s.transfer <= 0:
            self.step = None
            self.cooldown = self.params.refractory
