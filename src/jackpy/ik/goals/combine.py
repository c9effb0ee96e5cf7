"""AND and OR combinations of goals (book (3.1)-(3.3), §3.7); they nest freely.

``AllOf`` is the weighted sum of its members' potentials (their residuals stacked, each scaled by
``sqrt(member.weight)``). ``AnyOf`` is the minimum of its members' weighted potentials: each
evaluation works on the member with the smallest potential, e.g. a point kept outside a convex box
is ``AnyOf`` the six outward half-spaces. The minimum is non-smooth where the choice switches; the
solver restarts its quasi-Newton metric whenever :attr:`AnyOf.selected` changes.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.ik.goals.base import Context, Goal, GoalEval

if TYPE_CHECKING:
    from jackpy.peabody.model import Figure


class _Group(Goal):
    def __init__(self, goals: Sequence[Goal], weight: float = 1.0, name: str | None = None) -> None:
        if not goals:
            raise ValueError(f"{type(self).__name__} needs at least one goal")
        self.goals = list(goals)
        self.weight = float(weight)
        self.name = name or f"{type(self).__name__}({', '.join(g.name for g in self.goals)})"
        self._mask = np.zeros(0, dtype=bool)

    def bind(self, figure: Figure) -> None:
        for g in self.goals:
            g.bind(figure)
        self._mask = np.logical_or.reduce([g.chain_mask() for g in self.goals])

    def chain_mask(self) -> np.ndarray:
        return self._mask

    def leaves(self) -> list[Goal]:
        return [leaf for g in self.goals for leaf in g.leaves()]

    def to_dict(self) -> dict[str, Any]:
        """The members nested under ``goals``."""
        return {"kind": self.kind, "name": self.name, "weight": float(self.weight),
                "goals": [g.to_dict() for g in self.goals]}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Goal:
        if d.get("kind", cls.kind) != cls.kind:
            return Goal.from_dict(d)
        return cls([Goal.from_dict(g) for g in d["goals"]], d.get("weight", 1.0), d.get("name"))


class AllOf(_Group):
    """Conjunction: ``sum_i w_i P_i`` over ``goals``."""

    kind = "all-of"

    def evaluate(self, ctx: Context) -> GoalEval:
        evs = [(np.sqrt(g.weight), g.evaluate(ctx)) for g in self.goals]
        return GoalEval(np.concatenate([s * e.f for s, e in evs]), np.vstack([s * e.J for s, e in evs]),
                        metres=max(e.metres for _, e in evs), degrees=max(e.degrees for _, e in evs))


class AnyOf(_Group):
    """Disjunction: ``min_i w_i P_i`` over ``goals``; :attr:`selected` is the member last chosen."""

    kind = "any-of"

    def __init__(self, goals: Sequence[Goal], weight: float = 1.0, name: str | None = None) -> None:
        super().__init__(goals, weight, name)
        self.selected = -1

    def evaluate(self, ctx: Context) -> GoalEval:
        evs = [g.evaluate(ctx) for g in self.goals]
        pots = [g.weight * float(e.f @ e.f) for g, e in zip(self.goals, evs)]
        k = int(np.argmin(pots))
        self.selected = k
        s = np.sqrt(self.goals[k].weight)
        e = evs[k]
        return GoalEval(s * e.f, s * e.J, metres=e.metres, degrees=e.degrees)
