"""Incremental walking ([SH5] §5.1.7, §5.2.4 Fig. 5.13; digest §2.7, §2.8.4): a walker that only
needs the next footstep.

A :class:`Stepper` walks from two standing footsteps and asks its **footstep source** for one more
footstep whenever the step now running needs it: the walk of :mod:`.walk_path` over footsteps
σ_0..σ_{j+1} is final up to the heel strike of σ_j (banking, sway and the stance foot's toe-off
look one footstep ahead), so a source is asked for σ_{j+1} when step j begins. The targets of a
stepper fed a planned sequence one by one are those of the whole walk (test:
``test_stepper_fed_a_plan_is_the_planned_walk``).

A source is any callable ``source(stepper) -> Footstep | None``: a footstep to take next (its
side is the foot whose turn it is), or None to stop (the stepper then brings the feet together
beside the last footstep, as :func:`.footsteps.from_path` ends). Sources here:

- :class:`Planned`: a planned footstep sequence, one at a time (scripted walking);
- :class:`Approach`: the book's behavior-driven walker, steering toward a target point: the
  heading change is clipped to ±45° per step, the step shortened on turns
  (``sl = sl₀·(1 − 0.5·|Δψ|/45°)``, ≥ 0.3·sl₀) and the next foot placed beside the new heading
  line (:func:`steer`); it stops within ``arrive`` of the target.

:func:`constrain_landing` is the footstep rule the balance stepper
(:mod:`jackpy.behaviors.stepping`) applies to its landing points: at least a width beside the
stance foot and at most a step length from where the foot is.

Floor points (x, z) metres, headings rad about +y (0 faces +z), time s.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from jackpy.locomotion.footsteps import K_TURN, MAX_TURN, MIN_STEP, _dir, _lat, _stop
from jackpy.locomotion.walk_gait import START_TIME, GaitParams
from jackpy.locomotion.walk_path import Footstep, FrameTargets, Walk

Source = Callable[["Stepper"], "Footstep | None"]
OTHER = {"left": "right", "right": "left"}


def wrap(a: float) -> float:
    return float((a + np.pi) % (2.0 * np.pi) - np.pi)


def centre_of(p: GaitParams, f: Footstep, half_width: float | None = None) -> np.ndarray:
    """The walking line's point beside footstep ``f`` (m): ``half_width`` (default the walking
    step's) toward the body's midline."""
    w = p.step_half_width if half_width is None else half_width
    return f.point - (w if f.side == "left" else -w) * _lat(f.psi)


def steer(p: GaitParams, last: Footstep, desired: float, length: float | None = None) -> Footstep:
    """The book's footstep rule (§5.1.7): the next footstep, of the other foot, after ``last``
    toward heading ``desired`` (rad): the change clipped to ±45°, the step (``length``, default
    the gait's) shortened by the turn, the foot beside the new heading line."""
    turn = float(np.clip(wrap(desired - last.psi), -MAX_TURN, MAX_TURN))
    psi = last.psi + turn
    sl = p.step_length if length is None else float(length)
    sl *= max(MIN_STEP, 1.0 - K_TURN * abs(turn) / MAX_TURN)
    side = OTHER[last.side]
    c = centre_of(p, last) + sl * _dir(psi)
    q = c + (p.step_half_width if side == "left" else -p.step_half_width) * _lat(psi)
    return Footstep(float(q[0]), float(q[1]), float(psi), side)


def constrain_landing(stance: np.ndarray, swing: np.ndarray, proposed: np.ndarray, min_width: float,
                      max_length: float) -> np.ndarray:
    """Landing floor point of a swing foot now at ``swing`` stepping to ``proposed`` beside the
    stance foot at ``stance``: moved out to at least ``min_width`` beside the stance foot (across
    the feet's present line) and at most ``max_length`` from ``swing`` (m)."""
    stance, swing, new = (np.asarray(v, dtype=float) for v in (stance, swing, proposed))
    lateral = swing - stance
    lateral = lateral / max(float(np.linalg.norm(lateral)), 1e-9)
    width = float((new - stance) @ lateral)
    if width < min_width:
        new = new + (min_width - width) * lateral
    d = new - swing
    n = float(np.linalg.norm(d))
    if n > max_length:
        d *= max_length / n
    return swing + d


class Stepper:
    """Walks gait ``p`` from the standing footsteps ``standing`` (σ_0, σ_1) with footsteps from
    ``source``; :meth:`next_frame` advances time and gives the targets (:class:`FrameTargets`)."""

    def __init__(self, p: GaitParams | None, standing: list[Footstep], source: Source, max_steps: int = 500) -> None:
        """``p`` None: footsteps only (:meth:`next_footstep`; the caller swings the feet itself)."""
        if len(standing) != 2 or {standing[0].side, standing[1].side} != {"left", "right"}:
            raise ValueError("a stepper starts from two standing footsteps, one left and one right")
        self.p, self.source, self.max_steps = p, source, max_steps
        self.steps: list[Footstep] = list(standing)
        self.t = 0.0
        self.stopped = False
        self._walk: Walk | None = None

    # ----- footsteps ----------------------------------------------------------------------------------
    @property
    def next_side(self) -> str:
        return self.steps[0].side if len(self.steps) == 2 else OTHER[self.steps[-1].side]

    def end_here(self) -> None:
        """The footsteps given so far end the walk (they already stand together: a plan's end)."""
        self.stopped = True

    def stop(self, at=None, facing: float | None = None) -> None:
        """End the walk standing with the feet together at floor point ``at`` (default: on the
        walking line beside the last footstep), facing ``facing`` (default the last heading);
        turns beyond 45° take steps on the spot."""
        last = self.steps[-1]
        if at is None:
            at = centre_of(self.p, last) if len(self.steps) > 2 else 0.5 * (self.steps[0].point + self.steps[1].point)
        psi = last.psi if facing is None else float(facing)
        self.steps += _stop(self.p, self.steps, np.asarray(at, dtype=float), psi, self.next_side)
        self.stopped = True
        self._walk = None

    def _ask(self) -> None:
        f = self.source(self)
        if self.stopped:
            return
        if f is None:
            if self.p is None:
                self.stopped = True
            else:
                self.stop()
            return
        if f.side != self.next_side:
            raise ValueError(f"footstep {len(self.steps)} must be the {self.next_side} foot, not the {f.side}")
        if len(self.steps) - 2 >= self.max_steps:
            raise ValueError(f"the footstep source gave more than {self.max_steps} footsteps")
        self.steps.append(f)
        self._walk = None

    def next_footstep(self) -> Footstep | None:
        """Ask the source for the next footstep now (a step-at-a-time caller such as the balance
        stepper, which swings the foot itself); the footstep, or None when the walk has ended."""
        n = len(self.steps)
        if not self.stopped:
            self._ask()
        return self.steps[n] if len(self.steps) > n and not self.stopped else None

    def _land(self, k: int) -> float:
        """Heel-strike time of footstep ``k`` (≥ 2; s)."""
        return START_TIME + (k - 1) * self.p.step_time

    def _need(self, t: float) -> None:
        # the step running at t (footstep j swinging in) needs σ_{j+1}: t < land(n - 2)
        while not self.stopped and (len(self.steps) < 4 or t >= self._land(len(self.steps) - 2)):
            self._ask()

    # ----- time -------------------------------------------------------------------------------------
    @property
    def walk(self) -> Walk:
        """The walk over the footsteps known so far."""
        if self.p is None:
            raise ValueError("a stepper without a gait gives footsteps only")
        if self._walk is None:
            self._walk = Walk(self.steps, self.p)
        return self._walk

    @property
    def done(self) -> bool:
        """Stopped and standing still at the end."""
        return self.stopped and self.t >= self.walk.duration

    def at(self, t: float) -> FrameTargets:
        """Targets at time ``t`` (s, from the start; asking the source for what that needs)."""
        self._need(float(t))
        return self.walk.at(float(t))

    def next_frame(self, dt: float) -> FrameTargets:
        """Advance by ``dt`` (s) and give the targets there."""
        self.t += float(dt)
        return self.at(self.t)

    def run(self, limit_s: float = 600.0) -> list[Footstep]:
        """Ask for footsteps until the source stops (or ``limit_s`` of walking); the footsteps."""
        while not self.stopped and self._land(len(self.steps) - 2) < limit_s:
            self._ask()
        return self.steps


class Planned:
    """A planned footstep sequence (σ_0, σ_1 the standing feet, the end standing together) given
    one footstep at a time."""

    def __init__(self, steps: list[Footstep]) -> None:
        self.steps = steps

    def standing(self) -> list[Footstep]:
        return self.steps[:2]

    def __call__(self, stepper: Stepper) -> Footstep | None:
        k = len(stepper.steps)
        if k >= len(self.steps):
            stepper.end_here()
            return None
        return self.steps[k]


class Approach:
    """The book's behavior-driven walker (§5.1.7): each footstep turns toward ``target`` (x, z)
    by at most 45° (:func:`steer`), the first from standing half a step; when the walking line is
    within ``arrive`` (m, default one step) of the target the feet come together on it, facing
    ``facing`` (default: as they arrive)."""

    def __init__(self, target, arrive: float | None = None, facing: float | None = None) -> None:
        self.target = np.asarray(target, dtype=float)[:2]
        self.arrive, self.facing = arrive, facing

    def __call__(self, stepper: Stepper) -> Footstep | None:
        p, steps = stepper.p, stepper.steps
        if len(steps) == 2:  # from standing: half a step from between the standing feet
            here = 0.5 * (steps[0].point + steps[1].point)
            psi0 = steps[0].psi + 0.5 * wrap(steps[1].psi - steps[0].psi)
        else:
            here, psi0 = centre_of(p, steps[-1]), steps[-1].psi
        d = self.target - here
        dist = float(np.linalg.norm(d))
        if dist <= (p.step_length if self.arrive is None else self.arrive):
            stepper.stop(self.target, self.facing)
            return None
        turn = float(np.clip(wrap(float(np.arctan2(d[0], d[1])) - psi0), -MAX_TURN, MAX_TURN))
        psi = psi0 + turn
        sl = (0.5 if len(steps) == 2 else 1.0) * p.step_length * max(MIN_STEP, 1.0 - K_TURN * abs(turn) / MAX_TURN)
        side = stepper.next_side
        q = here + sl * _dir(psi) + (p.step_half_width if side == "left" else -p.step_half_width) * _lat(psi)
        return Footstep(float(q[0]), float(q[1]), float(psi), side)


class Balance:
    """The balance stepper's source (sensor-driven stepping, :mod:`jackpy.behaviors.stepping`):
    each footstep is where the behavior's step decision wants the swing foot, ``proposed`` (x, z;
    set before each ask), landed by the shared rule :func:`constrain_landing` (at least
    ``min_width`` beside the stance foot, at most ``max_length`` from where the foot is; m),
    keeping the foot's heading. Footstep points here are the behavior's foot reference points."""

    def __init__(self, min_width: float, max_length: float) -> None:
        self.min_width, self.max_length = float(min_width), float(max_length)
        self.proposed: np.ndarray | None = None

    def __call__(self, stepper: Stepper) -> Footstep | None:
        if self.proposed is None:
            return None
        side = stepper.next_side
        swing = next(f for f in reversed(stepper.steps) if f.side == side)
        stance = next(f for f in reversed(stepper.steps) if f.side != side)
        q = constrain_landing(stance.point, swing.point, self.proposed, self.min_width, self.max_length)
        self.proposed = None
        return Footstep(float(q[0]), float(q[1]), swing.psi, side)
