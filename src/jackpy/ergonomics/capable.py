"""Percent capable: for each main joint moment, the share of a population (by sex) strong enough.

The required moments are the static joint torques of :func:`jackpy.analysis.statics.joint_torques`:
gravity on every segment plus ``task.load_kg`` in the hands (half at each grip site), standing on
the feet that touch the floor (:func:`~jackpy.analysis.statics.foot_reactions`: the weight shared
by the lever rule, each foot pushing at its centre of pressure), so the legs carry the body whatever
the figure's root. The strength of the muscle group that must act comes from the public API of
:mod:`jackpy.body.strength` (``torque(kind, dof, sex, percentile, angle)`` at each DOF's current
angle, so the posture curves apply where its data have them: hip, knee, ankle, shoulder elevation,
elbow flexion; its data, sources and percentile model are documented there and in docs/strength.md). Percent capable = ``100 - P*`` where the group's strength at percentile ``P*``
equals the required moment, found on a grid of percentiles (1-99, the range that module accepts) and
interpolated linearly in their normal quantiles z (exact for that module's linear-in-z model); the
result is clamped to 1-99 % (99 means 99 % or more, 1 means 1 % or fewer). The weakest joint is the one
with the lowest percent capable.

Joints: neck (atlanto-occipital), trunk (L5/S1), each shoulder (its three DOFs), elbow and wrist, and
the hips, knees and ankles of the feet bearing weight; seated (``task.seated``) the legs are left out
(the seat carries them: flagged).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.stats import norm

from jackpy.analysis.statics import Load, foot_reactions, joint_torques
from jackpy.ergonomics.base import Assessment, Method, Task, register
from jackpy.ergonomics.posture import SIDES, Posture
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

VALIDITY = ("static exertions; strength from jackpy.body.strength (cited means by sex, normal spread) at "
            "each DOF's angle where its data have a posture curve")
#: the percentile grid and its normal quantiles
P_GRID = np.array([1, 2, 5, 10, 20, 30, 40, 50, 60, 70, 80, 90, 95, 98, 99], dtype=float)
Z_GRID = norm.ppf(P_GRID / 100.0)
_UPPER_JOINTS = ["atlanto_occipital", "l5_s1"] + [f"{s}_{j}" for s in SIDES for j in ("shoulder", "elbow", "wrist")]
_LEG_JOINTS = [f"{s}_{j}" for s in SIDES for j in ("hip", "knee", "ankle")]


def _strength_grid(kind: str, dof: str, sex: str, angle: float | None = None) -> np.ndarray:
    """(len(Z_GRID), 2): (toward-lower, toward-upper) strength N·m at each grid percentile, at the
    DOF's ``angle`` (rad) where the strength data have a posture curve."""
    from jackpy.body.strength import torque

    return np.array([torque(kind, dof, sex, float(p), angle) for p in P_GRID])


def percent_capable(required: float, strengths: np.ndarray) -> float:
    """Percent of the population whose strength (ascending over :data:`Z_GRID`) exceeds ``required``."""
    z = float(np.interp(required, strengths, Z_GRID))  # clamps to the grid's ends
    return float(100.0 * norm.sf(z))


def assess(figure: Figure, task: Task, posture: Posture, fk: FKResult | None = None) -> Assessment:
    """Percent capable per joint DOF, by sex; the score is the lowest over the chosen sexes."""
    from jackpy.body.skeleton import dof_names_of, joint_kind

    loads = [Load.held_mass(figure, f"{s}_palm", "grip", task.load_kg / 2) for s in SIDES] if task.load_kg > 0 else []
    flags = []
    joints = list(_UPPER_JOINTS)
    shares: dict[str, float] = {}
    if task.seated:
        flags.append("legs not assessed: seated (the seat carries them)")
    else:
        bearing = posture.feet_bearing()
        reactions = foot_reactions(figure, loads, [f"{s}_foot" for s in bearing], fk)
        total = sum(float(r.force[1]) for r in reactions) or 1.0
        shares = {r.segment.removesuffix("_foot"): float(r.force[1]) / total for r in reactions}
        loads = loads + reactions
        joints += [j for j in _LEG_JOINTS if j.split("_")[0] in bearing]
    tau = joint_torques(figure, loads, fk=fk)
    sexes = ["male", "female"] if task.sex == "both" else [task.sex]
    rows: list[dict[str, Any]] = []
    for jn in joints:
        if jn not in figure.joints:
            continue
        j = figure.joint(jn)
        sl = figure.joint_dof_slice(jn)
        kind = joint_kind(jn)
        disp = np.asarray(j.displacement, dtype=float).reshape(-1)
        for k, dname in enumerate(dof_names_of(j)):
            t = float(tau[sl][k])
            angle = float(disp[k]) if k < disp.size else None
            row: dict[str, Any] = {"joint": jn, "dof": dname, "moment_Nm": t,
                                   "direction": "toward upper" if t >= 0 else "toward lower"}
            for sex in sexes:
                grid = _strength_grid(kind, dname, sex, angle)[:, 1 if t >= 0 else 0]
                row[f"{sex}_capable_pct"] = percent_capable(abs(t), grid)
                row[f"{sex}_p50_strength_Nm"] = float(grid[list(P_GRID).index(50.0)])
            rows.append(row)
    score_key = {s: f"{s}_capable_pct" for s in sexes}
    def order(r: dict[str, Any], s: str) -> tuple[float, float]:  # ties (at the 99 % clamp): highest share of p50
        return r[score_key[s]], -abs(r["moment_Nm"]) / max(r[f"{s}_p50_strength_Nm"], 1e-9)

    weakest = {s: min(rows, key=lambda r: order(r, s)) for s in sexes}
    worst_sex = min(sexes, key=lambda s: weakest[s][score_key[s]])
    w = weakest[worst_sex]
    score = w[score_key[worst_sex]]
    lv = 1 if score >= 99.0 else (2 if score >= 75.0 else 3)
    text = {1: "almost everyone capable (>= 99 %)", 2: "most capable (75-99 %)",
            3: "fewer than 75 % capable: redesign"}[lv]
    ws = {"joints": rows, "sexes": sexes, "load_kg": task.load_kg, "weight_share": shares,
          "weakest": {s: {"joint": weakest[s]["joint"], "dof": weakest[s]["dof"],
                          "capable_pct": weakest[s][score_key[s]]} for s in sexes}}
    return Assessment("capable", score, lv, f"{text}; weakest {w['joint']} {w['dof']} ({worst_sex})", ws,
                      {"trunk_flexion": posture.trunk_flexion,
                       **{f"{s}_upper_arm_flexion": posture.arms[s].upper_arm_flexion for s in SIDES},
                       **{f"{s}_elbow_flexion": posture.arms[s].elbow_flexion for s in SIDES}},
                      "joint torques N·m per DOF (sign: + pushes toward the DOF's upper limit)", flags,
                      w["joint"], unit="%")


METHOD = register(Method("capable", "Percent capable (static strength)",
                         "statics: jackpy.analysis.statics; strength: jackpy.body.strength (data/strength.csv)",
                         VALIDITY, assess, (1, 3)))
