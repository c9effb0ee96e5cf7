"""The timeline: every motion, timed behavior and key track of a scene, run against the figures'
behavior loops ([SH4] §4.3; behaviors.md §4.1, §4.6).

:meth:`Timeline.apply` at time ``t`` (s) runs one step across all motions in the book's order:

1. **motion**: each active motion samples its goal at its progress ``s(u)``; motions on one part of
   one figure blend by their current weights (``weight`` x weight function) and the part's goal is
   written once (into the loop's state, or a user goal of the loop);
2. **post-action** of each motion whose last step (the first at or after t1, at u = 1) was the step
   before, so its final goal has been solved; of each timed behavior whose end time has come;
3. **pre-action** of each motion (and timed behavior) whose start time has come (t >= t0): it
   activates its constraint with the start goal taken from the posture *now*;

then the key tracks write their interpolated targets. It never sets joint angles (except a torso
motion's spine bend, which the book does by forward kinematics, and joint-angle key tracks); the
caller then steps each loop (goals -> behaviors -> IK -> FK). ``apply`` is meant for increasing
``t``; going back, items that had not started by ``t`` become pending again, but an exact replay
from an earlier time needs the figures' state of then (:class:`jackpy.motion.bake.Baker` keeps it).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from jackpy import jsonfile
from jackpy.motion.base import KINDS, Context, Motion
from jackpy.motion.functions import normalised_time, progress, weight_factor
from jackpy.motion.keyframes import KeyTrack
from jackpy.motion.timed import TimedBehavior

if TYPE_CHECKING:
    from jackpy.behaviors.loop import BehaviorLoop
    from jackpy.peabody.model import Environment

PENDING, ACTIVE, DONE = "pending", "active", "done"


def load_kinds() -> None:
    """Register every motion kind (they live in :mod:`jackpy.motion.kinds`)."""
    from jackpy.motion.kinds import load_all

    load_all()


@dataclass
class Timeline:
    """Motions, timed behaviors and key tracks; ``cast`` optionally says how to make each figure
    (``{"NAME": {"human": "male:50", "position": [x, z], "heading_deg": 0}}``); ``span`` is the
    visible width of the timeline panel (s; 3 s at first, as in Jack)."""

    motions: list[Motion] = field(default_factory=list)
    timed: list[TimedBehavior] = field(default_factory=list)
    tracks: list[KeyTrack] = field(default_factory=list)
    cast: dict[str, dict[str, Any]] = field(default_factory=dict)
    explicit_duration: float | None = None
    span: float = 3.0
    _last_t: float | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        load_kinds()
        self.validate()

    # ----- contents ---------------------------------------------------------------------------------
    @property
    def duration(self) -> float:
        """Length (s): the explicit duration, else the latest end of any item (0 when empty)."""
        if self.explicit_duration is not None:
            return float(self.explicit_duration)
        ends = [m.t1 for m in self.motions] + [b.t1 for b in self.timed] + [k.span[1] for k in self.tracks if k.keys]
        return float(max(ends, default=0.0))

    @duration.setter
    def duration(self, value: float | None) -> None:
        self.explicit_duration = None if value is None else float(value)

    def figures(self) -> list[str]:
        """Names of the figures the timeline drives, in first-use order."""
        out: list[str] = list(self.cast)
        for item in [*self.motions, *self.timed, *self.tracks]:
            if item.figure not in out:
                out.append(item.figure)
        return out

    def add(self, item: Motion | TimedBehavior | KeyTrack) -> Motion | TimedBehavior | KeyTrack:
        """Add a motion, timed behavior or key track (a torso motion may not overlap another)."""
        if isinstance(item, Motion):
            self.motions.append(item)
        elif isinstance(item, TimedBehavior):
            self.timed.append(item)
        elif isinstance(item, KeyTrack):
            self.tracks.append(item)
        else:
            raise TypeError(f"cannot add {type(item).__name__} to a timeline")
        try:
            self.validate()
        except ValueError:
            self.remove(item)
            raise
        return item

    def remove(self, item: Motion | TimedBehavior | KeyTrack) -> None:
        for lst in (self.motions, self.timed, self.tracks):
            for k, x in enumerate(lst):
                if x is item:
                    del lst[k]
                    return
        raise KeyError("item is not on this timeline")

    def track(self, figure: str, part: str, create: bool = True) -> KeyTrack | None:
        """The key track of ``part`` of ``figure`` (made when missing, with ``create``)."""
        for k in self.tracks:
            if k.figure == figure and k.part == part:
                return k
        if not create:
            return None
        return self.add(KeyTrack(figure, part))  # type: ignore[return-value]

    def set_key(self, loop: "BehaviorLoop", part: str, t: float) -> KeyTrack:
        """"Set key": store ``part``'s current target (read from the figure) at time ``t``."""
        from jackpy.motion.keyframes import capture

        tr = self.track(loop.figure.name, part)
        tr.set_key(t, capture(loop, part))
        return tr

    def validate(self) -> None:
        """Raise ValueError when two unweighted (torso) motions of one figure overlap in time."""
        unweighted: dict[tuple[str, str], list[Motion]] = {}
        for m in self.motions:
            if m.enabled and not m.weighted:
                unweighted.setdefault((m.figure, m.part), []).append(m)
        for (fig, part), ms in unweighted.items():
            ms = sorted(ms, key=lambda m: m.t0)
            for a, b in zip(ms, ms[1:]):
                if b.t0 < a.t1:
                    raise ValueError(f"{part} motions of {fig} may not overlap: [{a.t0:g}, {a.t1:g}] s and "
                                     f"[{b.t0:g}, {b.t1:g}] s (a {part} motion uses no constraint to blend)")

    def load_dict(self, d: dict[str, Any]) -> None:
        """Replace the contents with :meth:`to_dict` data, in place (undo keeps this object)."""
        other = Timeline.from_dict(d)
        self.motions, self.timed, self.tracks = other.motions, other.timed, other.tracks
        self.cast, self.explicit_duration, self.span = other.cast, other.explicit_duration, other.span
        self._last_t = None

    # ----- running ----------------------------------------------------------------------------------
    def items(self) -> list[Motion | TimedBehavior]:
        """Motions then timed behaviors, each with a ``run`` dict holding its phase."""
        return [*self.motions, *self.timed]

    def reset(self) -> None:
        """Forget what ran: every item pending again (the figures are not touched)."""
        for item in self.items():
            item.run.clear()
        self._last_t = None

    def apply(self, t: float, loops: Mapping[str, "BehaviorLoop"], env: "Environment") -> None:
        """One step at time ``t`` (s): motion -> post-action -> pre-action, then key tracks."""
        t = float(t)
        if self._last_t is not None and t < self._last_t:
            for item in self.items():
                if item.run.get("phase", PENDING) != PENDING and item.t0 > t:
                    item.run.clear()
        self._last_t = t
        ctxs = {name: Context(loop, env) for name, loop in loops.items()}
        motions = [m for m in self.motions if m.enabled and m.figure in ctxs]
        timed = [b for b in self.timed if b.enabled and b.figure in ctxs]
        active = [m for m in motions if m.run.get("phase") == ACTIVE]
        # motions whose last step (at u = 1) was an earlier step end now, after that step's solve
        ending = [m for m in active if m.run.get("last")]
        moving = [m for m in active if not m.run.get("last")]
        # 1. motion functions, blended per (figure, part)
        groups: dict[tuple[str, str], list[tuple[Motion, Any, float]]] = {}
        for m in moving:
            if t >= m.t1:
                m.run["last"] = True
            u = normalised_time(t, m.t0, m.t1)
            w = m.weight * weight_factor(m.weight_fn, u) if m.weighted else 1.0
            ctx = ctxs[m.figure]
            groups.setdefault((m.figure, m.part), []).append((m, m.sample(ctx, progress(m.velocity_fn, u)), w))
        for (fig, _), entries in groups.items():
            first = entries[0][0]
            values, weights = [e[1] for e in entries], [e[2] for e in entries]
            value = values[0] if len(entries) == 1 else first.blend(values, weights)
            first.write(ctxs[fig], value, max(weights))
        # 2. post-actions
        still = {(m.figure, m.part) for m in moving}
        for name, ctx in ctxs.items():
            ctx.active = {p for f, p in still if f == name}
        for m in ending:
            m.post(ctxs[m.figure])
            m.run["phase"] = DONE
        for b in timed:
            if b.run.get("phase") == ACTIVE and t >= b.t1:
                b.post(ctxs[b.figure].loop, env)
                b.run["phase"] = DONE
        # 3. pre-actions
        for m in sorted((m for m in motions if m.run.get("phase", PENDING) == PENDING and t >= m.t0),
                        key=lambda m: m.t0):
            m.pre(ctxs[m.figure])
            m.run["phase"] = ACTIVE
            ctxs[m.figure].active.add(m.part)
        for b in sorted((b for b in timed if b.run.get("phase", PENDING) == PENDING and t >= b.t0),
                        key=lambda b: b.t0):
            b.pre(ctxs[b.figure].loop, env)
            b.run["phase"] = ACTIVE
        for k in self.tracks:
            if k.figure in loops:
                k.apply(loops[k.figure], t)

    # ----- files ------------------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """JSON-ready data (the ``timeline`` of a motion file or a saved document)."""
        out: dict[str, Any] = {
            "motions": [m.to_dict() for m in self.motions],
            "timed": [b.to_dict() for b in self.timed],
            "keyframes": [k.to_dict() for k in self.tracks],
            "span": self.span,
        }
        if self.cast:
            out["figures"] = self.cast
        if self.explicit_duration is not None:
            out["duration"] = self.explicit_duration
        return out

    @classmethod
    def from_dict(cls, d: dict[str, Any], where: str = "") -> "Timeline":
        """A timeline from :meth:`to_dict` data; :class:`jsonfile.Invalid` names the key path at fault."""
        load_kinds()
        d = jsonfile.obj(d, where)
        known = {"motions", "timed", "keyframes", "figures", "duration", "span"}
        for k in d:
            if k not in known:
                raise jsonfile.Invalid(jsonfile.key(where, k), f"unknown key (known: {', '.join(sorted(known))})")
        mw, tw, kw = jsonfile.key(where, "motions"), jsonfile.key(where, "timed"), jsonfile.key(where, "keyframes")
        motions = [Motion.from_dict(x, jsonfile.key(mw, i)) for i, x in enumerate(jsonfile.arr(d.get("motions", []), mw))]
        timed = [TimedBehavior.from_dict(x, jsonfile.key(tw, i))
                 for i, x in enumerate(jsonfile.arr(d.get("timed", []), tw))]
        tracks = [KeyTrack.from_dict(x, jsonfile.key(kw, i))
                  for i, x in enumerate(jsonfile.arr(d.get("keyframes", []), kw))]
        fw = jsonfile.key(where, "figures")
        cast = {}
        for name, spec in jsonfile.obj(d.get("figures", {}), fw).items():
            cast[name] = _cast_entry(spec, jsonfile.key(fw, name))
        duration = d.get("duration")
        if duration is not None:
            duration = jsonfile.num(duration, jsonfile.key(where, "duration"), 0.0)
        span = jsonfile.num(d.get("span", 3.0), jsonfile.key(where, "span"), 1e-3)
        try:
            return cls(motions, timed, tracks, cast, duration, span)
        except ValueError as exc:
            raise jsonfile.Invalid(mw, str(exc)) from None


def _cast_entry(spec: Any, where: str) -> dict[str, Any]:
    spec = jsonfile.obj(spec, where)
    human = jsonfile.string(spec.get("human", "male:50"), jsonfile.key(where, "human"))
    pos = jsonfile.vector(spec.get("position", [0.0, 0.0]), jsonfile.key(where, "position"), 2)
    heading = jsonfile.num(spec.get("heading_deg", 0.0), jsonfile.key(where, "heading_deg"))
    return {"human": human, "position": [float(pos[0]), float(pos[1])], "heading_deg": heading}




load_kinds()
__all__ = ["KINDS", "Timeline"]
