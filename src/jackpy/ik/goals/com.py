"""Centre-of-mass (balance) goal (§3.9): the figure's COM directly above a balance point.

A vertical :class:`~jackpy.ik.goals.line.Line` goal with the whole-figure COM as end effector and its
exact Jacobian (the mass-weighted sum of segment-centroid Jacobians, §7.2 item 7): the COM height
stays free, so it drops when the figure bends. ``P = |(I - up up^T)(c - p)|^2``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import math

import numpy as np

from jackpy.errors import FigureError
from jackpy.ik.goals.base import Context, Goal, GoalEval, chain_mask, point3, unit

if TYPE_CHECKING:
    from jackpy.peabody.model import Figure


class CentreOfMass(Goal):
    """Keep the COM on the vertical line (along ``up``) through ``point`` (world, metres).

    ``chain`` is an explicit joint set (the book uses the dominant leg's ankle, knee and hip with the
    figure rooted at that foot); ``None`` (default) frees every DOF.
    """

    kind = "centre-of-mass"
    targets = ("point",)
    params = ("up", "chain")

    def __init__(self, point: np.ndarray, up: np.ndarray = (0.0, 1.0, 0.0),
                 chain: Sequence[str] | None = None,
                 weight: float = 1.0, name: str | None = None) -> None:
        self.point = point3(point)
        self.up = unit(up, "up direction")
        self.chain = chain
        self.weight = float(weight)
        self.name = name or "CentreOfMass"
        self._mask = np.zeros(0, dtype=bool)

    def bind(self, figure: Figure) -> None:
        kin = figure.kinematics()
        if kin.mass.sum() <= 0:
            raise FigureError(f"figure {figure.name!r} has no mass: a centre-of-mass goal needs one")
        if self.chain is None:
            self._mask = np.ones(kin.ndof, dtype=bool)
        else:
            self._mask = chain_mask(figure, 0, list(self.chain))

    def chain_mask(self) -> np.ndarray:
        return self._mask

    def evaluate(self, ctx: Context) -> GoalEval:
        c, Jc = ctx.com()
        up, d = self.up, c - self.point  # (I - up up^T) applied without forming it
        f = d - up * float(up @ d)
        return GoalEval(f, Jc - np.outer(up, up @ Jc), metres=math.sqrt(float(f @ f)))
