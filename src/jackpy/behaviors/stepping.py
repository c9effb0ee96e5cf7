"""Active stepping: take a step when losing balance (A1) or when the pelvis is twisted (A2)
([SH4] §4.1.3, §4.2.2, §4.2.4, Fig. 4.6; behaviors.md §2.12).

A1 fires when the balance point comes within ``edge_margin`` of the support polygon's perimeter
(or leaves it). Front or back (0 <= x <= 1): the lighter foot steps; beside a foot (x < 0 or
x > 1): that (support) foot steps, the only one that can widen the base on that side. The new
reference point is the stationary foot's reflected through the balance point, ``r' = 2 b - r_other``,
so the balance point lands in the middle of the new polygon ((x, z) = (0.5, 0)); [proposal] the
step is at most ``max_step`` x leg length and keeps at least ``min_width`` between the feet.

A2 fires when the pelvis yaw differs from the feet's mean yaw by more than ``twist_threshold``
(about 45°): the lighter foot swings round the other, turned 90° in the twist direction, keeping
the stance width; the pelvis-follows-feet behavior then untwists the pelvis.

A step is a motion primitive of ``frames`` iterations: the figure is rooted through the stance
foot, the swing foot's goal (full orientation, heel free) follows an arc of peak ``height``
(smoothstep progress, yaw interpolated), the balance point is held in the world, and on landing
the foot is planted again and the balance parameters are re-read from the new polygon. A
refractory period of ``refractory`` frames follows each step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param
from jackpy.behaviors.pelvis import feet_yaw, pelvis_yaw
from jackpy.behaviors.support import wrap
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
    k: int = 0


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
        if frame.balance_frame().margin(b) < -p.edge_margin:
            return None
        x, _ = st.balance
        swing = ("right" if x < 0.5 else "left") if 0.0 <= x <= 1.0 else ("right" if x > 1.0 else "left")
        other = OTHER[swing]
        ref = {s: frame.loop.foot_reference(s, f.target) for s, f in st.feet.items()}
        new = 2.0 * b - ref[other]
        lateral = ref[swing] - ref[other]
        lateral /= max(np.linalg.norm(lateral), 1e-9)
        width = (new - ref[other]) @ lateral
        if width < p.min_width:
            new = new + (p.min_width - width) * lateral
        d = new - ref[swing]
        longest = p.max_step * frame.anatomy.leg_length
        if np.linalg.norm(d) > longest:
            d *= longest / np.linalg.norm(d)
        end = st.feet[swing].target.copy()
        end[[0, 2], 3] += d
        return self._start(frame, swing, "balance", end)

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

    def _start(self, frame: "Frame", swing: str, kind: str, end: np.ndarray) -> Step:
        st, p = frame.state, self.params
        fs = st.feet[swing]
        turn = wrap(frame.loop.foot_yaw(swing, end) - frame.loop.foot_yaw(swing, fs.target))
        step = Step(swing, kind, fs.target.copy(), end, p.frames, p.height, st.balance_point.copy(),
                    (fs.mode, fs.heel), turn)
        if st.root != OTHER[swing]:
            frame.set_root(OTHER[swing])
        st.root_claimed = True
        fs.mode, fs.heel = "hold", "free"
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
        s.k += 1
        k = min(s.k, s.frames)  # settling frames hold the end pose
        u = _smooth(k / s.frames)
        pose = _yaw_rotate(s.start, s.turn * u)
        pose[:3, 3] = (1 - u) * s.start[:3, 3] + u * s.end[:3, 3] + Y * s.height * np.sin(np.pi * k / s.frames)
        fs = st.feet[s.side]
        fs.target = pose if s.k < s.frames else s.end.copy()
        if st.com_drag is None:
            st.balance_point = s.balance_point
            frame.com_goal = np.array([s.balance_point[0], 0.0, s.balance_point[1]])

    def finish(self, frame: "Frame") -> None:
        s = self.step
        if s is None or s.k < s.frames:
            return
        st = frame.state
        # land only on the floor: the IK may trail the arc's last frames (its budget is per frame),
        # and a foot planted in the air would stay there once it roots the figure
        spec = frame.anatomy.feet[s.side]
        miss = float(np.linalg.norm(frame.site(*spec.ball)[:3, 3] - s.end[:3, 3]))
        if miss > self.params.land_tolerance and s.k < s.frames + self.params.settle:
            return
        fs = st.feet[s.side]
        fs.mode, fs.heel = s.saved
        fs.target = s.end.copy()
        st.root_claimed = False
        frame.invalidate_balance()
        st.balance = frame.balance_frame().params(st.balance_point)
        st.steps_taken += 1
        frame.note(f"{s.kind} step landed: {s.side} foot")
        self.step = None
        self.cooldown = self.params.refractory
