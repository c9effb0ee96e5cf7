"""Undo and redo: one step per drag or command, as snapshots of the state before it.

The stack stores whatever snapshot the application captures (figure postures and placements plus
goals, see :class:`jackpy.ui.app.Snapshot`); it never looks inside. Undo hands back the snapshot to
restore and keeps the current one for redo; a new command clears the redo side.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Generic, TypeVar

S = TypeVar("S")


@dataclass
class Step(Generic[S]):
    """A labelled snapshot."""

    label: str
    state: S


class UndoStack(Generic[S]):
    """Bounded undo and redo stacks of snapshots."""

    def __init__(self, limit: int = 200) -> None:
        self.limit = limit
        self._undo: list[Step[S]] = []
        self._redo: list[Step[S]] = []

    def push(self, label: str, before: S) -> None:
        """Record a command about to change the state; ``before`` is the state to return to."""
        self._undo.append(Step(label, before))
        del self._undo[:-self.limit]
        self._redo.clear()

    def undo(self, current: S) -> S | None:
        """The state before the last command (``current`` goes to redo), or None if none."""
        if not self._undo:
            return None
        step = self._undo.pop()
        self._redo.append(Step(step.label, current))
        return step.state

    def redo(self, current: S) -> S | None:
        """The state after the last undone command (``current`` goes back to undo), or None."""
        if not self._redo:
            return None
        step = self._redo.pop()
        self._undo.append(Step(step.label, current))
        return step.state

    def clear(self) -> None:
        """Forget every step (a new or opened scene)."""
        self._undo.clear()
        self._redo.clear()

    def peek_undo(self) -> S | None:
        """The snapshot :meth:`undo` would return, left in place."""
        return self._undo[-1].state if self._undo else None

    def peek_redo(self) -> S | None:
        """The snapshot :meth:`redo` would return, left in place."""
        return self._redo[-1].state if self._redo else None

    @property
    def undo_label(self) -> str | None:
        """Label of the step :meth:`undo` would revert."""
        return self._undo[-1].label if self._undo else None

    @property
    def redo_label(self) -> str | None:
        """Label of the step :meth:`redo` would re-apply."""
        return self._redo[-1].label if self._redo else None
