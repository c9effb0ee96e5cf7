"""Joint ranges of motion from ``data/joint_limits.csv`` and ``data/spine.csv`` (sources named there)."""

from __future__ import annotations

from functools import cache

import numpy as np

from jackpy.body.anthropometry import data_rows

#: flexion share of the combined flexion+extension range of a vertebral level [proposal, spine.csv]
SPINE_FLEXION_SHARE = 0.6


@cache
def joint_limits() -> dict[tuple[str, str], tuple[float, float]]:
    """``{(joint kind, dof name): (lower, upper)}`` in radians, for the left side (right mirrors)."""
    return {(r["joint"], r["dof"]): (np.radians(float(r["lower_deg"])), np.radians(float(r["upper_deg"])))
            for r in data_rows("joint_limits.csv")}


def limits(kind: str, dof: str) -> tuple[float, float]:
    """(lower, upper) radians of DOF ``dof`` of a joint of kind ``kind`` (e.g. ``"hip", "flexion"``)."""
    return joint_limits()[(kind, dof)]


@cache
def spine_levels() -> list[dict[str, object]]:
    """The 18 vertebral joints bottom to top: names, relative vertebra height and limits (radians).

    Each entry has ``joint``, ``below``, ``above``, ``height`` (relative, ``None`` for the neck joint)
    and ``limits`` ``{dof: (lower, upper)}`` for ``axial``, ``lateral``, ``flexion``.
    """
    out = []
    for r in data_rows("spine.csv"):
        fe = np.radians(float(r["flex_ext"]))
        lat = np.radians(float(r["lateral"]))
        ax = np.radians(float(r["axial"]))
        out.append({
            "joint": r["joint"], "below": r["below"], "above": r["above"],
            "height": float(r["height"]) if r["height"] else None,
            "limits": {"axial": (-ax, ax), "lateral": (-lat, lat),
                       "flexion": (-(1 - SPINE_FLEXION_SHARE) * fe, SPINE_FLEXION_SHARE * fe)},
        })
    return out
