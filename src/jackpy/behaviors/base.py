"""The behavior protocol and parameter descriptions the workbench's Behaviors panel draws from.

A behavior ([SH4] §4.1, Table 4.1) is an object with a ``name``, an ``enabled`` switch, a ``params``
dataclass and an ``order`` within the frame. Each frame the :class:`~jackpy.behaviors.loop.BehaviorLoop`
calls ``update(frame)`` on every enabled behavior in ``order`` before the solve (behaviors read
the figure and write goals into the frame) and ``finish(frame)`` after it.

Parameter fields carry their description in ``dataclasses.field(metadata=...)`` built by
:func:`param`: ``doc`` (one line), ``unit`` (as shown to the user), ``range`` (inclusive limits in
internal units) and, for choices, ``choices``. :func:`describe` lists them for a panel.
"""

from __future__ import annotations

from dataclasses import MISSING, dataclass, field, fields
from typing import TYPE_CHECKING, Any, ClassVar, Protocol, runtime_checkable

if TYPE_CHECKING:
    from jackpy.behaviors.loop import Frame


def param(default: Any, doc: str, unit: str = "", range: tuple[float, float] | None = None,
          choices: tuple[str, ...] | None = None) -> Any:
    """A dataclass field with its panel description (``range`` in internal units: m, rad, kg, s)."""
    return field(default=default, metadata={"doc": doc, "unit": unit, "range": range, "choices": choices})


@dataclass(frozen=True)
class ParamSpec:
    """One parameter as a panel shows it."""

    name: str
    default: Any
    value: Any
    doc: str
    unit: str
    range: tuple[float, float] | None
    choices: tuple[str, ...] | None


def describe(params: Any) -> list[ParamSpec]:
    """The :class:`ParamSpec` of every field of a params dataclass instance."""
    out = []
    for f in fields(params):
        m = f.metadata
        default = f.default if f.default is not MISSING else None
        out.append(ParamSpec(f.name, default, getattr(params, f.name), m.get("doc", ""), m.get("unit", ""),
                             m.get("range"), m.get("choices")))
    return out


def validate(params: Any) -> None:
    """Raise ValueError naming the field when a value is outside its range or choices."""
    for s in describe(params):
        if s.range is not None and not (s.range[0] <= s.value <= s.range[1]):
            raise ValueError(f"{type(params).__name__}.{s.name} = {s.value!r} outside {s.range}")
        if s.choices is not None and s.value not in s.choices:
            raise ValueError(f"{type(params).__name__}.{s.name} = {s.value!r} not one of {s.choices}")


@runtime_checkable
class Behavior(Protocol):
    """What the loop needs from a behavior."""

    name: str
    enabled: bool
    params: Any
    order: ClassVar[int]

    def update(self, frame: "Frame") -> None:
        """Read the figure and state; write goals and state before the solve."""
        ...

    def finish(self, frame: "Frame") -> None:
        """After the solve (attachments, bookkeeping of active behaviors)."""
        ...


class BehaviorBase:
    """Convenience base: ``enabled`` on by default, no-op hooks."""

    name: ClassVar[str] = ""
    order: ClassVar[int] = 0

    def __init__(self, params: Any, enabled: bool = True) -> None:
        validate(params)
        self.params = params
        self.enabled = enabled

    def update(self, frame: "Frame") -> None:
        return None

    def finish(self, frame: "Frame") -> None:
        return None

    def __repr__(self) -> str:
        return f"{type(self).__name__}(enabled={self.enabled}, params={self.params})"
