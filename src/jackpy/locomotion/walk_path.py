"""Walking any planar footstep sequence ([SH5] §5.2.3; digest §2.8.4): the gait profiles of
:mod:`.walk_gait` laid onto the footsteps.

- **footsteps** ``Σ = {σ_i}``: ankle floor point ``(x, z)``, heading ``psi`` and side; σ_0, σ_1
  are the standing feet, each later σ_j is reached by swinging that foot from its previous one;
- **timing**: step j (heel strike of σ_{j-1} to that of σ_j) lasts ``1/sf``; double support is
  the first ``2·DOUBLE_SUPPORT`` of it, then the swing;
- **stance foot**: rolls about its heel to foot-flat, stays flat, rolls about the ball of the foot
  to toe-off (the toes stay on the floor);
- **swing ankle**: top view on the book's quadratic Bézier D1 (ankle at toe-off), D2 (the stance
  ankle mirrored across the walking line), D3 (ankle at heel strike); on a straight path the three
  are collinear and the curve is the straight 1-D travel; height from the 1-D profile; its heading
  turns from toe-off to heel strike by the book's parabolic twist decay (5.16);
- **centre site** (pelvis centre): a C¹ cubic Hermite from the mid-foot point at one heel strike to
  the next, tangents along the mean foot heading with the chord as magnitude (a straight, uniform
  path gives the straight line at uniform speed), swaying toward the stance foot; the pelvis faces
  along the path tangent and stays upright; its height is the book's hip-height rule (5.14): the
  stance leg keeps the length ω(t) it has at that moment in the underlying 1-D walk
  (:meth:`Walk.underlying`, whose height is Boulic's profile, lowered where a leg would have to
  stretch beyond ``MAX_LEG`` of its length).

All positions world metres, y up.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.locomotion.walk_gait import (DOUBLE_SUPPORT, FOOT_FLAT, HEEL_OFF, MAX_LEG, MAX_PITCH, PITCH_HS, PITCH_TO,
                                         SIDES, START_TIME, STOP_TIME, SWAY_CROSSING, TOES_RELEASE, GaitParams,
                                         foot_transform, pelvis_drop, rot_y, smooth, swing_lift, swing_pitch)


#: a step whose centre site travels more than this from the feet's heading (rad), over more than
#: SHUFFLE_MIN (m), is a sideways or backwards step
SHUFFLE_ANGLE = np.radians(60.0)
SHUFFLE_MIN = 0.05


@dataclass
class Footstep:
    """One foot placement: ankle floor point (m), heading (rad), ``"left"``/``"right"``."""

    x: float
    z: float
    psi: float
    side: str

    @property
    def point(self) -> np.ndarray:
        return np.array([self.x, self.z])


@dataclass
class FrameTargets:
    """What the solver must achieve at one frame (world, m, rad)."""

    pelvis: np.ndarray  # 4x4 of the pelvis centre (root) frame
    feet: dict[str, np.ndarray]  # side -> 4x4 floor frame of the foot
    toes_flat: dict[str, float]  # 1: toes flat (bent at the ball joint), 0: straight with the foot
    arm: dict[str, float]  # side -> shoulder swing (rad, + forward)
    phase: dict[str, str]  # side -> "heel" | "flat" | "ball" | "swing"


def landing_times(steps: list[Footstep], p: GaitParams) -> np.ndarray:
    """Heel-strike time of every footstep (σ_0, σ_1: 0, standing)."""
    t = np.zeros(len(steps))
    for j in range(2, len(steps)):
        t[j] = (START_TIME if j == 2 else t[j - 1]) + p.step_time
    return t


def duration(steps: list[Footstep], p: GaitParams) -> float:
    land = landing_times(steps, p)
    return float(land[-1] + STOP_TIME) if len(steps) > 2 else START_TIME + STOP_TIME


def _ankle(p: GaitParams, T: np.ndarray, side: str) -> np.ndarray:
    a = p.foot.ankle * np.array([-1.0 if side == "right" else 1.0, 1.0, 1.0])
    return T[:3, :3] @ a + T[:3, 3]


def _frame(a: float) -> np.ndarray:
    """Top-view (x, z) frame of heading ``a``: columns forward and left."""
    return np.array([[np.sin(a), np.cos(a)], [np.cos(a), -np.sin(a)]])


def _angle_lerp(a: float, b: float, s: float) -> float:
    d = (b - a + np.pi) % (2.0 * np.pi) - np.pi
    return a + s * d


class Walk:
    """Targets of a walk over ``steps`` for a figure with gait ``p``; :meth:`at` gives one time."""

    def __init__(self, steps: list[Footstep], p: GaitParams, one_d: bool = False) -> None:
        """``one_d``: this is an underlying 1-D walk (its pelvis height is Boulic's profile itself)."""
        if len(steps) < 2 or {steps[0].side, steps[1].side} != set(SIDES):
            raise ValueError("a walk starts from two standing footsteps, one left and one right")
        for j in range(2, len(steps)):
            if steps[j].side == steps[j - 1].side:
                raise ValueError(f"footstep {j} is on the same side as footstep {j - 1}")
        self.steps, self.p = steps, p
        self.land = landing_times(steps, p)
        self.duration = duration(steps, p)
        self.by_side = {s: [j for j in range(len(steps)) if steps[j].side == s] for s in SIDES}
        # centre-site keys at the heel strikes: midpoint of the two feet
        self.keys = [0.5 * (steps[0].point + steps[1].point)]
        self.key_dir = [_angle_lerp(steps[0].psi, steps[1].psi, 0.5)]
        for j in range(2, len(steps)):
            self.keys.append(0.5 * (steps[j - 1].point + steps[j].point))
            self.key_dir.append(_angle_lerp(steps[j - 1].psi, steps[j].psi, 0.5))
        self.shuffle = self._shuffle_steps()
        self.bank_keys = self._bank_at_keys()
        #: the underlying 1-D walk (eq. 5.14's ω(t)); None for a 1-D walk itself
        self._one_cache: tuple[float, FrameTargets] | None = None
        self.underlying = None if one_d else Walk(self._unrolled(), p, one_d=True)

    def _unrolled(self) -> list[Footstep]:
        """The footsteps of the underlying straight (1-D) walk, facing along the heading of the
        first centre-site key: the standing feet as they are about that key, and each later foot
        σ_{i+1} from the same foot's previous place σ_{i-1} by that stride, taken in the frame of
        its mean heading (so the 1-D steps are the 2-D ones unrolled: their lengths the chords of
        the centre-site steps). Only σ_0..σ_i decide σ_i's place, so a walk extended by more
        footsteps keeps its earlier 1-D steps (the incremental stepper); a straight path unrolls
        onto itself."""
        st, a0 = self.steps, self.key_dir[0]
        R0 = _frame(a0)
        pts = [self.keys[0] + R0 @ (R0.T @ (s.point - self.keys[0])) for s in st[:2]]
        for i in range(2, len(st)):
            m = _angle_lerp(st[i - 2].psi, st[i].psi, 0.5)
            pts.append(pts[i - 2] + R0 @ (_frame(m).T @ (st[i].point - st[i - 2].point)))
        return [Footstep(float(q[0]), float(q[1]), a0, s.side) for q, s in zip(pts, st)]

    def _shuffle_steps(self) -> list[bool]:
        """Per step j: whether the centre site travels sideways or backwards (more than
        ``SHUFFLE_ANGLE`` from the feet's heading, over more than ``SHUFFLE_MIN``): such a step
        moves the centre site straight between its keys while the pelvis keeps facing the feet
        (:func:`.footsteps.shuffle`), instead of turning the pelvis along the travel."""
        out = [False] * len(self.steps)
        for j in range(2, len(self.steps)):
            chord = self.keys[j - 1] - self.keys[j - 2]
            if float(np.linalg.norm(chord)) <= SHUFFLE_MIN:
                continue
            heading = _angle_lerp(self.key_dir[j - 2], self.key_dir[j - 1], 0.5)
            travel = float(np.arctan2(chord[0], chord[1]))
            out[j] = abs((travel - heading + np.pi) % (2.0 * np.pi) - np.pi) > SHUFFLE_ANGLE
        return out

    # -- feet ------------------------------------------------------------------------------
    def _flat(self, j: int, pitch: float) -> np.ndarray:
        s = self.steps[j]
        return foot_transform(self.p, s.x, s.z, s.psi, pitch, s.side)

    def foot(self, side: str, t: float) -> tuple[np.ndarray, bool, str]:
        """The foot's floor frame at ``t``, whether its toes are on the floor, and its phase."""
        p, land, idx = self.p, self.land, self.by_side[side]
        cur = max(j for j in idx if land[j] <= t or j < 2)
        nxt = next((j for j in idx if j > cur), None)
        cycle = 2.0 * p.step_time
        if nxt is None:
            return self._stance(cur, t, cycle, None, None)
        t_s = START_TIME if nxt == 2 else land[nxt - 1]  # the other foot's heel strike
        t_to = t_s + 2.0 * DOUBLE_SUPPORT * (land[nxt] - t_s)
        if t < t_to:
            return self._stance(cur, t, cycle, t_s, t_to)
        u = (t - t_to) / (land[nxt] - t_to)
        # the toes straighten over the first TOES_RELEASE of the swing
        return self._swing(cur, nxt, u, side), 1.0 - float(smooth(u / TOES_RELEASE)), "swing"

    def _stance(self, cur, t, cycle, t_s, t_to):
        dt = t - self.land[cur]
        if cur >= 2 and dt < FOOT_FLAT * cycle:
            return self._flat(cur, self._hs_pitch(cur) * (1.0 - float(smooth(dt / (FOOT_FLAT * cycle))))), 0.0, "heel"
        if t_to is None:
            return self._flat(cur, 0.0), 1.0, "flat"
        t_ho = self.land[cur] + HEEL_OFF * cycle if cur >= 2 else t_s
        t_ho = min(max(t_ho, self.land[cur] + FOOT_FLAT * cycle if cur >= 2 else t_ho), t_to)
        if t <= t_ho:
            return self._flat(cur, 0.0), 1.0, "flat"
        u = (t - t_ho) / (t_to - t_ho)
        return self._flat(cur, self._to_pitch(cur) * float(smooth(u))), 1.0, "ball"

    def _stride(self, j: int) -> float:
        """Fraction of a full stride (2 step lengths) that footstep j's foot travels to land there."""
        prev = max((k for k in self.by_side[self.steps[j].side] if k < j), default=None)
        if prev is None:
            return 0.0
        d = float(np.linalg.norm(self.steps[j].point - self.steps[prev].point))
        return min(1.0, d / (2.0 * self.p.step_length))

    def _hs_pitch(self, j: int) -> float:
        """Heel-strike pitch of footstep j: full after a full stride, flatter after short ones."""
        return PITCH_HS * self._stride(j)

    def _to_pitch(self, cur: int) -> float:
        """Toe-off pitch leaving footstep ``cur``: with the length of the stride that follows."""
        nxt = next((k for k in self.by_side[self.steps[cur].side] if k > cur), None)
        return 0.0 if nxt is None else PITCH_TO * self._stride(nxt)

    def _swing(self, cur: int, nxt: int, u: float, side: str) -> np.ndarray:
        p, st = self.p, self.steps
        p0 = self._to_pitch(cur)
        p1 = self._hs_pitch(nxt)
        T0, T1 = self._flat(cur, p0), self._flat(nxt, p1)
        d1, d3 = _ankle(p, T0, side), _ankle(p, T1, side)
        # stance foot: the other foot's latest footstep; mirror its ankle across the walking line
        # α: along the stance heading, halfway between the stance ankle and the swing chord's middle
        other = nxt - 1
        a_st = _ankle(p, self._flat(other, 0.0), st[other].side)[[0, 2]]
        lateral = np.array([np.cos(st[other].psi), -np.sin(st[other].psi)])
        off = float(np.dot(0.5 * (d1[[0, 2]] + d3[[0, 2]]) - a_st, lateral))
        d2 = a_st + off * lateral
        s = float(smooth(u))
        top = (1 - s) ** 2 * d1[[0, 2]] + 2 * s * (1 - s) * d2 + s * s * d3[[0, 2]]
        y = d1[1] + s * (d3[1] - d1[1]) + swing_lift(p, p0, p1) * np.sin(np.pi * u)
        pitch = swing_pitch(u, p0, p1)
        psi = swing_yaw(st[cur].psi, st[nxt].psi, u)
        T = foot_transform(p, 0.0, 0.0, psi, pitch, side)
        a = _ankle(p, T, side)
        T[:3, 3] += np.array([top[0], y, top[1]]) - a
        return T

    # -- pelvis ----------------------------------------------------------------------------
    def _centre(self, t: float) -> tuple[np.ndarray, float, float | None]:
        """Centre-site floor point, yaw and cycle fraction (None standing)."""
        land, n = self.land, len(self.steps)
        if n == 2 or t < START_TIME:
            return self.keys[0], self.key_dir[0], None
        if t >= land[-1]:
            return self.keys[-1], self.key_dir[-1], None
        j = int(np.searchsorted(land[2:], t, side="right")) + 2  # footstep j is swinging in
        t0 = START_TIME if j == 2 else land[j - 1]
        u = (t - t0) / (land[j] - t0)
        c0, c1 = self.keys[j - 2], self.keys[j - 1]
        a0, a1 = self.key_dir[j - 2], self.key_dir[j - 1]
        if self.shuffle[j]:  # sideways or backwards: straight, facing the feet
            return c0 + u * (c1 - c0), _angle_lerp(a0, a1, u), 0.5 * u
        pt, yaw = _hermite_at_arc(c0, c1, a0, a1, u)
        return pt, yaw, 0.5 * u

    def _bank_at_keys(self) -> np.ndarray:
        """Banking angle φ = arctan(κ v² / g) (eq. 5.13; rad, + leaning left) at each centre-site
        key: κ is each step's mean curvature of the centre-site path (heading change over arc
        length) and v its speed; a key takes the mean of its two steps, 0 standing at both ends."""
        n = len(self.steps)
        phi = np.zeros(n)  # phi[j]: step j (footstep j swinging in), j >= 2
        if self.p.banking:
            from jackpy.locomotion.walk_gait import GRAVITY

            for j in range(2, n):
                if self.shuffle[j]:
                    continue  # no turn is walked sideways or backwards
                c0, c1, a0, a1 = self.keys[j - 2], self.keys[j - 1], self.key_dir[j - 2], self.key_dir[j - 1]
                length = _arc_length(c0, c1, a0, a1)
                if length < 1e-6:
                    continue  # a step on the spot: no travel, no banking
                t0 = START_TIME if j == 2 else self.land[j - 1]
                kappa = ((a1 - a0 + np.pi) % (2.0 * np.pi) - np.pi) / length
                v = length / (self.land[j] - t0)
                phi[j] = np.arctan(kappa * v * v / GRAVITY)
        keys = np.zeros(len(self.keys))
        for k in range(1, len(self.keys) - 1):  # key k joins step k + 1 and step k + 2
            keys[k] = 0.5 * (phi[k + 1] + phi[k + 2])
        return keys

    def bank(self, t: float) -> float:
        """Banking angle (rad, + leaning left) at ``t``: between the keys of the step, smoothly."""
        land, n = self.land, len(self.steps)
        if n == 2 or t < START_TIME or t >= land[-1]:
            return 0.0
        j = int(np.searchsorted(land[2:], t, side="right")) + 2
        t0 = START_TIME if j == 2 else land[j - 1]
        s = float(smooth((t - t0) / (land[j] - t0)))
        return float((1.0 - s) * self.bank_keys[j - 2] + s * self.bank_keys[j - 1])

    def _sway_amplitude(self, j: int) -> float:
        """Signed (+ left) sway of step j toward its stance foot σ_{j-1}: ``p.sway`` for a foot at
        half the step width from the step's centre line (through the middle of its two centre-site
        keys), in proportion for wider ones (the first step from standing and the stop shift the
        weight further, onto a foot at the standing width)."""
        st, p = self.steps, self.p
        key = 0.5 * (self.keys[j - 2] + self.keys[j - 1])
        a = _angle_lerp(self.key_dir[j - 2], self.key_dir[j - 1], 0.5)
        off = float(np.dot(st[j - 1].point - key, [np.cos(a), -np.sin(a)]))
        return p.sway * off / p.step_half_width

    def sway(self, t: float) -> float:
        """Lateral shift of the centre site (m, + left of the path) toward the stance foot: a
        sine over each single stance that crosses the centre line in the middle of each double
        support (``SWAY_CROSSING`` of the step), as the COM does in human walking."""
        land, n = self.land, len(self.steps)
        if n == 2:
            return 0.0
        if t < START_TIME:  # the weight shift onto the first stance foot
            return self._sway_amplitude(2) * float(smooth(t / START_TIME))
        if t >= land[-1]:  # the stop: eases back to the middle
            u = min(1.0, (t - land[-1]) / STOP_TIME)
            return self._sway_at(n - 1, 1.0) * (1.0 - float(smooth(u)))
        j = int(np.searchsorted(land[2:], t, side="right")) + 2
        t0 = START_TIME if j == 2 else land[j - 1]
        return self._sway_at(j, (t - t0) / (land[j] - t0))

    def _sway_at(self, j: int, u: float) -> float:
        phi = SWAY_CROSSING
        if j == 2:  # from the full weight shift at the first step's start
            return self._sway_amplitude(2) * float(np.sin(np.pi * (0.5 + (0.5 - phi) * u)))
        if u < phi:  # the previous stance's sine, crossing the centre line
            return self._sway_amplitude(j - 1) * float(np.sin(np.pi * (1.0 + u - phi)))
        return self._sway_amplitude(j) * float(np.sin(np.pi * (u - phi)))

    def pelvis(self, t: float, feet: dict[str, np.ndarray], phase: dict[str, str]) -> np.ndarray:
        p = self.p
        pt, yaw, cyc = self._centre(t)
        lat = np.array([np.cos(yaw), -np.sin(yaw)])  # left of the heading, top view (x, z)
        # banking (5.13) by the ankles: the body leans by φ about the feet, so the centre site
        # moves toward the centre of the turn by its height·tan φ (the pelvis itself stays upright)
        pt = pt + (self.sway(t) + p.hip_height * np.tan(self.bank(t))) * lat
        stand = p.hip_height - 0.003 * p.hip_height
        if cyc is None:
            if t < START_TIME:
                h = stand + (stand + pelvis_drop(p, 0.0) - stand) * float(smooth(t / START_TIME))
            else:
                u = min(1.0, (t - self.land[-1]) / STOP_TIME) if len(self.steps) > 2 else 1.0
                k = self._stride(len(self.steps) - 1) if len(self.steps) > 2 else 0.0
                h = stand + k * pelvis_drop(p, 0.0) * (1.0 - float(smooth(u)))
        else:
            # short steps (the first and the last) dip less: Boulic's offset times the stride fraction
            j = int(np.searchsorted(self.land[2:], t, side="right")) + 2
            k = min(self._stride(j), max(self._stride(j - 1), 0.5)) if j - 1 >= 2 else self._stride(j)
            h = stand + k * pelvis_drop(p, cyc)
            if self.underlying is not None and not self.shuffle[j]:
                h = self._hip_height(t, np.array([pt[0], h, pt[1]]), yaw, self.steps[j - 1].side, feet)
        centre = np.array([pt[0], h, pt[1]])
        for side in SIDES:
            if phase[side] != "swing":
                centre[1] = min(centre[1], self._reach_top(centre, yaw, side, feet[side]))
        T = np.eye(4)
        T[:3, :3] = rot_y(yaw)
        T[:3, 3] = centre
        return T

    def _hip_height(self, t: float, centre: np.ndarray, yaw: float, side: str, feet: dict[str, np.ndarray]) -> float:
        """The book's hip-height rule (5.14): the stance leg (hip to ankle) has the length ω(t) of
        the underlying 1-D walk's stance leg at ``t``, so the pelvis height is
        ``y2 = y1 + sqrt(ω² − (x2 − x1)² − (z2 − z1)²)``, (x1, y1, z1) the stance ankle and
        (x2, z2) the stance hip's floor point (the pelvis is upright: both hips at y2). A centre
        site displaced from the 1-D one (banking, curvature) sits lower; a straight path is the
        1-D height."""
        one = self._one_d(t)
        c1 = one.pelvis[:3, 3]
        yaw1 = float(np.arctan2(one.pelvis[0, 2], one.pelvis[2, 2]))
        omega = float(np.linalg.norm(self.underlying._hip(c1, yaw1, side) - _ankle(self.p, one.feet[side], side)))
        hip, a = self._hip(centre, yaw, side), _ankle(self.p, feet[side], side)
        dh2 = (hip[0] - a[0]) ** 2 + (hip[2] - a[2]) ** 2
        return float(a[1] + np.sqrt(max(omega * omega - dh2, 0.0)))

    def _hip(self, centre: np.ndarray, yaw: float, side: str) -> np.ndarray:
        off = self.p.hip_half_width if side == "left" else -self.p.hip_half_width
        return centre + off * np.array([np.cos(yaw), 0.0, -np.sin(yaw)])

    def _reach_top(self, centre: np.ndarray, yaw: float, side: str, T: np.ndarray) -> float:
        """Highest pelvis centre from which the hip still reaches the foot's ankle."""
        hip, a = self._hip(centre, yaw, side), _ankle(self.p, T, side)
        reach = MAX_LEG * self.p.leg_length
        dh = np.hypot(hip[0] - a[0], hip[2] - a[2])
        return float(a[1] + np.sqrt(max(reach * reach - dh * dh, 0.0)))

    def _lift_heel(self, j: int, T: np.ndarray, pelvis: np.ndarray, side: str) -> tuple[np.ndarray, float]:
        """The book's rule: raise the heel (roll about the ball joint) until the ankle is within
        reach of the hip; returns the foot's frame and its pitch."""
        yaw = float(np.arctan2(pelvis[0, 2], pelvis[2, 2]))
        pitch0 = float(np.arcsin(np.clip(-T[1, 2], -1.0, 1.0)))
        if pitch0 < 0.0 or self._reach_top(pelvis[:3, 3], yaw, side, T) >= pelvis[1, 3]:
            return T, pitch0
        lo, hi = pitch0, MAX_PITCH
        if self._reach_top(pelvis[:3, 3], yaw, side, self._flat(j, hi)) < pelvis[1, 3]:
            return self._flat(j, hi), hi
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            if self._reach_top(pelvis[:3, 3], yaw, side, self._flat(j, mid)) >= pelvis[1, 3]:
                hi = mid
            else:
                lo = mid
        return self._flat(j, hi), hi

    def arms(self, t: float) -> dict[str, float]:
        """Shoulder swing: each arm forward while the opposite leg swings forward."""
        st, land, n = self.steps, self.land, len(self.steps)
        if n <= 2 or t <= START_TIME or t >= land[-1]:
            return {"left": 0.0, "right": 0.0}
        j = int(np.searchsorted(land[2:], t, side="right")) + 2
        t0 = START_TIME if j == 2 else land[j - 1]
        u = (t - t0) / (land[j] - t0)
        sign = 1.0 if st[j].side == "left" else -1.0  # +1: right arm swinging forward
        val = -sign + 2.0 * sign * float(smooth(u))
        if j == 2:
            val = sign * float(smooth(u))
        if j == n - 1:
            val = -sign * (1.0 - float(smooth(u)))
        amp = self.p.arm_swing
        return {"left": -val * amp, "right": val * amp}

    def at(self, t: float) -> FrameTargets:
        feet, toes, phase = {}, {}, {}
        for side in SIDES:
            feet[side], toes[side], phase[side] = self.foot(side, t)
        self._ball_from_1d(t, feet, phase)
        pel = self.pelvis(t, {s: feet[s] for s in SIDES}, {s: ("swing" if phase[s] != "heel" else "heel")
                                                           for s in SIDES})
        yaw = float(np.arctan2(pel[0, 2], pel[2, 2]))
        for side in SIDES:
            if phase[side] in ("flat", "ball"):
                j = self._standing_on(side, t)
                feet[side], pitch = self._lift_heel(j, feet[side], pel, side)
                if pitch > 1e-9:
                    phase[side] = "ball"
                pel[1, 3] = min(pel[1, 3], self._reach_top(pel[:3, 3], yaw, side, feet[side]))
        return FrameTargets(pel, feet, toes, self.arms(t), phase)

    def _step_at(self, t: float) -> int | None:
        """The step running at ``t`` (footstep j swinging in), None standing."""
        if len(self.steps) == 2 or t < START_TIME or t >= self.land[-1]:
            return None
        return int(np.searchsorted(self.land[2:], t, side="right")) + 2

    def _one_d(self, t: float) -> FrameTargets:
        """The underlying 1-D walk's targets at ``t`` (the last time asked is kept)."""
        if self._one_cache is None or self._one_cache[0] != t:
            self._one_cache = (t, self.underlying.at(t))
        return self._one_cache[1]

    def _ball_from_1d(self, t: float, feet: dict[str, np.ndarray], phase: dict[str, str]) -> None:
        """The book's stance leg: the stance foot's ball-of-foot angle is the 1-D walk's (where the
        1-D heel is raised further, so is this one)."""
        j = self._step_at(t)
        if self.underlying is None or j is None or self.shuffle[j]:
            return
        side = self.steps[j - 1].side
        if phase[side] not in ("flat", "ball"):
            return
        pitch = lambda T: float(np.arcsin(np.clip(-T[1, 2], -1.0, 1.0)))  # noqa: E731
        p1 = pitch(self._one_d(t).feet[side])
        if p1 > pitch(feet[side]) + 1e-12:
            feet[side], phase[side] = self._flat(j - 1, p1), "ball"

    def _standing_on(self, side: str, t: float) -> int:
        return max(j for j in self.by_side[side] if self.land[j] <= t or j < 2)

    def frames(self, fps: float) -> list[FrameTargets]:
        n = int(np.floor(self.duration * fps + 1e-9)) + 1
        return [self.at(i / fps) for i in range(n)]


def swing_yaw(psi_to: float, psi_hs: float, u: float) -> float:
    """Heading (rad) of the swing foot at swing fraction ``u`` (time since toe-off over the swing
    time): its twist from the landing heading decays as the book's parabola (5.16),
    ``θ̃(t) = θ̃(0)·((t_sw − t)/t_sw)²``, from the toe-off heading to the heel-strike one. (Its
    roll, the other free rotation (5.15), is zero at toe-off in this kinematic walk.)"""
    d = (psi_to - psi_hs + np.pi) % (2.0 * np.pi) - np.pi
    return float(psi_hs + d * (1.0 - float(np.clip(u, 0.0, 1.0))) ** 2)


def _hermite(c0, c1, a0, a1, s):
    m = float(np.linalg.norm(c1 - c0))
    t0 = m * np.array([np.sin(a0), np.cos(a0)])
    t1 = m * np.array([np.sin(a1), np.cos(a1)])
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
    d00, d10, d01, d11 = 6 * s**2 - 6 * s, 3 * s**2 - 4 * s + 1, -6 * s**2 + 6 * s, 3 * s**2 - 2 * s
    pt = np.outer(h00, c0) + np.outer(h10, t0) + np.outer(h01, c1) + np.outer(h11, t1)
    dv = np.outer(d00, c0) + np.outer(d10, t0) + np.outer(d01, c1) + np.outer(d11, t1)
    return pt, dv


def _arc_length(c0, c1, a0, a1) -> float:
    """Top-view arc length (m) of the centre-site Hermite from ``c0`` to ``c1``."""
    pts, _ = _hermite(c0, c1, a0, a1, np.linspace(0.0, 1.0, 65))
    return float(np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1)))


def _hermite_at_arc(c0, c1, a0, a1, u: float) -> tuple[np.ndarray, float]:
    """Point and tangent yaw at arc-length fraction ``u`` of the centre-site Hermite."""
    if np.linalg.norm(c1 - c0) < 1e-9:
        return c0.copy(), _angle_lerp(a0, a1, u)
    s = np.linspace(0.0, 1.0, 65)
    pts, _ = _hermite(c0, c1, a0, a1, s)
    cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    si = float(np.interp(u * cum[-1], cum, s))
    pt, dv = _hermite(c0, c1, a0, a1, np.array([si]))
    return pt[0], float(np.arctan2(dv[0, 0], dv[0, 1]))
