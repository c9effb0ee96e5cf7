"""Joint ranges of motion from ``data/joint_limits.csv`` and ``data/spine.csv`` (sources named there)."""

from __future__ import annotations

from functools import cache

import numpy as np

from jackpy.body.anthropometry import data_rows

#: flexion share of the combined flexion+extension range of a vertebral level [proposal, spine.csv]
SPINE_FLEXION_SHARE = 0.6
#: AAOS (1965) whole-region ranges, degrees: thoracolumbar (L5/S1 .. T1/T2, the 17 joints below the
#: neck) and cervical (C7/T1 plus the atlanto-occipital joint) - flexion, extension, lateral bend and
#: rotation to one side. The per-level ranges of spine.csv (White & Panjabi) give each level's share.
AAOS_THORACOLUMBAR = {"flexion": 80.0, "extension": 25.0, "lateral": 35.0, "axial": 45.0}
AAOS_CERVICAL = {"flexion": 45.0, "extension": 45.0, "lateral": 45.0, "axial": 60.0}


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
    and ``limits`` ``{dof: (lower, upper)}`` for ``axial``, ``lateral``, ``flexion``. The 17
    thoracolumbar levels' White & Panjabi ranges (flexion = SPINE_FLEXION_SHARE of flex_ext) are scaled
    per direction so that they sum to :data:`AAOS_THORACOLUMBAR`: the region's total range is AAOS's,
    its distribution over the levels White & Panjabi's (which the Monheit weighting then shares).
    C7/T1 keeps its White & Panjabi range; the atlanto-occipital joint takes the rest of AAOS's
    cervical range (joint_limits.csv).
    """
    rows = data_rows("spine.csv")
    raw = []
    for r in rows:
        fe, lat, ax = (float(r[k]) for k in ("flex_ext", "lateral", "axial"))
        raw.append({"flexion": SPINE_FLEXION_SHARE * fe, "extension": (1 - SPINE_FLEXION_SHARE) * fe,
                    "lateral": lat, "axial": ax})
    body = raw[:-1]
    scale = {k: AAOS_THORACOLUMBAR[k] / sum(lv[k] for lv in body) for k in AAOS_THORACOLUMBAR}
    out = []
    for i, (r, lv) in enumerate(zip(rows, raw)):
        f = scale if i < len(body) else dict.fromkeys(scale, 1.0)
        fl, ex, lat, ax = (np.radians(lv[k] * f[k]) for k in ("flexion", "extension", "lateral", "axial"))
        out.append({
            "joint": r["joint"], "below": r["below"], "above": r["above"],
            "height": float(r["height"]) if r["height"] else None,
            "limits": {"axial": (-ax, ax), "lateral": (-lat, lat), "flexion": (-ex, fl)},
        })
    return out
