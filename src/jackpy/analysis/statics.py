"""Static joint torques: gravity on every segment plus external loads (book §2.8, static analysis).

The figure is held static by its root (the support: feet, seat, or a fixed base); every DOF carries
what lies beyond it from the root. With ``Q = sum_s J_s^T (m_s g) + sum_l J_l^T F_l`` the generalised
force of gravity and loads, the joint actuators must supply ``tau = -Q``. Units: N·m for rotational
DOFs, N for translational ones; ``tau[i] > 0`` means the joint pushes towards increasing ``q[i]``.
Vectorised over all DOFs through the segment Jacobians of :mod:`jackpy.peabody.kinematics`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from jackpy.errors import FigureError
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

#: standard gravity, world frame (y up), m/s^2
G = 9.80665
GRAVITY = np.array([0.0, -G, 0.0])


@dataclass
class Load:
    """An external force (world N) and moment (world N·m) applied at ``point`` (segment frame, metres)
    of segment ``segment``; the reaction of something the figure holds or pushes."""

    segment: str
    point: np.ndarray = field(default_factory=lambda: np.zeros(3))
    force: np.ndarray = field(default_factory=lambda: np.zeros(3))
    moment: np.ndarray = field(default_factory=lambda: np.zeros(3))

    @classmethod
    def held_mass(cls, figure: Figure, segment: str, site: str, kg: float,
                  gravity: np.ndarray = GRAVITY) -> "Load":
        """The weight of ``kg`` kilograms held at ``segment.site``."""
        point = figure.site_location(segment, site)[:3, 3].copy()
        return cls(segment, point, kg * np.asarray(gravity, dtype=float))


def joint_torques(figure: Figure, loads: Sequence[Load] = (), q: np.ndarray | None = None,
                  gravity: np.ndarray = GRAVITY, fk: FKResult | None = None) -> np.ndarray:
    """Torques (ndof,) the joints must exert to hold posture ``q`` (default: the figure's) against
    gravity on the segment masses and ``loads``; see the module docstring for units and sign."""
    kin = figure.kinematics()
    q = figure.q if q is None else np.asarray(q, dtype=float)
    if fk is None:
        fk = kin.forward(q, figure.location)
    g = np.asarray(gravity, dtype=float)
    gen = (kin.com_jacobian(fk) * kin.mass.sum()).T @ g
    for load in loads:
        if load.segment not in kin.segment_index:
            raise FigureError(f"figure {figure.name!r}: load on unknown segment {load.segment!r}")
        si = kin.segment_index[load.segment]
        w = fk.segments[si]
        point = w[:3, :3] @ np.asarray(load.point, dtype=float) + w[:3, 3]
        gen = gen + kin.point_jacobian(fk, si, point).T @ np.asarray(load.force, dtype=float)
        if np.any(load.moment):
            gen = gen + kin.rotation_jacobian(fk, si).T @ np.asarray(load.moment, dtype=float)
    return -gen


def foot_reactions(figure: Figure, loads: Sequence[Load], feet: Sequence[str],
                   fk: FKResult | None = None, gravity: np.ndarray = GRAVITY) -> list[Load]:
    """The floor's reactions on the feet ``feet`` (segment names, each with ``heel`` and ``ball``
    sites) holding the whole figure and ``loads`` static: the vertical and horizontal load is shared
    between the feet by the lever rule (where the centre of the weights lies along the line between
    the feet's centres), and each foot's reaction acts at its centre of pressure, the point of its
    heel-ball line level with the centre of the weights along that line (kept between heel and
    ball; outside it the figure would tip, and the root carries the rest). World N, segment points.

    With these loads :func:`joint_torques` gives the standing torques of the legs even when the
    figure is rooted at the pelvis (the root then carries nothing while the weights' centre lies
    over the feet)."""
    kin = figure.kinematics()
    if fk is None:
        fk = kin.forward(figure.q, figure.location)
    g = np.asarray(gravity, dtype=float)
    down = g / np.linalg.norm(g)
    total = kin.mass.sum() * g
    moment_point = kin.mass.sum() * kin.centre_of_mass(fk) * float(np.linalg.norm(g))
    weight = kin.mass.sum() * float(np.linalg.norm(g))
    for load in loads:
        w = fk.segments[kin.segment_index[load.segment]]
        p = w[:3, :3] @ np.asarray(load.point, dtype=float) + w[:3, 3]
        f = np.asarray(load.force, dtype=float)
        total = total + f
        vertical = max(float(f @ down), 0.0)
        moment_point = moment_point + vertical * p
        weight += vertical
    centre = moment_point / weight  # where the downward forces act on average
    soles = {}
    for foot in feet:
        w = fk.segments[kin.segment_index[foot]]
        heel = (w @ figure.site_location(foot, "heel"))[:3, 3]
        ball = (w @ figure.site_location(foot, "ball"))[:3, 3]
        soles[foot] = (heel, ball, w)
    if len(feet) == 1:
        shares = {feet[0]: 1.0}
    else:
        a, b = ((soles[f][0] + soles[f][1]) / 2 for f in feet[:2])
        ab = (b - a) - ((b - a) @ down) * down
        t = float(np.clip((centre - a) @ ab / max(ab @ ab, 1e-12), 0.0, 1.0))
        shares = {feet[0]: 1.0 - t, feet[1]: t}
    out = []
    for foot, share in shares.items():
        heel, ball, w = soles[foot]
        hb = (ball - heel) - ((ball - heel) @ down) * down
        s = float(np.clip((centre - heel) @ hb / max(hb @ hb, 1e-12), 0.0, 1.0))
        cop = heel + s * (ball - heel)
        local = w[:3, :3].T @ (cop - w[:3, 3])
        out.append(Load(foot, local, -share * total))
    return out
