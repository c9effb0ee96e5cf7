"""Joint strength: per DOF, the peak torque of the two opposing muscle groups (book §2.6.6).

Data and model in ``data/strength.csv`` (sources named there): 50th-percentile male torques per joint
DOF and direction, a female ratio per body region (Laubach 1976), and a percentile model
``T(P) = T50 * max(0.2, 1 + cv * z(P))`` with ``cv = 0.25``. Posture dependence is not modelled yet.
"""

from __future__ import annotations

from functools import cache

from scipy.stats import norm

from jackpy.body.anthropometry import check_percentile, check_sex, data_rows
from jackpy.body.human import body_spec
from jackpy.body.skeleton import dof_names_of, joint_kind
from jackpy.peabody.model import Figure

#: coefficient of variation of strength within a sex
STRENGTH_CV = 0.25


@cache
def strength_data() -> dict[tuple[str, str], tuple[float, float, float]]:
    """``{(joint kind, dof): (male_lower_Nm, male_upper_Nm, female_ratio)}``."""
    return {(r["joint"], r["dof"]): (float(r["male_lower"]), float(r["male_upper"]), float(r["female_ratio"]))
            for r in data_rows("strength.csv")}


def torque(kind: str, dof: str, sex: str, percentile: float) -> tuple[float, float]:
    """(toward-lower, toward-upper) peak torque, N m, of one DOF for ``sex`` at ``percentile``."""
    check_sex(sex)
    lo, hi, ratio = strength_data()[(kind, dof)]
    f = max(0.2, 1.0 + STRENGTH_CV * float(norm.ppf(check_percentile(percentile) / 100.0)))
    if sex == "female":
        f *= ratio
    return lo * f, hi * f


def strength_table(figure: Figure, sex: str | None = None, percentile: float | None = None) -> dict[str, tuple[float, float]]:
    """Per DOF name (``joint[k]`` as :meth:`Figure.dof_names`): ``(lower_dir_Nm, upper_dir_Nm)``.

    Sex and percentile default to the figure's body specification.
    """
    if sex is None or percentile is None:
        spec = body_spec(figure)
        sex = spec.sex if sex is None else sex
        percentile = spec.percentile if percentile is None else percentile
    out = {}
    for j in figure.joints.values():
        for k, name in enumerate(dof_names_of(j)):
            out[f"{j.name}[{k}]"] = torque(joint_kind(j.name), name, sex, percentile)
    return out
