"""Undo and redo: one command per drag or edit of the document.

A :class:`Command` is a labelled change of the document, undone by putting back the document's
state from before it (:meth:`jackpy.document.Document.capture`: postures, placements, goals,
behavior switches and parameters; whole figures for structural commands). The stack never looks
inside a state. Undo hands back the state to restore and keeps the current one for redo; a new
command clears the redo side.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Generic, TypeVar

S = TypeVar("S")


@dataclass
class Command(Generic[S]):
    """A labelled command and the document state before it (or, on the redo side, after it)."""

    label: str
    state: S


class UndoStack(Generic[S]):
    """Bounded undo and redo stacks of commands."""

    def __init__(self, limit: int = 200) -> None:
        self.limit = limit
        self._undo: list[Command[S]] = []
        self._redo: list[Command[S]] = []

    def push(self, label: str, before: S) -> None:
        """Record a command about to change the state; ``before`` is the state to return to."""
        self._undo.append(Command(label, before))
        del self._undo[:-self.limit]
        self._redo.clear()

    def undo(self, current: S) -> S | None:
        """The state before the last command (``current`` goes to redo), or None if none."""
        if not self._undo:
            return None
        step = self._undo.pop()
        self._redo.append(Command(step.label, current))
        return step.state

    def redo(self, current: S) -> S | None:
        """The state after the last undone command (``current`` goes back to undo), or None."""
        if not self._redo:
            return None
        step = self._redo.pop()
        self._undo.append(Command(step.label, current))
        return step.state

    def clear(self) -> None:
        """Forget every command (a new or opened document)."""
        self._undo.clear()
        self._redo.clear()

    def peek_undo(self) -> S | None:
        """The state :meth:`undo` would return, left in place."""
        return self._undo[-1].state if self._undo else None

    def peek_redo(self) -> S | None:
        """The state :meth:`redo` would return, left in place."""
        return self._redo[-1].state if self._redo else None

    @property
    def undo_label(self) -> str | None:
        """Label of the command :meth:`undo` would revert."""
        return self._undo[-1].label if self._undo else None

    @property
    def redo_label(self) -> str | None:
        """Label of the command :meth:`redo` would re-apply."""
        return self._redo[-1].label if self._redo else None
