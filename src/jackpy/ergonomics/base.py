"""The assessment registry, the task parameters, the result type and the error of the package.

An assessment is one module of :mod:`jackpy.ergonomics` that calls :func:`register` with a
:class:`Method`; :func:`methods` imports every module of the package once, so a new assessment is one
new file. ``Method.assess(figure, task, posture, fk)`` returns an :class:`Assessment`.
"""

from __future__ import annotations

import importlib
import math
import pkgutil
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, fields
from typing import Any

from jackpy.errors import JackpyError
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure


class ErgonomicsError(JackpyError):
    """Bad task parameters or an unknown method: names the parameter and what is allowed."""

    exit_code = 2


@dataclass
class Lift:
    """One NIOSH lifting task (Waters et al. 1993). Lengths in cm, angles in degrees, load in kg.

    ``h``, ``v``, ``a`` at the origin are measured from the posture when left ``None``; the
    destination's ``dest_h``/``dest_v``/``dest_a`` are given (or ``None``: the destination is
    not assessed and ``d`` must be given). ``d`` defaults to ``|dest_v - v|``. ``frequency`` in lifts
    per minute, ``duration_h`` the work duration (<= 1, <= 2 or <= 8 h). ``coupling``: ``good``,
    ``fair``, ``poor`` or ``auto`` (from ``container``, ``optimal_object`` / ``optimal_handles`` and the
    finger flexion measured on the holding hand, the manual's decision tree)."""

    load_kg: float = 0.0
    h: float | None = None
    v: float | None = None
    a: float | None = None
    d: float | None = None
    dest_h: float | None = None
    dest_v: float | None = None
    dest_a: float | None = None
    frequency: float = 0.2
    duration_h: float = 1.0
    coupling: str = "auto"
    container: bool = True
    optimal_object: bool = True
    optimal_handles: bool = True
    name: str = ""


@dataclass
class Task:
    """Task parameters shared by the methods (kg, booleans; see docs/ergonomics.md for each).

    ``load_kg``: load in the hands (total); ``side``: the arm RULA/REBA score (``left``, ``right`` or
    ``worst``); ``static``: a posture held longer than a minute; ``repeated``: repeated 4 times a
    minute or more; ``shock``: shock or rapidly building force; ``arm_supported``: the arm is supported
    or the person leans; ``seated``: sitting (OWAS legs 1, REBA legs); ``seated_supported``: seated with
    the trunk well supported (RULA trunk 1); ``walking``: OWAS legs 7; ``coupling``: REBA hand
    coupling (good/fair/poor/unacceptable); ``rapid_change``: REBA's rapid large posture changes or
    unstable base; ``overrides``: adjustment name -> bool, replacing what the posture gives (e.g.
    ``{"shoulder_raised": true}``; names in docs/ergonomics.md); ``lifts``: NIOSH lifting tasks
    (several: the composite lifting index); ``sex``: percent capable population (``male``,
    ``female``, or ``both``)."""

    load_kg: float = 0.0
    side: str = "worst"
    static: bool = False
    repeated: bool = False
    shock: bool = False
    arm_supported: bool = False
    seated: bool = False
    seated_supported: bool = False
    walking: bool = False
    coupling: str = "good"
    rapid_change: bool = False
    overrides: dict[str, bool] = field(default_factory=dict)
    lifts: list[Lift] = field(default_factory=list)
    sex: str = "both"

    def __post_init__(self) -> None:
        self.validate()

    def validate(self) -> None:
        """Raise :class:`ErgonomicsError` for a value no method can score."""
        _non_negative("load_kg", self.load_kg)
        _choice("side", self.side, ("left", "right", "worst"))
        _choice("coupling", self.coupling, ("good", "fair", "poor", "unacceptable"))
        _choice("sex", self.sex, ("male", "female", "both"))
        for k, v in self.overrides.items():
            if not isinstance(v, bool):
                raise ErgonomicsError(f"task overrides.{k}: expected true or false, got {v!r}")

    @classmethod
    def from_dict(cls, d: Mapping[str, Any], where: str = "task") -> "Task":
        """A task from JSON-like data; unknown keys and wrong types raise :class:`ErgonomicsError`."""
        if not isinstance(d, Mapping):
            raise ErgonomicsError(f"{where}: expected an object, got {type(d).__name__}")
        known = {f.name: f for f in fields(cls)}
        kw: dict[str, Any] = {}
        for k, v in d.items():
            if k not in known:
                raise ErgonomicsError(f"{where}: unknown key {k!r} (known: {', '.join(sorted(known))})")
            if k == "lifts":
                if not isinstance(v, list):
                    raise ErgonomicsError(f"{where}.lifts: expected a list of lifting tasks")
                kw[k] = [_lift(x, f"{where}.lifts[{i}]") for i, x in enumerate(v)]
            elif k == "overrides":
                if not isinstance(v, Mapping):
                    raise ErgonomicsError(f"{where}.overrides: expected an object of name: true/false")
                kw[k] = dict(v)
            else:
                kw[k] = _typed(f"{where}.{k}", v, known[k].type)
        return cls(**kw)


