"""The live analyses of a document (strength, clearance), brought up to date after each solve.

:meth:`LiveAnalyses.refresh` runs at the end of :meth:`jackpy.document.Document.step` (after IK and
FK), so the results are current for whoever reads them next, a window's draw or a headless script;
the draw only turns them into overlays. Work is skipped when the posture, placements and choices
are those of the last refresh.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.peabody import Environment, Figure

if TYPE_CHECKING:
    from jackpy.analysis import Clearance


@dataclass
class StrengthReadout:
    """Live strength: DOF torques (N m), utilisation, per-joint utilisation, bars of the hand's chain."""

    torques: np.ndarray
    utilisation: np.ndarray
    joints: dict[str, float]
    bars: list
    segment_colours: dict[str, tuple[float, ...]]


def segment_strength_colours(figure: Figure, joint_util: Mapping[str, float]) -> dict[str, tuple[float, ...]]:
    """``segment -> RGBA``: each segment coloured by the largest utilisation among the joints it
    touches (segments touching no joint with data: white)."""
    from jackpy.analysis import strength_colour

    worst: dict[str, float] = {s: 0.0 for s in figure.segments}
    for j in figure.joints.values():
        u = joint_util.get(j.name, float("nan"))
        if np.isnan(u):
            continue
        for s in (j.from_seg, j.to_seg):
            worst[s] = max(worst[s], float(u))
    return {s: tuple(float(c) for c in strength_colour(u)) + (1.0,) for s, u in worst.items()}


def scene_objects(env: Environment) -> list[Figure]:
    """The environment's unjointed figures that carry geometry (CAD objects, chairs, tables)."""
    out = []
    for fig in env.figures.values():
        if fig.joints:
            continue
        if any(s.psurf is not None and s.psurf.mesh is not None and len(s.psurf.mesh.faces) for s in fig.segments.values()):
            out.append(fig)
    return out


def figure_of_interest(env: Environment) -> Figure | None:
    """The first articulated figure (the human)."""
    return next((f for f in env.figures.values() if f.joints), None)


@dataclass
class LiveAnalyses:
    """The choices and results of the live analyses of a document's figure of interest."""

    hand: str = "right"
    load_kg: float = 0.0
    strength_live: bool = False
    """Compute strength each step (the Analysis panel sets it while its section is open)."""
    torque_colouring: bool = False
    strength: StrengthReadout | None = None
    strength_error: str | None = None
    clearance_on: bool = False
    clearance_object: str | None = None
    clearance: Clearance | None = None
    colliding: set[str] = field(default_factory=set)
    clearance_error: str | None = None
    refreshes: int = 0
    """How many refreshes recomputed something (tests and benches read it)."""
    _checker: Any = None
    _checker_key: tuple = ()
    _live_key: tuple = ()
    _tables: dict = field(default_factory=dict)

    def strength_table(self, figure: Figure):
        """The figure's strength table (cached per figure object); raises when it has none."""
        key = id(figure)
        if key not in self._tables:
            from jackpy.analysis import dof_strengths
            from jackpy.body.strength import strength_table

            try:
                self._tables[key] = (figure, dof_strengths(strength_table(figure)), None)
            except Exception as exc:  # synthetic figures have no body specification
                self._tables[key] = (figure, None, f"{exc}")
        _, table, error = self._tables[key]
        if table is None:
            raise LookupError(error)
        return table

    @staticmethod
    def posture_strength_table(figure: Figure):
        """The strength table at the figure's current joint angles (the posture curves of
        :mod:`jackpy.body.strength`; a few ms, so it is recomputed when the posture changes)."""
        from jackpy.analysis import dof_strengths
        from jackpy.body.strength import strength_table

        return dof_strengths(strength_table(figure, at_posture=True))

    def update_strength(self, figure: Figure) -> None:
        """Torques and utilisation at the figure's posture holding ``load_kg`` in the chosen hand."""
        from jackpy.analysis import (
            Chain,
            Load,
            figure_parts,
            joint_torques,
            joint_utilisation,
            strength_bars,
            utilisation,
        )

        try:
            self.strength_table(figure)  # raises (cached) for a figure without a body specification
            table = self.posture_strength_table(figure)
            hand = figure_parts(figure).hands[self.hand]
        except Exception as exc:
            self.strength, self.strength_error = None, f"strength not available: {exc}"
            return
        loads = [Load.held_mass(figure, hand.segment, hand.site, self.load_kg)] if self.load_kg > 0 else []
        tau = joint_torques(figure, loads)
        util = utilisation(figure, tau, table)
        ju = joint_utilisation(figure, util)
        names = figure.dof_names()
        chain = Chain(figure, hand.start_joint, hand.segment, np.zeros(3))
        arm = [names[i] for i in chain.dofs if names[i] in table]
        self.strength = StrengthReadout(tau, util, ju, strength_bars(figure, tau, table, arm),
                                        segment_strength_colours(figure, ju))
        self.strength_error = None

    def update_clearance(self, env: Environment, figure: Figure) -> None:
        """Rebuild the checker when the figure or objects changed, then query this posture."""
        from jackpy.analysis import ClearanceChecker

        objects = [o for o in scene_objects(env) if o is not figure]
        key = (id(figure), tuple(id(o) for o in objects))
        try:
            if self._checker is None or key != self._checker_key:
                self._checker = ClearanceChecker(figure, objects)
                self._checker_key = key
            chk = self._checker
            chk.update()
            self.colliding = chk.colliding_segments()
            names = [o.name for o in objects]
            if self.clearance_object not in names:
                self.clearance_object = names[0] if names else None
            self.clearance = chk.clearance(self.clearance_object) if self.clearance_object else None
            self.clearance_error = None
        except Exception as exc:  # no python-fcl, no geometry on the figure
            self.clearance, self.colliding, self.clearance_error = None, set(), f"{exc}"

    def refresh(self, env: Environment) -> None:
        """Bring the live analyses up to date when the posture, placements or choices changed."""
        fig = figure_of_interest(env)
        if fig is None:
            self.strength, self.clearance, self.colliding = None, None, set()
            return
        want_strength = self.strength_live or self.torque_colouring
        state = [fig.q.tobytes(), fig.location.tobytes(), id(fig), self.load_kg, self.hand,
                 want_strength, self.clearance_on, self.clearance_object]
        if self.clearance_on:
            state += [o.location.tobytes() for o in env.figures.values() if not o.joints]
            state.append(len(env.figures))
        key = tuple(state)
        if key == self._live_key:
            return
        self._live_key = key
        self.refreshes += 1
        if want_strength:
            self.update_strength(fig)
        if self.clearance_on:
            self.update_clearance(env, fig)
        else:
            self.clearance, self.colliding = None, set()
