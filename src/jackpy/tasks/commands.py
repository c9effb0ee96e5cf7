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
    """Walk to a place: needs the walking issue (13); until it lands the command fails saying so."""

    place: str = ""

    def expand(self, sim):
        return [st.Fail(self.agent, f"Walk to {self.place}",
                        reason=f"{self.agent} cannot walk to {self.place}: walking is not available yet "
                               "(issue 13); place the agent with a stand instead")]