def _typed(where: str, v: Any, kind: Any) -> Any:
    kind = str(kind)
    if kind.startswith("bool"):
        if not isinstance(v, bool):
            raise ErgonomicsError(f"{where}: expected true or false, got {v!r}")
        return v
    if kind.startswith("float"):
        if v is None and "None" in kind:
            return None
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise ErgonomicsError(f"{where}: expected a number, got {v!r}")
        return float(v)
    if kind.startswith("str"):
        if not isinstance(v, str):
            raise ErgonomicsError(f"{where}: expected a string, got {v!r}")
        return v
    return v


def _lift(d: Any, where: str) -> Lift:
    if not isinstance(d, Mapping):
        raise ErgonomicsError(f"{where}: expected an object")
    known = {f.name: f for f in fields(Lift)}
    kw = {}
    for k, v in d.items():
        if k not in known:
            raise ErgonomicsError(f"{where}: unknown key {k!r} (known: {', '.join(sorted(known))})")
        kw[k] = _typed(f"{where}.{k}", v, known[k].type)
    return Lift(**kw)


def _non_negative(name: str, v: float) -> None:
    if not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0:
        raise ErgonomicsError(f"task {name}: must be a number >= 0, got {v!r}")


def _choice(name: str, v: str, allowed: tuple[str, ...]) -> None:
    if v not in allowed:
        raise ErgonomicsError(f"task {name}: {v!r} is not one of {', '.join(allowed)}")


@dataclass
class Assessment:
    """What one method found.

    ``score``: the method's result (RULA grand score, REBA score, OWAS action category, NIOSH lifting
    index, L5/S1 compression in N, lowest percent capable); ``level`` and ``action``: its action level
    and what the method says to do; ``worksheet``: every intermediate value the method's worksheet
    shows; ``posture``: the measurements it used (degrees, frame in ``frame``); ``flags``: inputs outside
    the method's validity range or judgments it cannot measure (never silently scored);
    ``worst``: the body part or joint contributing most (for highlighting)."""

    method: str
    score: float
    level: int | None
    action: str
    worksheet: dict[str, Any]
    posture: dict[str, Any]
    frame: str
    flags: list[str] = field(default_factory=list)
    worst: str | None = None
    unit: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"method": self.method, "score": self.score, "unit": self.unit, "level": self.level,
                "action": self.action, "worst": self.worst, "worksheet": self.worksheet,
                "posture": self.posture, "frame": self.frame, "flags": list(self.flags)}


AssessFn = Callable[[Figure, Task, Any, "FKResult | None"], Assessment]


@dataclass(frozen=True)
class Method:
    """A registered assessment: ``name`` (CLI name), ``title``, ``source`` (citation),
    ``validity`` (the range the method holds for, as text), ``assess`` and ``levels``, its lowest and
    highest action level (for colour coding: lowest green, highest red)."""

    name: str
    title: str
    source: str
    validity: str
    assess: AssessFn
    levels: tuple[int, int] = (1, 4)


_METHODS: dict[str, Method] = {}
_LOADED = False


def register(method: Method) -> Method:
    """Add ``method`` to the registry (each assessment module calls this once)."""
    _METHODS[method.name] = method
    return method


def methods() -> dict[str, Method]:
    """Every registered method by name (imports the package's modules on first use)."""
    global _LOADED
    if not _LOADED:
        import jackpy.ergonomics as pkg

        for info in pkgutil.iter_modules(pkg.__path__):
            importlib.import_module(f"jackpy.ergonomics.{info.name}")
        _LOADED = True
    return dict(_METHODS)


def method(name: str) -> Method:
    """The method called ``name`` (ErgonomicsError listing the known ones otherwise)."""
    all_ = methods()
    if name not in all_:
        raise ErgonomicsError(f"unknown ergonomic method {name!r} (known: {', '.join(sorted(all_))})")
    return all_[name]


def parse_methods(text: str) -> list[str]:
    """``"rula,reba"`` -> ``["rula", "reba"]``, each checked; ``"all"`` -> every method."""
    names = [s.strip() for s in text.split(",") if s.strip()]
    if names == ["all"]:
        return sorted(methods())
    if not names:
        raise ErgonomicsError("no ergonomic method given")
    for n in names:
        method(n)
    return names


#: degrees: measurement noise ignored at a band edge
EDGE_TOLERANCE = 1e-6


def band(x: float, edges: tuple[float, ...], at_edge: bool) -> int:
    """1 + how many of the ascending ``edges`` ``x`` has reached: with ``at_edge`` the score steps at
    each edge (bands [lower, upper): RULA's "20-45°, 45-90°, 90°+"), without it just above (bands
    (lower, upper]: REBA's "> 20°"). Measurements within :data:`EDGE_TOLERANCE` of an edge count as on
    it (a posed 60° measures 59.99999999°)."""
    return 1 + sum(1 for e in edges if (x >= e - EDGE_TOLERANCE if at_edge else x > e + EDGE_TOLERANCE))


def adjustment(task: Task, name: str, measured: bool, used: dict[str, Any]) -> bool:
    """An adjustment's value: ``task.overrides[name]`` when given, else the measured one; records
    ``{name: {"measured": .., "value": .., "overridden": ..}}`` in ``used``."""
    value = task.overrides.get(name, measured)
    used[name] = {"measured": bool(measured), "value": bool(value), "overridden": name in task.overrides}
    return bool(value)
