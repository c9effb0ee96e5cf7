"""Strength against required torque: utilisation, the strength bar, and the torque body colouring
(book §2.8; shared/spec/body-model.md §3.6).

Strength is per DOF and per direction ("both muscle groups"): :class:`DofStrength` gives the largest
torque the group driving ``+q`` can exert and the largest the group driving ``-q`` can exert (both
N·m, >= 0). A strength table maps DOF names (``"joint[k]"``, :meth:`Figure.dof_names`) to them; DOFs
missing from the table have no strength data (utilisation NaN, drawn white).

Utilisation ``u = |tau| / strength of the group that must act`` (tau from
:func:`jackpy.analysis.statics.joint_torques`): 0 no load, 1 at maximum strength, > 1 beyond it.
Colour: white (u = 0) -> blue (u = 1) linearly; red above 1.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from jackpy.body.skin import segment_surfaces
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

WHITE = np.array([1.0, 1.0, 1.0])
BLUE = np.array([0.1, 0.25, 1.0])
RED = np.array([0.9, 0.05, 0.05])
GREEN = (0.1, 0.75, 0.2)
PURPLE = (0.6, 0.2, 0.8)
BAR_RED = (0.9, 0.1, 0.1)


@dataclass(frozen=True)
class DofStrength:
    """Largest torque (N·m, >= 0) of the muscle group driving ``+q`` and of the one driving ``-q``."""

    positive: float
    negative: float

    def against(self, torque: float) -> float:
        """The strength of the group that must act to produce ``torque``."""
        return self.positive if torque >= 0 else self.negative


StrengthTable = Mapping[str, DofStrength]


def utilisation(figure: Figure, torques: np.ndarray, table: StrengthTable) -> np.ndarray:
    """Per-DOF ``|tau| / strength`` (ndof,): NaN where the table has no entry, ``inf`` where the
    acting group has zero strength but torque is needed."""
    out = np.full(len(torques), np.nan)
    for i, name in enumerate(figure.dof_names()):
        s = table.get(name)
        if s is None:
            continue
        t = float(torques[i])
        cap = s.against(t)
        out[i] = abs(t) / cap if cap > 0 else (0.0 if t == 0 else np.inf)
    return out


def joint_utilisation(figure: Figure, dof_util: np.ndarray) -> dict[str, float]:
    """Per joint, the largest utilisation over its DOFs (NaN when none has data)."""
    out: dict[str, float] = {}
    start = 0
    for j in figure.joints.values():
        u = dof_util[start:start + j.ndof]
        start += j.ndof
        out[j.name] = float(np.nanmax(u)) if np.any(~np.isnan(u)) else float("nan")
    return out


def strength_colour(u: np.ndarray | float) -> np.ndarray:
    """RGB in [0, 1] for utilisation ``u`` (scalar -> (3,), array (n,) -> (n,3)); NaN is white."""
    u = np.asarray(u, dtype=float)
    t = np.clip(np.nan_to_num(u, nan=0.0), 0.0, 1.0)[..., None]
    rgb = WHITE * (1 - t) + BLUE * t
    return np.where((np.nan_to_num(u, nan=0.0) > 1.0)[..., None], RED, rgb)


@dataclass(frozen=True)
class StrengthBar:
    """One bar of the strength bar display for a DOF: ``parts`` are (length N·m, RGB) from the inside
    out; ``over`` is True when the required torque exceeds the strength (the joint is highlighted)."""

    dof: str
    required: float
    strength: float
    parts: tuple[tuple[float, tuple[float, float, float]], ...]
    over: bool


def strength_bars(figure: Figure, torques: np.ndarray, table: StrengthTable,
                  dofs: list[str] | None = None) -> list[StrengthBar]:
    """Bars for ``dofs`` (default: every DOF with strength data), after book §2.8: strength above the
    requirement -> inner red = required, outer green = margin; otherwise inner green = strength, outer
    red = excess; zero requirement -> one green part; equal -> one purple part."""
    names = figure.dof_names()
    index = {n: i for i, n in enumerate(names)}
    bars = []
    for name in dofs if dofs is not None else [n for n in names if n in table]:
        t = float(torques[index[name]])
        req = abs(t)
        cap = table[name].against(t)
        if np.isclose(req, cap, rtol=1e-9, atol=1e-12):
            parts: tuple = ((cap, PURPLE),)
        elif req == 0.0:
            parts = ((cap, GREEN),)
        elif cap > req:
            parts = ((req, BAR_RED), (cap - req, GREEN))
        else:
            parts = (((cap, GREEN),) if cap > 0 else ()) + ((req - cap, BAR_RED),)
        bars.append(StrengthBar(name, req, cap, parts, req > cap))
    return bars


def joint_world_positions(figure: Figure, fk: FKResult) -> dict[str, np.ndarray]:
    """World position (metres) of every joint's centre (its from-site origin)."""
    kin = figure.kinematics()
    pos = (fk.segments[kin.joint_from_seg] @ kin.L_from)[:, :3, 3] if kin.njoints else np.zeros((0, 3))
    return {name: pos[k] for k, name in enumerate(kin.joint_names)}


def torque_vertex_colours(figure: Figure, joint_util: Mapping[str, float], spread: float = 0.1,
                          fk: FKResult | None = None) -> dict[str, np.ndarray]:
    """Per-vertex RGB (n,3) for every segment with geometry: each joint's utilisation spreads onto
    the vertices of the segments it joins, fading linearly to nothing at ``spread`` metres from the
    joint centre; a vertex takes the largest faded value (white far from loaded joints; an overloaded
    joint is red out to where its faded value drops to 1)."""
    kin = figure.kinematics()
    if fk is None:
        fk = kin.forward(figure.q, figure.location)
    centres = joint_world_positions(figure, fk)
    touching: dict[str, list[str]] = {s: [] for s in figure.segments}
    for j in figure.joints.values():
        touching[j.from_seg].append(j.name)
        touching[j.to_seg].append(j.name)
    world = {name: fk.segments[i] for i, name in enumerate(kin.segment_names)}
    out: dict[str, np.ndarray] = {}
    for name, mesh in segment_surfaces(figure, world).items():  # what figure_bodies draws
        w = world[name]
        v = mesh.vertices @ w[:3, :3].T + w[:3, 3]
        u = np.zeros(len(v))
        for jn in touching[name]:
            val = joint_util.get(jn, float("nan"))
            if np.isnan(val):
                continue
            fade = np.clip(1.0 - np.linalg.norm(v - centres[jn], axis=1) / spread, 0.0, 1.0)
            u = np.maximum(u, val * fade)
        out[name] = strength_colour(u)
    return out


def dof_strengths(pairs: Mapping[str, tuple[float, float]]) -> dict[str, DofStrength]:
    """A strength table from ``{dof: (toward_lower_Nm, toward_upper_Nm)}`` pairs, the form of
    :func:`jackpy.body.strength.strength_table`."""
    return {name: DofStrength(positive=float(up), negative=float(lo)) for name, (lo, up) in pairs.items()}
