"""The primitive steps commands expand to, the Yaps directives ([SH6] §6.3.2): a *generate-motion*
(look, reach, carry, return: one timed motion of the motion model, its duration by Fitts' law
evaluated when the step starts, from the posture reached by then), *create-constraint* (hold,
place) and *delete-constraint* (release), each a ``t_constraint`` long.

``begin(sim, t)`` adds the step's motions or timed behaviors to the timeline and returns its
duration (s); ``finish(sim, t)`` checks it was achieved, raising :class:`TaskError` with the reason,
and may return follow-up steps (the corrective sub-movement of a reach).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.tasks.kb import Ref
from jackpy.tasks.semantics import TaskError

if TYPE_CHECKING:
    from jackpy.tasks.script import Simulation

LOOK_TOLERANCE_DEG = 1.0
REACH_TOLERANCE_M = 0.01
MAX_CORRECTIONS = 4
MAX_SETTLE_FRAMES = 10
TIP_SITE = "index_3"


def view_axis(sim: "Simulation", agent: str) -> tuple[np.ndarray, np.ndarray]:
    """The agent's view point and unit view axis (world): the mean of the two eyes' centres and
    forward axes (the eyes turn first and the head follows, [SH4] §4.2.5)."""
    loop = sim.loops[agent]
    a = loop.anatomy
    Ts = [loop.figure.site_world(*a.eyes[s]) for s in sorted(a.eyes)]
    p = np.mean([T[:3, 3] for T in Ts], axis=0)
    f = np.sum([T[:3, :3] @ a.eye_forward for T in Ts], axis=0)
    return p, f / np.linalg.norm(f)


def view_error_deg(sim: "Simulation", agent: str, point: np.ndarray) -> float:
    p, f = view_axis(sim, agent)
    d = point - p
    return float(np.degrees(np.arccos(np.clip(f @ d / np.linalg.norm(d), -1.0, 1.0))))


def fingertip(sim: "Simulation", agent: str, side: str) -> np.ndarray:
    fig = sim.loops[agent].figure
    seg = f"{side}_{TIP_SITE}"
    if seg in fig.segments and "tip" in fig.segments[seg].sites:
        return fig.site_world(seg, "tip")[:3, 3]
    return palm(sim, agent, side)


def palm(sim: "Simulation", agent: str, side: str) -> np.ndarray:
    loop = sim.loops[agent]
    return loop.figure.site_world(*loop.anatomy.hands[side].palm)[:3, 3]


@dataclass
class Step:
    agent: str
    label: str
    run: dict[str, Any] = field(default_factory=dict)

    def begin(self, sim: "Simulation", t: float) -> float:
        raise NotImplementedError

    def finish(self, sim: "Simulation", t: float) -> list["Step"]:
        return []


@dataclass
class Look(Step):
    """Aim the head's view axis at a target (a view goal, [SH6] §6.1.2); Fitts head time on the
    angle between the view axis and the target direction."""

    ref: Ref | None = None
    settles: int = 0

    def begin(self, sim, t):
        from jackpy.motion.kinds.gaze import GazeMotion

        point = sim.kb.world(self.ref)
        a = view_error_deg(sim, self.agent, point)
        dur = sim.timed(self.agent, self.label, "head", a, t)
        sim.timeline.add(GazeMotion(figure=self.agent, which="eyes", t0=t, t1=t + dur, target=sim.kb.target(self.ref),
                                    label=self.label))
        return dur

    def finish(self, sim, t):
        err = view_error_deg(sim, self.agent, sim.kb.world(self.ref))
        self.run["error_deg"] = err
        if err <= LOOK_TOLERANCE_DEG:
            return []
        if self.settles >= MAX_SETTLE_FRAMES:
            raise TaskError(f"{self.agent} cannot {self.label.lower()}: view axis {err:.1f}° off")
        return [Settle(self.agent, self.label, run={"look": self})]


@dataclass
class Settle(Step):
    """Wait one frame more for the head to finish turning (up to MAX_SETTLE_FRAMES frames)."""

    def begin(self, sim, t):
        look = self.run["look"]
        look.settles += 1
        return sim.dt

    def finish(self, sim, t):
        look = self.run["look"]
        out = look.finish(sim, t)
        self.run["error_deg"] = look.run["error_deg"]
        return out


@dataclass
class Reach(Step):
    """Bring the fingertip (``tip``) or the palm to a point: an arm motion of the palm goal, then
    corrective sub-movements (each timed by Fitts on what is left) until within 1 cm."""

    ref: Ref | None = None
    side: str = "right"
    tip: bool = True
    waist: bool = False
    offset: np.ndarray | None = None  # world offset added to the reference point
    point: np.ndarray | None = None  # a world point instead of a reference
    corrections: int = 0

    def goal(self, sim) -> np.ndarray:
        p = self.point if self.ref is None else sim.kb.world(self.ref)
        return p if self.offset is None else p + self.offset

    def effector(self, sim) -> np.ndarray:
        return fingertip(sim, self.agent, self.side) if self.tip else palm(sim, self.agent, self.side)

    def begin(self, sim, t):
        from jackpy.motion.kinds.arm import ArmMotion

        goal = self.goal(sim)
        eff = self.effector(sim)
        amp_cm = float(np.linalg.norm(goal - eff) * 100.0)
        label = self.label if self.corrections == 0 else f"{self.label} (correction {self.corrections})"
        dur = sim.timed(self.agent, label, "arm", amp_cm, t)
        palm_goal = goal - (eff - palm(sim, self.agent, self.side))
        sim.timeline.add(ArmMotion(figure=self.agent, side=self.side, t0=t, t1=t + dur,
                                   target={"point": palm_goal.tolist()}, waist=self.waist, label=label))
        return dur

    def finish(self, sim, t):
        err = float(np.linalg.norm(self.goal(sim) - self.effector(sim)))
        self.run["error_m"] = err
        if err <= REACH_TOLERANCE_M:
            return []
        if self.corrections >= MAX_CORRECTIONS:
            raise TaskError(f"{self.agent} cannot reach {self.label}: {'fingertip' if self.tip else 'palm'} "
                            f"{err * 100:.1f} cm short (unreachable)")
        nxt = Reach(self.agent, self.label, ref=self.ref, side=self.side, tip=self.tip, waist=self.corrections >= 1,
                    offset=self.offset, point=self.point, corrections=self.corrections + 1)
        return [nxt]


@dataclass
class SetControl(Step):
    """Drive a control's DOF to a state or by an angle (the KB's control state; the control's
    geometry is not animated, as in the book)."""

    control: Any = None
    state: str | None = None
    degrees: float | None = None
    side: str = "right"

    def begin(self, sim, t):
        return sim.config.t_constraint_s

    def finish(self, sim, t):
        c = self.control
        err = float(np.linalg.norm(fingertip(sim, self.agent, self.side) -
                                   sim.kb.world(sim.kb.resolve(f"{self.run['obj']}.{c.site}"))))
        self.run["fingertip_error_m"] = err
        if err > REACH_TOLERANCE_M:
            if self.run.get("retries", 0) >= 2:
                raise TaskError(f"{self.agent} is not touching {c.name} ({err * 100:.1f} cm away)")
            again = SetControl(self.agent, self.label, control=c, state=self.state, degrees=self.degrees,
                               side=self.side, run={**self.run, "retries": self.run.get("retries", 0) + 1})
            return [Reach(self.agent, f"Turn {c.name}", ref=sim.kb.resolve(f"{self.run['obj']}.{c.site}"),
                          side=self.side, waist=True, corrections=1), again]
        if self.state is not None:
            c.angle_deg, c.state = c.value_of(self.state), self.state
        else:
            new = c.angle_deg + float(self.degrees)
            if not c.limits[0] - 1e-9 <= new <= c.limits[1] + 1e-9:
                raise TaskError(f"{c.name} cannot turn {self.degrees:+g}°: {new:g}° is outside {c.limits}")
            c.angle_deg = new
            c.state = next((k for k, v in c.states.items() if abs(v - new) < 1e-6), f"{new:g}°")
        return []


@dataclass
class Hold(Step):
    """create-constraint: the hand carries ``obj`` (a timed attachment until released)."""

    obj: str = ""
    side: str = "right"

    def begin(self, sim, t):
        from jackpy.motion.timed import TimedBehavior

        tb = TimedBehavior(figure=self.agent, control=f"attach.{self.side}", value=self.obj, t0=t, t1=t + 1e6)
        sim.timeline.add(tb)
        sim.holds[(self.agent, self.side)] = (self.obj, tb)
        sim.kb.lift(self.obj)
        return sim.config.t_constraint_s


@dataclass
class Release(Step):
    """delete-constraint: the hand lets go of what it holds (ends the timed attachment)."""

    side: str = "right"

    def begin(self, sim, t):
        held = sim.holds.pop((self.agent, self.side), None)
        if held is None:
            raise TaskError(f"{self.agent}'s {self.side} hand holds nothing")
        held[1].t1 = t
        self.run["obj"] = held[0]
        return sim.config.t_constraint_s


@dataclass
class Carry(Step):
    """generate-motion of a held object: the palm moves so the object's reference point goes to
    ``pose``'s position (Fitts arm time on the object's displacement)."""

    obj: str = ""
    pose: np.ndarray | None = None
    side: str = "right"
    lift_m: float = 0.0

    def begin(self, sim, t):
        from jackpy.motion.kinds.arm import ArmMotion

        o = sim.env.figures[self.obj].location[:3, 3]
        goal = self.pose[:3, 3] + np.array([0.0, self.lift_m, 0.0])
        amp_cm = float(np.linalg.norm(goal - o) * 100.0)
        dur = sim.timed(self.agent, self.label, "arm", amp_cm, t)
        palm_goal = palm(sim, self.agent, self.side) + (goal - o)
        sim.timeline.add(ArmMotion(figure=self.agent, side=self.side, t0=t, t1=t + dur,
                                   target={"point": palm_goal.tolist()}, waist=True, label=self.label))
        return dur

    def finish(self, sim, t):
        err = float(np.linalg.norm(sim.env.figures[self.obj].location[:3, 3] - self.pose[:3, 3] -
                                   [0.0, self.lift_m, 0.0]))
        self.run["error_m"] = err
        if err > 0.05:
            raise TaskError(f"{self.agent} cannot bring {self.obj} there: {err * 100:.1f} cm short (unreachable)")
        return []


@dataclass
class Place(Step):
    """create-constraint ``supported-by``: the object is set onto its resolved resting pose (the
    carry brought it within a few cm; no physics) and rests on the supporter from now on."""

    obj: str = ""
    pose: np.ndarray | None = None
    supporter: str = ""

    def begin(self, sim, t):
        sim.placements.append({"t": t, "object": self.obj, "location": self.pose.tolist(), "on": self.supporter})
        sim.env.figures[self.obj].location = self.pose.copy()
        return sim.config.t_constraint_s

    def finish(self, sim, t):
        sim.env.figures[self.obj].location = self.pose.copy()
        sim.kb.rest_on(self.obj, self.supporter)
        return []
