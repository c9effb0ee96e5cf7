"""Timed behaviors ([SH4] §4.4.1, §4.4.5, §4.4.8; behaviors.md §4.5): a behavior setting held over
[t0, t1] that reverts at t1 to the value it had when it started.

``control`` names what is set (``value`` in brackets):

- ``support``: the figure support [``"left"``, ``"right"`` foot or ``"pelvis"``] (timed figure support);
- ``balance``: balance control on or off [true/false];
- ``torso``: the torso control [``"vertical"``, ``"hold"``, ``"bend"``] (timed torso control);
- ``hand.left`` / ``hand.right``: hand control [``"hold"`` where it is, ``"hold:OBJECT"`` relative to an
  object or ``figure.segment``, ``"release"``] (timed hand control);
- ``head``: head fixation [a point [x, y, z] or null] (timed head control);
- ``foot.left`` / ``foot.right``: foot control [``{"mode": "pivot"|"hold", "heel": "floor"|"free"}``]
  (timed foot control);
- ``attach.left`` / ``attach.right``: an object carried by the hand [its name] (timed attachment);
- ``behavior.NAME.enabled`` / ``behavior.NAME.PARAM``: any behavior's switch or parameter.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy import jsonfile
from jackpy.behaviors import manipulation as m

if TYPE_CHECKING:
    from jackpy.behaviors.loop import BehaviorLoop
    from jackpy.peabody.model import Environment

CONTROLS = ("support", "balance", "torso", "hand", "head", "foot", "attach", "behavior")


def _get(loop: "BehaviorLoop", env: "Environment", control: str) -> Any:
    base, _, arg = control.partition(".")
    st = loop.state
    if base == "support":
        return [st.root, st.root_claimed]
    if base == "balance":
        return loop.behavior("balance").enabled
    if base == "torso":
        return [st.torso_mode, None if st.torso_goal is None else st.torso_goal.tolist()]
    if base == "hand":
        hs = st.hands[arg]
        return copy.copy(hs.__dict__)
    if base == "head":
        return None if st.head_target is None else st.head_target.tolist()
    if base == "foot":
        fs = st.feet[arg]
        return {"mode": fs.mode, "heel": fs.heel}
    if base == "attach":
        return None
    if base == "behavior":
        name, _, prm = arg.partition(".")
        b = loop.behavior(name)
        return b.enabled if prm == "enabled" else getattr(b.params, prm)
    raise ValueError(f"unknown timed control {control!r} (one of {', '.join(CONTROLS)})")


def _set(loop: "BehaviorLoop", env: "Environment", control: str, value: Any, reverting: bool) -> None:
    base, _, arg = control.partition(".")
    st = loop.state
    if base == "support":
        if reverting:
            root, claimed = value
            loop.set_root(root)
            st.root_claimed = claimed
        else:
            loop.set_root(value)
            st.root_claimed = True
    elif base == "balance":
        loop.behavior("balance").enabled = bool(value)
    elif base == "torso":
        if reverting:
            st.torso_mode = value[0]
            st.torso_goal = None if value[1] is None else np.array(value[1])
        else:
            m.set_torso_behavior(loop, value)
    elif base == "hand":
        if reverting:
            loop.state.hands[arg].__dict__.update(value)
        elif value == "release":
            m.release_hand(loop, arg)
        elif value == "hold":
            _hold_hand(loop, arg, None)
        elif isinstance(value, str) and value.startswith("hold:"):
            from jackpy.motion.base import FrameRef

            _hold_hand(loop, arg, FrameRef(env, value[5:]))
        else:
            raise ValueError(f"hand control must be 'hold', 'hold:OBJECT' or 'release', not {value!r}")
    elif base == "head":
        m.move_head(loop, None if value is None else np.asarray(value, dtype=float))
    elif base == "foot":
        m.set_foot_behavior(loop, arg, value.get("mode"), value.get("heel"))
    elif base == "attach":
        if reverting:
            obj = env.figure(value)
            hs = loop.state.hands[arg]
            hs.attached = [a for a in hs.attached if not (isinstance(a.obj, _Carried) and a.obj.obj is obj)]
        else:
            m.grab(loop, arg, _Carried(env.figure(value)))
    elif base == "behavior":
        name, _, prm = arg.partition(".")
        b = loop.behavior(name)
        if prm == "enabled":
            b.enabled = bool(value)
        else:
            setattr(b.params, prm, value)


def _hold_hand(loop: "BehaviorLoop", side: str, frame: Any) -> None:
    """Hold hand ``side``'s palm where it is: in the world, or relative to ``frame`` (with a
    ``pose``; the hand then follows it)."""
    hs = loop.state.hands[side]
    palm = loop.figure.site_world(*loop.anatomy.hands[side].palm)
    hs.goal, hs.orient, hs.rules, hs.lean = palm.copy(), True, False, False
    hs.local = frame
    hs.local_offset = None if frame is None else np.linalg.inv(frame.pose) @ palm


class _Carried:
    """An environment object as the hands behavior carries it (its ``pose`` is its location)."""

    def __init__(self, obj: Any) -> None:
        self.obj = obj

    @property
    def pose(self) -> np.ndarray:
        return self.obj.location

    @pose.setter
    def pose(self, value: np.ndarray) -> None:
        self.obj.location = np.asarray(value, dtype=float).copy()

    def __deepcopy__(self, memo: dict) -> "_Carried":
        return self


@dataclass
class TimedBehavior:
    """``control`` set to ``value`` on figure ``figure`` over [t0, t1] (s), reverting at t1."""

    figure: str
    control: str
    value: Any
    t0: float = 0.0
    t1: float = 1.0
    enabled: bool = True
    label: str = ""
    run: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.control.partition(".")[0] not in CONTROLS:
            raise ValueError(f"unknown timed control {self.control!r} (one of {', '.join(CONTROLS)})")
        if not (np.isfinite(self.t0) and np.isfinite(self.t1)) or self.t1 < self.t0 or self.t0 < 0:
            raise ValueError(f"timed {self.control}: needs 0 <= t0 <= t1 (s), got [{self.t0}, {self.t1}]")

    @property
    def part(self) -> str:
        return f"timed {self.control}"

    def pre(self, loop: "BehaviorLoop", env: "Environment") -> None:
        """Save the current setting and apply ``value``."""
        self.run["saved"] = _get(loop, env, self.control)
        _set(loop, env, self.control, self.value, reverting=False)

    def post(self, loop: "BehaviorLoop", env: "Environment") -> None:
        """Revert to the saved setting (a timed attachment releases its object)."""
        if self.control.startswith("attach."):
            _set(loop, env, self.control, self.value, reverting=True)
        else:
            _set(loop, env, self.control, self.run["saved"], reverting=True)

    def to_dict(self) -> dict[str, Any]:
        return {"figure": self.figure, "control": self.control, "value": self.value, "t0": self.t0,
                "t1": self.t1, "enabled": self.enabled, "label": self.label}

    @classmethod
    def from_dict(cls, d: dict[str, Any], where: str = "timed") -> "TimedBehavior":
        d = jsonfile.obj(d, where)
        unknown = set(d) - {"figure", "control", "value", "t0", "t1", "enabled", "label"}
        if unknown:
            raise jsonfile.Invalid(jsonfile.key(where, sorted(unknown)[0]), "unknown field of a timed behavior")
        try:
            return cls(jsonfile.string(jsonfile.required(d, "figure", where), jsonfile.key(where, "figure")),
                       jsonfile.string(jsonfile.required(d, "control", where), jsonfile.key(where, "control")),
                       jsonfile.required(d, "value", where),
                       jsonfile.num(d.get("t0", 0.0), jsonfile.key(where, "t0")),
                       jsonfile.num(d.get("t1", 1.0), jsonfile.key(where, "t1")),
                       jsonfile.boolean(d.get("enabled", True), jsonfile.key(where, "enabled")),
                       jsonfile.string(d.get("label", ""), jsonfile.key(where, "label")))
        except ValueError as exc:
            raise jsonfile.Invalid(where, str(exc)) from None
