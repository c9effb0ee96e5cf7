"""The arm's joint space for motion planning: the free variables of the chain from the clavicle
(or ``start_joint``) to the hand, in the form the figure's own limits are stated.

For the standard human that is 7 variables: the shoulder complex's group angles (elevation,
abduction, twist: the clavicle follows the humerus by the shoulder rhythm, book §2.4), the elbow,
the forearm group's twist and the wrist's two DOFs. Joint groups on the chain contribute their
group angles (box limits and linear rows ``A θ <= b``); ungrouped DOFs their displacement limits.
Everything off the chain keeps the posture the space was made in.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy import ik
from jackpy.analysis.parts import figure_parts
from jackpy.peabody.model import Figure


@dataclass
class _Group:
    group: object
    dofs: np.ndarray  # indices into q of the group's member DOFs
    x: slice  # its angles in x


class ArmSpace:
    """Free variables ``x`` of ``figure``'s ``hand`` chain (module docstring). ``figure`` is used
    as given (pass a private copy when its posture must not change); ``x0`` is its posture when
    the space was made."""

    def __init__(self, figure: Figure, hand: str = "right", start_joint: str | None = None) -> None:
        h = figure_parts(figure).hands[hand]
        self.figure = figure
        self.hand = hand
        self.site = (h.segment, h.site)
        self.chain = start_joint or h.start_joint
        problem = ik.Problem(figure)
        goal = problem.add(ik.Position(f"{h.segment}.{h.site}", np.zeros(3), chain=self.chain))
        problem.compile()
        on_chain = goal.chain_mask()
        self.q0 = figure.q.copy()
        grouped = np.zeros(figure.ndof, dtype=bool)
        groups: list[tuple[object, np.ndarray]] = []
        for g in figure.groups.values():
            idx = np.concatenate([np.arange(figure.ndof)[figure.joint_dof_slice(jn)] for jn in g.joints])
            grouped[idx] = True
            if on_chain[idx].any():
                groups.append((g, idx))
        self.free_dofs = np.flatnonzero(on_chain & ~grouped)
        names = figure.dof_names()
        self.names = [names[i] for i in self.free_dofs]
        lower, upper = [figure.lower[self.free_dofs]], [figure.upper[self.free_dofs]]
        self.groups: list[_Group] = []
        start = len(self.free_dofs)
        for g, idx in groups:
            self.groups.append(_Group(g, idx, slice(start, start + g.nangles)))
            self.names += [f"{g.name}.{a}" for a in g.angle_names]
            lower.append(g.lower)
            upper.append(g.upper)
            start += g.nangles
        self.lower, self.upper = np.concatenate(lower), np.concatenate(upper)
        self.ndim = start
        rows = [np.zeros((0, start))]
        for g in self.groups:
            a = np.zeros((g.group.A.shape[0], start))
            a[:, g.x] = g.group.A
            rows.append(a)
        #: every group's linear limits over ``x``: ``A @ x <= b``
        self.A = np.vstack(rows)
        self.b = np.concatenate([np.zeros(0)] + [np.asarray(g.group.b, dtype=float) for g in self.groups])
        self.x0 = self.x()
        kin = figure.kinematics()
        dofs = np.unique(np.concatenate([self.free_dofs] + [g.dofs for g in self.groups]))
        #: the joints the variables move, root side first
        self.joints = list(dict.fromkeys(kin.joint_names[j] for j in kin.dof_joint[dofs]))

    def x(self) -> np.ndarray:
        """The figure's current variables."""
        q = self.figure.q
        return np.concatenate([q[self.free_dofs]] + [np.array(g.group.angles, dtype=float) for g in self.groups])

    def q(self, x: np.ndarray) -> np.ndarray:
        """Whole-figure displacements for arm variables ``x`` (the rest as at the start)."""
        q = self.q0.copy()
        q[self.free_dofs] = x[:len(self.free_dofs)]
        for g in self.groups:
            q[g.dofs] = g.group.driver(np.asarray(x[g.x], dtype=float))
        return q

    def feasible(self, x: np.ndarray, tol: float = 1e-9) -> bool:
        """``x`` within the box and every group's linear limits."""
        return bool(np.all(x >= self.lower - tol) and np.all(x <= self.upper + tol)
                    and np.all(self.A @ x <= self.b + tol))

    def apply(self, x: np.ndarray) -> None:
        """Put the figure at ``x`` (displacements and group angles)."""
        self.figure.q = self.q(x)
        for g in self.groups:
            g.group.angles = np.array(x[g.x], dtype=float)

    def hand_position(self, x: np.ndarray) -> np.ndarray:
        """World position (m) of the hand's reach site at ``x`` (the figure is left at ``x``)."""
        self.figure.q = self.q(x)
        return self.figure.site_world(*self.site)[:3, 3].copy()

    def hand_positions(self, xs: np.ndarray) -> np.ndarray:
        """(N, 3) hand positions for (N, ndim) variables."""
        return np.array([self.hand_position(x) for x in xs]).reshape(-1, 3)

    def solve_ik(self, target: np.ndarray, x_start: np.ndarray, tolerance: float,
                 max_iterations: int = 300) -> np.ndarray:
        """Variables that put the hand on ``target`` (world, m) by the IK over the chain, started at
        ``x_start``; returns the variables the IK ended at (near the target when reachable)."""
        self.apply(x_start)
        problem = ik.Problem(self.figure)
        problem.add(ik.Position(f"{self.site[0]}.{self.site[1]}", np.asarray(target, dtype=float), chain=self.chain))
        ik.solve(problem, max_iterations=max_iterations, tol_position=tolerance / 5)
        return self.x()

    def sample(self, rng: np.random.Generator) -> np.ndarray:
        """A uniform random feasible ``x`` (rejection sampling on the groups' linear limits)."""
        while True:
            x = self.lower + rng.uniform(size=self.ndim) * (self.upper - self.lower)
            if self.feasible(x):
                return x
