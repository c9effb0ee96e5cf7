"""A motion: a scripted change to the constraints and behaviors of one body part of one figure
over [t0, t1] ([SH4] §4.3; [PB91] §6; behaviors.md §4.1, §4.6).

A motion never sets joint angles. It has three phases, run by :class:`~jackpy.motion.timeline.Timeline`:

1. ``pre(ctx)`` at t0: activate its constraint or behavior; the start goal is the part's pose *at
   run time* (the posture when the motion begins, not when it was authored);
2. ``sample(ctx, s)`` every step after t0 up to and including t1: the goal at progress ``s`` (from the
   velocity function) along the path; the timeline blends the samples of all motions active on one
   part by their current weights (``weight`` x weight function) and calls ``write`` once per part;
3. ``post(ctx)`` at t1 after the last step: deactivate.

Each kind (``com``, ``pelvis``, ``torso``, ``foot``, ``heel``, ``arm``, ``gaze``) is one module that
registers its class with :func:`register`. A motion's parameters are dataclass fields (JSON-ready
through ``to_dict``/``from_dict``); what it learns at run time lives in ``run`` (plain data, so a
baked state can be copied and restored).
"""

from __future__ import annotations

from dataclasses import MISSING, dataclass, field, fields
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from jackpy import jsonfile
from jackpy.motion.functions import VELOCITY_FUNCTIONS, WEIGHT_FUNCTIONS
from jackpy.motion.interpolate import mean_array

if TYPE_CHECKING:
    from jackpy.behaviors.loop import BehaviorLoop
    from jackpy.peabody.model import Environment, Figure

#: motion kinds by name (filled by :func:`register`)
KINDS: dict[str, type["Motion"]] = {}


def register(cls: type["Motion"]) -> type["Motion"]:
    """Class decorator: make a motion kind known to files and the timeline by its ``kind``."""
    KINDS[cls.kind] = cls
    return cls


@dataclass
class Context:
    """What a motion acts on at one step: the figure's behavior loop, the environment (objects a
    target may be relative to) and the names of the parts with a motion active this step."""

    loop: "BehaviorLoop"
    env: "Environment"
    active: set[str] = field(default_factory=set)

    @property
    def figure(self) -> "Figure":
        return self.loop.figure


@dataclass
class Motion:
    """Fields every motion has: ``figure`` (name), ``t0``/``t1`` (s), ``weight`` (the maximum
    weight), ``weight_fn``/``velocity_fn`` (see :mod:`jackpy.motion.functions`), ``enabled`` and a
    ``label`` shown on its bar."""

    kind: ClassVar[str] = ""
    #: False for motions without a constraint (torso): no weight, no overlap on one part
    weighted: ClassVar[bool] = True

    figure: str = ""
    t0: float = 0.0
    t1: float = 1.0
    weight: float = 1.0
    weight_fn: str = "constant"
    velocity_fn: str = "constant"
    enabled: bool = True
    label: str = ""
    run: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self) -> None:
        self.check()

    # ----- what a kind provides ---------------------------------------------------------------------
    @property
    def part(self) -> str:
        """The body part this motion moves (its track): ``com``, ``pelvis``, ``foot.left``..."""
        return self.kind

    def pre(self, ctx: Context) -> None:
        """Activate at t0: remember the start goal (the current pose) in ``run``."""

    def sample(self, ctx: Context, s: float) -> Any:
        """The goal at progress ``s`` in [0, 1] along the path."""
        raise NotImplementedError

    def blend(self, values: list[Any], weights: list[float]) -> Any:
        """Weighted mean of several motions' goals on this part (arrays by default): the optimum
        of their constraints of those weights on one site."""
        return mean_array(values, weights)

    def write(self, ctx: Context, value: Any, weight: float) -> None:
        """Move the part's goal (in the loop's state or a user goal) to ``value``."""
        raise NotImplementedError

    def post(self, ctx: Context) -> None:
        """Deactivate after the last step at t1."""

    # ----- checks and files -----------------------------------------------------------------------------
    def check(self) -> None:
        """Raise ValueError naming the field for a parameter out of range."""
        if not (np.isfinite(self.t0) and np.isfinite(self.t1)) or self.t1 < self.t0:
            raise ValueError(f"{self.kind} motion: needs t0 <= t1 (s), got [{self.t0}, {self.t1}]")
        if self.t0 < 0:
            raise ValueError(f"{self.kind} motion: t0 must be >= 0 s, got {self.t0}")
        if not self.weight >= 0:
            raise ValueError(f"{self.kind} motion: weight must be >= 0, got {self.weight}")
        if self.weight_fn not in WEIGHT_FUNCTIONS:
            raise ValueError(f"{self.kind} motion: weight_fn must be one of {WEIGHT_FUNCTIONS}, not {self.weight_fn!r}")
        if self.velocity_fn not in VELOCITY_FUNCTIONS:
            raise ValueError(f"{self.kind} motion: velocity_fn must be one of {VELOCITY_FUNCTIONS}, "
                             f"not {self.velocity_fn!r}")

    def to_dict(self) -> dict[str, Any]:
        """The motion as JSON-ready data (``kind`` first; arrays as lists)."""
        out: dict[str, Any] = {"kind": self.kind}
        for f in fields(self):
            if f.name == "run":
                continue
            v = getattr(self, f.name)
            out[f.name] = v.tolist() if isinstance(v, np.ndarray) else v
        return out

    @classmethod
    def from_dict(cls, d: dict[str, Any], where: str = "motion") -> "Motion":
        """A motion from :meth:`to_dict` data; :class:`jsonfile.Invalid` names the key path at fault."""
        d = jsonfile.obj(d, where)
        kind = jsonfile.string(jsonfile.required(d, "kind", where), jsonfile.key(where, "kind"), tuple(KINDS))
        klass = KINDS[kind]
        known = {f.name: f for f in fields(klass) if f.name != "run"}
        kwargs: dict[str, Any] = {}
        for name, v in d.items():
            if name == "kind":
                continue
            if name not in known:
                raise jsonfile.Invalid(jsonfile.key(where, name), f"unknown field of a {kind} motion "
                                       f"(fields: {', '.join(known)})")
            kwargs[name] = _field_value(known[name], v, jsonfile.key(where, name))
        for name, f in known.items():
            if f.default is MISSING and f.default_factory is MISSING and name not in kwargs:
                raise jsonfile.Invalid(jsonfile.key(where, name), "missing")
        try:
            return klass(**kwargs)
        except ValueError as exc:
            raise jsonfile.Invalid(where, str(exc)) from None


