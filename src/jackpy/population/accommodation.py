"""The accommodation table: per criterion and for all criteria together, the share of the bodies
that pass (all and per sex) and the **binding dimension**.

The binding dimension of a criterion is the body dimension most correlated with passing it: the
largest absolute point-biserial correlation between the pass indicator (1/0) and the dimension's
value over all bodies (absolute values: reach and view depend on absolute size, whatever the sex).
Its sign says which bodies fail: ``small`` (passing goes with larger values: e.g. a high shelf) or
``large`` (e.g. headroom). A criterion every body passes, or none, has no binding dimension.
For a family the shares are of its cases, not of a population.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from jackpy.population.generate import CONTROLLED
from jackpy.population.study import Study

COLUMNS = ("criterion", "bodies", "passed", "share", "share_female", "share_male", "binding_dimension",
           "binding_r", "fails_when")


@dataclass(frozen=True)
class Accommodation:
    """One line of the table (``criterion`` is a criterion id or ``all``)."""

    criterion: str
    bodies: int
    passed: int
    share: float
    share_female: float | None
    share_male: float | None
    binding_dimension: str | None
    binding_r: float | None
    fails_when: str | None

    def as_row(self) -> dict[str, Any]:
        return {c: getattr(self, c) for c in COLUMNS}


def binding(passed: np.ndarray, values: dict[str, np.ndarray]) -> tuple[str | None, float | None, str | None]:
    """(dimension, correlation, ``small``/``large``) most associated with failing; Nones if no spread."""
    if passed.min() == passed.max():
        return None, None, None
    best, best_r = None, 0.0
    for dim, x in values.items():
        if np.ptp(x) == 0:
            continue
        r = float(np.corrcoef(passed, x)[0, 1])
        if abs(r) > abs(best_r):
            best, best_r = dim, r
    if best is None:
        return None, None, None
    return best, best_r, "small" if best_r > 0 else "large"


def accommodation(study: Study, rows: list[dict[str, Any]]) -> list[Accommodation]:
    """The table for the per-body ``rows`` of ``study`` (criteria in study order, then ``all``)."""
    if not rows:
        return []
    values = {d: np.array([r[d] for r in rows], dtype=float) for d in CONTROLLED}
    sex = np.array([r["sex"] for r in rows])
    out = []
    for cid in [c.id for c in study.criteria] + ["all"]:
        ok = np.array([r[cid] for r in rows], dtype=float)
        per_sex = {s: (float(ok[sex == s].mean()) if np.any(sex == s) else None) for s in ("female", "male")}
        dim, r, when = binding(ok, values)
        out.append(Accommodation(cid, len(rows), int(ok.sum()), float(ok.mean()), per_sex["female"], per_sex["male"],
                                 dim, r, when))
    return out
