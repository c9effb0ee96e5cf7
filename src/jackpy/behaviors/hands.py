"""Arms and hands: hand goals, consistent palm orientation, hold, attach and release
([SH4] §4.1.1 Table 4.5, §4.1.2, §4.2.6; behaviors.md §2.5 P4, §2.9, §2.11).

Hand goals are solved in a separate arm pass after the body, moving only that arm's joints, so a
reach does not drag the COM, pelvis or feet ([SH4] §4.1.1). A goal is the palm site's pose
(``state.hands[side].goal``); with ``local`` set it is carried by an object (hold local: the
doorknob model). Objects in ``attached`` are carried by the hand (grab: the screwdriver model).

**Hands maintain consistent orientation** (P4): while the user translates a hand (``rules``) its
orientation is held; when the hand passes into another region (relative to the shoulder, in the
pelvis's facing frame) the orientation goal turns, at most ``max_turn`` per frame, to the
Labanotation default: hanging at the side → palm in; forward or up → palms face each other; out to
the side → palm forward; across the midline → palm backward. Fingers point along the arm.

**Lean** ([proposal], for reaches beyond the arm): while a hand goal with ``lean`` is farther than
the arm can reach and the palm misses it, the body leans towards it: the chest's up direction
(and, by ``lean_pelvis`` of the angle, the pelvis) tilts towards the goal by ``lean_turn`` per
frame, up to ``lean_max``, and the balance point moves ``lean_rate`` per frame towards the goal, so
the stepping behavior catches the figure with a step when the weight reaches the edge of the feet.
The lean is a moving *goal* of the body pass, never a hand goal weighed against balance and torso:
every goal of the body pass stays reachable, and as each frame moves them only a little the body
pass starts each frame nearly solved (a hand goal in the body pass made it run to its iteration
cap every frame, 50-120 ms). The tilt is held while the goal is within reach and returns to
upright at the same rate once the goal is well inside the arm's reach (``lean_release``) or the
hand no longer leans. [decision] The lean advances only while the body keeps up with it: while the
COM is within ``LEAN_FOLLOW`` of the balance point (standing; seated there is no COM goal). After a
whole solve it always is (the COM loop holds it to ``com_tolerance``); when the time box cuts the
body pass short (a loaded machine, the workbench's cheaper rungs), the lean waits for the body
instead of running ahead of it; and a miss after a cut frame is the solves' unfinished work until it
stops shrinking (``LEAN_CONFIRM`` frames without falling below ``LEAN_STALL`` of itself), only then
a reach beyond the arm. Without these, cut frames moved the balance point a centimetre a frame to
the edge of the feet, the figure took a balance step and the released hand ended 10-30 cm off its
goal.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from jackpy.behaviors.base import BehaviorBase, param
from jackpy.behaviors.support import floor
from jackpy.ik.goals import Orientation, Position
from jackpy.peabody.transforms import rotation_matrix

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame

UP = np.array([0.0, 1.0, 0.0])
REGIONS = ("down", "forward", "side", "across")
#: how far inside the support polygon's edge (m) a lean leaves the balance point
LEAN_INSIDE = 0.005
#: the lean advances only while the COM is this close (m, on the floor) to the balance point
LEAN_FOLLOW = 0.01
#: after frames the time box cut, a miss leans only once it has stayed at least ``LEAN_STALL`` of
#: what it was ``LEAN_CONFIRM`` frames before (it stopped shrinking: a reach beyond the arm)
LEAN_CONFIRM, LEAN_STALL = 5, 0.9


@dataclass
class HandsParams:
    orientation_rules: bool = param(True, "hands maintain consistent orientation (P4) while translated")
    max_turn: float = param(np.radians(10.0), "largest turn of a hand's orientation goal per frame", "deg",
                            (0.0, np.pi))
    weight: float = param(1.0, "weight of the hand position goals", "", (0.0, 1e4))
    orientation_weight: float = param(0.1, "weight of the hand orientation goals", "", (0.0, 1e4))
    lean_weight: float = param(0.5, "weight of an out-of-reach hand goal on the body", "", (0.0, 1e4))
    track_arm: bool = param(True, "while translated, the palm keeps its region's rule as the arm swings "
                            "(fingers along the shoulder-to-hand line), so the goal stays reachable")
    orientation_level: int = param(1, "priority level of an orientation the user gave (rotate hand, hand on "
                                   "site): below the position (0), so an unreachable orientation never "
                                   "pulls the palm off its point", "", (0, 3))
    rules_level: int = param(0, "priority level of the orientation the palm rules pick (reachable by "
                             "construction, so weighed with the position: cheaper)", "", (0, 3))
    lean_rate: float = param(0.01, "balance-point shift per frame towards an out-of-reach goal", "cm",
                             (0.0, 0.1))
    lean_turn: float = param(np.radians(1.5), "largest change of the body's lean per frame", "deg",
                             (0.0, np.radians(20.0)))
    lean_max: float = param(np.radians(40.0), "largest lean of the chest from vertical for an out-of-reach "
                            "goal", "deg", (0.0, np.radians(80.0)))
    lean_pelvis: float = param(0.5, "share of the lean taken by the pelvis (hips), the rest by the spine",
                               "", (0.0, 1.0))
    lean_release: float = param(0.9, "the lean returns to upright once the goal is nearer the shoulder than "
                                "this x arm length", "", (0.5, 0.97))


def turn_towards(r: np.ndarray, target: np.ndarray, max_angle: float) -> tuple[np.ndarray, float]:
    """Rotate 3x3 ``r`` towards ``target`` by at most ``max_angle`` (rad); returns it and the angle left."""
    d = target @ r.T
    angle = float(np.arccos(np.clip((np.trace(d) - 1.0) / 2.0, -1.0, 1.0)))
    if angle < 1e-9:
        return target.copy(), 0.0
    axis = np.array([d[2, 1] - d[1, 2], d[0, 2] - d[2, 0], d[1, 0] - d[0, 1]])
    n = np.linalg.norm(axis)
    if n < 1e-9:  # half turn: any axis perpendicular works
        w, v = np.linalg.eigh(d + d.T)
        axis, n = v[:, -1], 1.0
    step = min(angle, max_angle)
    return rotation_matrix(axis / n, step) @ r, angle - step


def frame_from(fingers: np.ndarray, normal: np.ndarray, f_local: np.ndarray, n_local: np.ndarray) -> np.ndarray:
    """3x3 rotation taking local ``f_local``/``n_local`` to world ``fingers``/``normal`` (normal
    made perpendicular to fingers)."""
    a = fingers / np.linalg.norm(fingers)
    b = normal - (normal @ a) * a
    b /= np.linalg.norm(b)
    world = np.stack([a, b, np.cross(a, b)], axis=1)
    local = np.stack([f_local, n_local, np.cross(f_local, n_local)], axis=1)
    return world @ local.T


class Hands(BehaviorBase):
    """Hand goals for the arm passes; palm orientation rules; attachments; lean for far reaches."""

    name = "hands"
    order = 80

    def __init__(self, params: HandsParams | None = None, enabled: bool = True) -> None:
        super().__init__(params or HandsParams(), enabled)
        #: the body's lean: floor vector, direction of the lean times its angle (rad)
        self.lean = np.zeros(2)
        #: per hand: its misses (m) over the last cut frames, newest last (cleared by a whole solve)
        self._misses: dict[str, list[float]] = {}
        #: per hand: whether it leans this frame (decided once per frame by :meth:`_update_lean`)
        self._leaning: dict[str, bool] = {}

    def _far_miss(self, frame: "Frame", side: str, miss: float, reach: float) -> bool:
        """Whether a palm ``miss`` (m) of a goal at ``reach`` (arm lengths from the shoulder) is a
        reach beyond the arm: farther than 0.97, missed by over 1 cm and, after a frame the time box
        cut, no longer shrinking (module docstring). Called once per hand and frame."""
        if reach <= 0.97 or miss <= 0.01:
            self._misses.pop(side, None)
            return False
        if not frame.cut:
            self._misses.pop(side, None)
            return True
        seen = self._misses.setdefault(side, [])
        seen.append(miss)
        del seen[:-(LEAN_CONFIRM + 1)]
        return len(seen) > LEAN_CONFIRM and miss >= LEAN_STALL * seen[0]

    def region(self, frame: "Frame", side: str, point: np.ndarray) -> str:
        """P4 region of a palm position (world) for hand ``side``."""
        a = frame.anatomy
        pel = frame.site(a.pelvis, a.pelvis_site)
        fwd = pel[:3, :3] @ (frame.figure.site_location(a.pelvis, a.pelvis_site)[:3, :3].T @ a.pelvis_forward)
        fwd = fwd - (fwd @ UP) * UP
        fwd /= np.linalg.norm(fwd)
        left = np.cross(UP, fwd)
        out = left if side == "left" else -left
        if (point - pel[:3, 3]) @ out < 0.0:
            return "across"
        v = point - frame.site(*a.hands[side].shoulder)[:3, 3]
        n = max(np.linalg.norm(v), 1e-9)
        if v @ UP < -0.7 * n:
            return "down"
        if v @ out > v @ fwd and v @ out > 0.0:
            return "side"
        return "forward"

    def canonical(self, frame: "Frame", side: str, point: np.ndarray, region: str) -> np.ndarray:
        """Palm-site world rotation of the Labanotation default for ``region``."""
        a = frame.anatomy
        h = a.hands[side]
        pel = frame.site(a.pelvis, a.pelvis_site)
        fwd = pel[:3, :3] @ (frame.figure.site_location(a.pelvis, a.pelvis_site)[:3, :3].T @ a.pelvis_forward)
        fwd = fwd - (fwd @ UP) * UP
        fwd /= np.linalg.norm(fwd)
        left = np.cross(UP, fwd)
        out = left if side == "left" else -left
        normal = {"down": -out, "forward": -out, "side": fwd, "across": -fwd}[region]
        arm = point - frame.site(*h.shoulder)[:3, 3]
        if abs(arm @ normal) > 0.95 * np.linalg.norm(arm):
            arm = arm + 0.3 * np.linalg.norm(arm) * (UP if region != "down" else -UP)
        loc = frame.figure.site_location(*h.palm)[:3, :3]
        return frame_from(arm, normal, loc.T @ h.fingers, loc.T @ h.normal)

    def update(self, frame: "Frame") -> None:
        st, a, p = frame.state, frame.anatomy, self.params
        for side, hs in st.hands.items():
            if hs.local is not None:
                hs.goal = hs.local.pose @ hs.local_offset
            if hs.goal is None:
                continue
            h = a.hands[side]
            palm = f"{h.palm[0]}.{h.palm[1]}"
            if p.orientation_rules and hs.rules:
                reg = self.region(frame, side, hs.goal[:3, 3])
                if reg != hs.region:
                    hs.region, hs.blending = reg, True
                if hs.blending or p.track_arm:
                    target = self.canonical(frame, side, hs.goal[:3, 3], reg)
                    hs.goal[:3, :3], left = turn_towards(hs.goal[:3, :3], target, p.max_turn)
                    hs.blending = left > 0.0
            frame.arms[side].append((Position(palm, hs.goal, weight=p.weight, name=f"hand {side}"), 0))
            if hs.orient:
                frame.arms[side].append((Orientation(palm, hs.goal[:3, :3], weight=p.orientation_weight,
                                                     name=f"hand frame {side}"),
                                        p.rules_level if hs.rules and p.orientation_rules else p.orientation_level))
        self._lean_goals(frame)

    def _lean_goals(self, frame: "Frame") -> None:
        """Tilt this frame's chest-up and pelvis goals (made by the torso and pelvis behaviors, which
        run before) by the current lean."""
        angle = float(np.linalg.norm(self.lean))
        if angle < 1e-9:
            return
        a, p = frame.anatomy, self.params
        d = self.lean / angle
        axis = np.cross(UP, np.array([d[0], 0.0, d[1]]))  # tilting up towards d
        chest_rot = rotation_matrix(axis, angle)[:3, :3]
        pelvis_rot = rotation_matrix(axis, p.lean_pelvis * angle)[:3, :3]
        for i, (g, lv) in enumerate(frame.body):
            name = getattr(g, "name", None)
            if name == "chest up":
                w = g.weight
                frame.body[i] = (frame.keep_direction(*a.chest, a.chest_up, chest_rot @ UP, w, "chest up"), lv)
            elif name == "pelvis" and isinstance(g, Orientation):
                frame.body[i] = (Orientation(g.site_name, pelvis_rot @ g.target, weight=g.weight, name="pelvis"), lv)
            elif name == "chest" and isinstance(g, Orientation):  # hold global orientation
                frame.body[i] = (Orientation(g.site_name, chest_rot @ g.target, weight=g.weight, name="chest"), lv)

    @staticmethod
    def _body_keeps_up(frame: "Frame") -> bool:
        """Whether the solved posture's COM is within ``LEAN_FOLLOW`` of this frame's COM goal (the
        balance point); True without one (seated: the pelvis carries the figure)."""
        goal = frame.com_goal
        return goal is None or float(np.linalg.norm(floor(frame.com) - floor(goal))) <= LEAN_FOLLOW

    def _update_lean(self, frame: "Frame") -> None:
        """Move the lean a step towards the leaning hands' goals (while the body keeps up with it),
        hold it, or let it go upright."""
        st, a, p = frame.state, frame.anatomy, self.params
        want, hold = np.zeros(2), False
        self._leaning = {}
        for side, hs in st.hands.items():
            if hs.goal is None or not hs.lean:
                self._misses.pop(side, None)
                continue
            shoulder = frame.site(*a.hands[side].shoulder)[:3, 3]
            reach = float(np.linalg.norm(hs.goal[:3, 3] - shoulder)) / frame.loop.arm_length(side)
            palm = frame.site(*a.hands[side].palm)[:3, 3]
            self._leaning[side] = self._far_miss(frame, side, float(np.linalg.norm(hs.goal[:3, 3] - palm)), reach)
            if self._leaning[side]:
                d = floor(hs.goal[:3, 3] - shoulder)
                if np.linalg.norm(d) > 1e-6:
                    want += d / np.linalg.norm(d)
            elif reach > p.lean_release:
                hold = True
        n = float(np.linalg.norm(want))
        if n > 1e-9 and not self._body_keeps_up(frame):
            return
        if n > 1e-9:
            target = p.lean_max * want / n
        elif hold:
            return
        else:
            target = np.zeros(2)
        delta = target - self.lean
        dn = float(np.linalg.norm(delta))
        if dn > p.lean_turn:
            delta *= p.lean_turn / dn
        self.lean = self.lean + delta

    def finish(self, frame: "Frame") -> None:
        st, a, p = frame.state, frame.anatomy, self.params
        self._update_lean(frame)
        for side, hs in st.hands.items():
            palm = frame.site(*a.hands[side].palm)
            for att in hs.attached:
                att.obj.pose = palm @ att.offset
            if hs.goal is None or not hs.lean or st.com_drag is not None:
                continue
            miss = hs.goal[:3, 3] - palm[:3, 3]
            if self._leaning.get(side) and self._body_keeps_up(frame):
                d = floor(miss)
                bf = frame.balance_frame()
                if np.linalg.norm(d) > 1e-6:
                    b0 = st.balance_point
                    step = p.lean_rate * d / np.linalg.norm(d)
                    b = b0 + step
                    # the weight never leaves the feet by leaning: it stops LEAN_INSIDE inside the
                    # polygon's edge (stepping, when on, fires before that and widens the base)
                    if bf.margin(b) > -LEAN_INSIDE and bf.margin(b) > bf.margin(b0):
                        lo, hi = 0.0, 1.0
                        for _ in range(12):
                            mid = 0.5 * (lo + hi)
                            lo, hi = (mid, hi) if bf.margin(b0 + mid * step) <= -LEAN_INSIDE else (lo, mid)
                        b = b0 + lo * step
                    st.balance = bf.params(b)
                    st.balance_point = b