def _field_value(f: Any, v: Any, where: str) -> Any:
    """Check a JSON value against a dataclass field's default type."""
    default = f.default if f.default is not MISSING else (f.default_factory() if f.default_factory is not MISSING
                                                          else None)
    if isinstance(default, bool):
        return jsonfile.boolean(v, where)
    if isinstance(default, (int, float)) and not isinstance(default, bool):
        return jsonfile.num(v, where)
    if isinstance(default, str):
        return jsonfile.string(v, where)
    if v is None:
        return None
    if isinstance(v, list):
        return _numbers(v, where)
    if isinstance(v, dict):
        return v
    return v


def _numbers(v: list, where: str) -> list:
    """A (nested) list of finite numbers."""
    out = []
    for k, x in enumerate(v):
        out.append(_numbers(x, jsonfile.key(where, k)) if isinstance(x, list) else jsonfile.num(x, jsonfile.key(where, k)))
    return out


# ----------------------------------------------------------------------------- targets
class FrameRef:
    """A moving frame a target is relative to: ``"object"`` (a CAD object or any figure of the
    environment: its location) or ``"figure.segment"`` (a segment's base frame). ``pose`` is its
    world 4x4 now, so a hand goal held relative to it follows it (the doorknob model)."""

    def __init__(self, env: "Environment", ref: str) -> None:
        self.env, self.ref = env, ref
        name, _, seg = ref.partition(".")
        if name not in env.figures:
            raise ValueError(f"no object or figure named {name!r} in the scene")
        self.figure = env.figures[name]
        self.segment = seg or None
        if self.segment is not None:
            self.figure.segment(self.segment)

    @property
    def pose(self) -> np.ndarray:
        if self.segment is None:
            return np.asarray(self.figure.location, dtype=float)
        return self.figure.world_transforms()[self.segment]

    def __deepcopy__(self, memo: dict) -> "FrameRef":
        return self  # refers to the scene, which a baked state does not copy


def target_pose(env: "Environment", target: dict[str, Any]) -> tuple[np.ndarray, FrameRef | None, np.ndarray]:
    """Resolve a target description into (world 4x4 now, the frame it is relative to or None, the
    4x4 in that frame). A target is ``{"point": [x, y, z]}`` (m) or ``{"site": "object.site"}`` or
    ``{"site": "figure.segment.site"}``, optionally with ``"relative_to": "object"`` or
    ``"figure.segment"`` (then ``point`` is in that frame and the target moves with it)."""
    rel = target.get("relative_to")
    frame = FrameRef(env, rel) if rel else None
    if "site" in target:
        parts = str(target["site"]).split(".")
        if len(parts) == 2:
            from jackpy.scene.workplace import resolve_target

            obj, _ = resolve_target(env, target["site"])
            world = obj.location @ obj.user_sites()[parts[1]].location
        elif len(parts) == 3:
            fig = env.figure(parts[0])
            world = fig.site_world(parts[1], parts[2])
        else:
            raise ValueError(f"site target must be object.site or figure.segment.site, not {target['site']!r}")
        if frame is None:
            return world, None, world
        return world, frame, np.linalg.inv(frame.pose) @ world
    if "point" not in target:
        raise ValueError("a target needs 'point' or 'site'")
    local = np.eye(4)
    local[:3, 3] = np.asarray(target["point"], dtype=float)[:3]
    if frame is None:
        return local, None, local
    return frame.pose @ local, frame, local
