"""Yaps scheduling ([SH6] §6.3.5; digest §5.4): start conditions, named instances, hooks.

A script's top-level entries run **one after the other** by default (friendlier than Yaps's
simultaneity); a ``together()`` block starts its entries at once (Yaps's concurrency) and ends when
the last ends; ``After(name, delay)`` starts when the named entry ends (plus ``delay`` s),
``With(name)`` when it starts, ``At(t)`` at a time. The sub-steps of one command are always
sequential. ``on_success`` / ``on_failure`` entries start when the entry ends that way.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class After:
    """Start when entry ``name`` ends, plus ``delay`` seconds."""

    name: str
    delay: float = 0.0


@dataclass(frozen=True)
class With:
    """Start when entry ``name`` starts."""

    name: str


@dataclass(frozen=True)
class At:
    """Start at script time ``t`` seconds."""

    t: float


Start = After | With | At


@dataclass
class Entry:
    """One instance of a command in a script: its name, start condition, optional explicit
    duration (s; overrides Fitts for the whole command, its steps scaled to fit), hooks, and where
    it came from (``origin``: ``file:line`` of a checklist line)."""

    action: Any
    name: str
    start: Start | None = None
    duration: float | None = None
    on_success: list["Entry"] = field(default_factory=list)
    on_failure: list["Entry"] = field(default_factory=list)
    origin: str = ""
    hook: bool = False
