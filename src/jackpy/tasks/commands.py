"""The task-level commands ([SH6] §6.1–6.3; digest §5.4). Each is a small dataclass whose
``expand(sim)`` grounds its names against the knowledge base *when the command starts* and returns
its sequential primitive steps (:mod:`jackpy.tasks.steps`). ``agent`` is a figure name; ``hand`` is
``"right"`` or ``"left"``."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from jackpy.tasks import steps as st
from jackpy.tasks.placement import container_pose, resting_pose
from jackpy.tasks.semantics import TaskError, fold

if TYPE_CHECKING:
    from jackpy.tasks.script import Simulation


@dataclass
class Command:
    agent: str

    def expand(self, sim: "Simulation") -> list[st.Step]:
        raise NotImplementedError

    @property
    def text(self) -> str:
        return type(self).__name__.lower()


@dataclass
class LookAt(Command):
    """Aim the agent's view axis at a site, an object or another agent (head, Fitts head time)."""

    target: str = ""

    def expand(self, sim):
        return [st.Look(self.agent, self.text, ref=sim.kb.resolve(self.target))]

    @property
    def text(self):
        return f"Look {self.target}"


@dataclass
class Reach(Command):
    """Bring the fingertip to a site (Esakov's reach goal)."""

    target: str = ""
    hand: str = "right"

    def expand(self, sim):
        return [st.Reach(self.agent, self.text, ref=sim.kb.resolve(self.target), side=self.hand)]

    @property
    def text(self):
        return f"Reach {self.target}"


def _handle(sim: "Simulation", obj: str, purpose: str | None) -> tuple[str, str]:
    """(site, grip) to grasp ``obj`` by: the handle tagged with ``purpose``, else the first handle,
    else the object's origin with a power grip."""
    ref = sim.kb.resolve(obj)
    s = sim.kb.semantics.get(ref.obj)
    handles = s.handles if s else []
    if purpose:
        tagged = [h for h in handles if purpose in h.get("purpose", [])]
        if tagged:
            return fold(tagged[0]["site"]), tagged[0].get("grip", "power")
    if handles:
        return fold(handles[0]["site"]), handles[0].get("grip", "power")
    return "", "power"


@dataclass
class Grasp(Command):
    """reach (the palm to the grasp site: by purpose, else the default handle); hold."""

    obj: str = ""
    hand: str = "right"
    purpose: str | None = None

    def expand(self, sim):
        ref = sim.kb.resolve(self.obj)
        site, grip = _handle(sim, self.obj, self.purpose)
        target = sim.kb.resolve(f"{ref.obj}.{site}") if site else ref
        return [st.Reach(self.agent, f"Reach {self.obj}", ref=target, side=self.hand, tip=False),
                st.Hold(self.agent, f"Hold {self.obj}", obj=ref.obj, side=self.hand, run={"grip": grip})]


@dataclass
class Hold(Command):
    obj: str = ""
    hand: str = "right"

    def expand(self, sim):
        return [st.Hold(self.agent, f"Hold {self.obj}", obj=sim.kb.resolve(self.obj).obj, side=self.hand)]


@dataclass
class Release(Command):
    hand: str = "right"

    def expand(self, sim):
        return [st.Release(self.agent, "Release", side=self.hand)]


@dataclass
class Position(Command):
    """Move the held object so its origin goes to a site (the hand follows), then hold it there
    (attached to the destination object)."""

    obj: str = ""
    dest: str = ""
    hand: str = "right"

    def expand(self, sim):
        ref = sim.kb.resolve(self.dest)
        obj = sim.kb.resolve(self.obj).obj
        pose = sim.env.figures[obj].location.copy()
        pose[:3, 3] = sim.kb.world(ref)
        return [st.Carry(self.agent, f"Position {self.obj}", obj=obj, pose=pose, side=self.hand),
                st.Release(self.agent, "Release", side=self.hand),
                st.Place(self.agent, f"Attach {self.obj} to {ref.obj}", obj=obj, pose=pose, supporter=ref.obj)]


@dataclass
class Move(Command):
    """grasp; position (the book's move-action)."""

    obj: str = ""
    dest: str = ""
    hand: str = "right"

    def expand(self, sim):
        return (Grasp(self.agent, self.obj, self.hand).expand(sim) +
                Position(self.agent, self.obj, self.dest, self.hand).expand(sim))


@dataclass
class Attach(Move):
    """grasp obj1; position it at obj2's site (attach-action: the same directives as move; obj1
    then stays with obj2)."""


@dataclass
class Put(Command):
    """put X on|in Y [at site] ([SH6] §6.2.4): resolve the resting pose first (fails with the
    reason: no horizontal support, not free, does not fit, not a container, upside down); then
    grasp X, carry it above the pose, lower it, release, place it (supported by Y) and return the
    hand to where it was."""

    obj: str = ""
    on: str | None = None
    in_: str | None = None
    at: str | None = None
    hand: str = "right"
    clearance_m: float = 0.05

    def expand(self, sim):
        x = sim.kb.resolve(self.obj).obj
        if (self.on is None) == (self.in_ is None):
            raise TaskError("put needs exactly one of on= or in_=")
        y = sim.kb.resolve(self.on or self.in_).obj
        if self.on is not None:
            at = None if self.at is None else sim.kb.world(sim.kb.resolve(self.at))
            pose, face = resting_pose(sim.kb, x, y, at, near=st.palm(sim, self.agent, self.hand))
        else:
            pose, face = container_pose(sim.kb, x, y), "bottom"
        home = st.palm(sim, self.agent, self.hand).copy()
        return Grasp(self.agent, self.obj, self.hand).expand(sim) + [
            st.Carry(self.agent, f"Carry {self.obj}", obj=x, pose=pose, side=self.hand, lift_m=self.clearance_m),
            st.Carry(self.agent, f"Lower {self.obj}", obj=x, pose=pose, side=self.hand),
            st.Release(self.agent, "Release", side=self.hand),
            st.Place(self.agent, f"Place {self.obj} {face} on {y}", obj=x, pose=pose, supporter=y),
            st.Reach(self.agent, "Return hand", point=home, side=self.hand, tip=False),
        ]

    @property
    def text(self):
        return f"Put {self.obj} {'on' if self.on else 'in'} {self.on or self.in_}"


