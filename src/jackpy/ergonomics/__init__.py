"""Ergonomic assessments of a posed figure: RULA, REBA, OWAS, the NIOSH lifting equation, the L5/S1
low-back load and percent capable (docs/ergonomics.md).

Each method is one module that registers itself (:mod:`jackpy.ergonomics.base`); all of them read the
posture measured by :mod:`jackpy.ergonomics.posture` from the figure's world transforms.
"""

from __future__ import annotations

from jackpy.ergonomics.base import Assessment, ErgonomicsError, Lift, Method, Task, method, methods, parse_methods
from jackpy.ergonomics.posture import Posture, measure
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure


def assess(figure: Figure, names: list[str], task: Task | None = None,
           fk: FKResult | None = None) -> dict[str, Assessment]:
    """Run the methods ``names`` on ``figure``'s current posture (one forward pass and one posture
    measurement shared by all of them)."""
    task = Task() if task is None else task
    chosen = [method(n) for n in names]
    if fk is None:
        fk = figure.kinematics().forward(figure.q, figure.location)
    posture = measure(figure, fk)
    return {m.name: m.assess(figure, task, posture, fk) for m in chosen}


__all__ = ["Assessment", "ErgonomicsError", "Lift", "Method", "Posture", "Task", "assess", "measure", "method",
           "methods", "parse_methods"]