@dataclass
class Turn(Command):
    """Reach the control with the fingertip and drive it to a state (``state``; ``on``/``off`` are
    states) or by ``degrees`` about its DOF axis."""

    control: str = ""
    state: str | None = None
    degrees: float | None = None
    hand: str = "right"

    def expand(self, sim):
        ref, c = sim.kb.control(self.control)
        if (self.state is None) == (self.degrees is None):
            raise TaskError("turn needs a state or degrees")
        if self.state is not None:
            c.value_of(self.state)
        return [st.Reach(self.agent, self.text, ref=ref, side=self.hand),
                st.SetControl(self.agent, f"Set {self.control}", control=c, state=self.state,
                              degrees=self.degrees, side=self.hand, run={"obj": ref.obj})]

    @property
    def text(self):
        return f"Turn {self.control}"


@dataclass
class Ratchet(Command):
    """``iterations`` × (turn +degrees; turn −degrees) of a control or tool (the book's
    ratchet-action; net rotation zero)."""

    control: str = ""
    degrees: float = 30.0
    iterations: int = 1
    hand: str = "right"

    def expand(self, sim):
        ref, c = sim.kb.control(self.control)
        out: list[st.Step] = [st.Reach(self.agent, f"Turn {self.control}", ref=ref, side=self.hand)]
        for i in range(self.iterations):
            for d in (self.degrees, -self.degrees):
                out.append(st.SetControl(self.agent, f"Ratchet {self.control} {d:+g}°", control=c, degrees=d,
                                         side=self.hand, run={"obj": ref.obj}))
        return out


@dataclass
class WalkTo(Command):
    """Walk to a place (issue 13): an object (stand in front of it, facing it), a site (stand
    beside it, facing it), another agent (stand ``AGENT_DISTANCE`` before them, facing them) or a
    floor point ``(x, z)``; the path goes round the scene's objects. One walk motion on the
    timeline; ``facing_deg`` (about +y, 0 faces +z) overrides the end heading."""

    place: str | tuple = ""
    facing_deg: float | None = None

    def expand(self, sim):
        if isinstance(self.place, str):
            ref = sim.kb.resolve(self.place)
            target = ref if ref.agent else (ref.obj if ref.site is None else f"{ref.obj}.{ref.site}")
        else:
            target = tuple(float(v) for v in self.place)
        return [WalkStep(self.agent, self.text, target=target, facing_deg=self.facing_deg)]

    @property
    def text(self):
        return f"Walk to {self.place}"


#: how far from another agent's pelvis centre a walk to that agent stops (m)
AGENT_DISTANCE = 0.8
#: a walk ends within this of its planned standing point (m), or it fails
ARRIVE_TOLERANCE_M = 0.05


@dataclass
class WalkStep(st.Step):
    """generate-motion of the whole figure: footsteps planned when the step starts, from where
    the agent stands then, round the scene's objects (:func:`jackpy.locomotion.walk_target.plan`),
    as one walk motion; it lasts the walk plus two frames (the walk's post-action, after which
    the agent's behaviors run again)."""

    target: object = None
    facing_deg: float | None = None

    def begin(self, sim, t):
        import numpy as np

        from jackpy.errors import JackpyError
        from jackpy.locomotion import walk_target
        from jackpy.locomotion.walk_gait import GaitParams
        from jackpy.motion.kinds.walk import WalkMotion
        from jackpy.tasks.kb import Ref

        fig = sim.loops[self.agent].figure
        objects = [f for n, f in sorted(sim.env.figures.items()) if n not in sim.loops and hasattr(f, "mesh")]
        facing = None if self.facing_deg is None else float(np.radians(self.facing_deg))
        target = self.target
        if isinstance(target, Ref):  # another agent: a point before them, facing them
            me = fig.site_world("pelvis", "centre")[:3, 3][[0, 2]]
            them = sim.loops[target.obj].figure.site_world("pelvis", "centre")[:3, 3][[0, 2]]
            d = them - me
            n = float(np.linalg.norm(d))
            if n <= AGENT_DISTANCE:
                raise TaskError(f"{self.agent} is already beside {target.obj}")
            target = tuple(them - AGENT_DISTANCE * d / n)
            facing = float(np.arctan2(d[0], d[1])) if facing is None else facing
        p = GaitParams.for_figure(fig)
        try:
            steps, _, goal = walk_target.plan(fig, p, target, objects, facing=facing)
        except JackpyError as exc:
            raise TaskError(f"{self.agent} cannot {self.label.lower()}: {exc}") from None
        m = sim.timeline.add(WalkMotion.of_steps(self.agent, steps, p, t0=t, label=self.label))
        self.run["goal"] = goal.point
        return (m.t1 - m.t0) + 2.0 * sim.dt

    def finish(self, sim, t):
        import numpy as np

        c = sim.loops[self.agent].figure.site_world("pelvis", "centre")[:3, 3]
        err = float(np.hypot(c[0] - self.run["goal"][0], c[2] - self.run["goal"][1]))
        self.run["error_m"] = err
        if err > ARRIVE_TOLERANCE_M:
            raise TaskError(f"{self.agent} stopped {err * 100:.1f} cm from where {self.label.lower()} should end")
        return []
