"""Joint strength: per DOF, the peak torque of the two opposing muscle groups (book §2.6.6).

Two data sets, sources named in the files:

* ``data/strength_posture.csv`` - hip, knee and ankle flexion/extension of young adults by sex, with
  their between-subject SDs and posture curves (Anderson, Madigan & Nussbaum 2007, Table 3):
  ``T(θ, P) = (c1 + z(P)·c1_sd) · m·g·h · max(POSTURE_FLOOR, cos(c2·(θ - c3)))``, floored at 20 % of
  the mean (m body mass in kg, h stature in m, θ the DOF angle in rad).
* ``data/strength_regression.csv`` - elbow flexion and wrist flexion toward their upper limits, by sex, from body size (Harbo, Brincks & Andersen 2012):
  ``T50 = I + A·age + H·h + W·m`` (age :data:`REFERENCE_AGE`), spread as the rows below.
* ``data/strength.csv`` - every other DOF and direction: 50th-percentile male torques that no cited
  source backs yet, a female ratio per body region (Laubach 1976) and
  ``T(P) = T50 · max(0.2, 1 + STRENGTH_CV·z(P))``; no posture dependence.
"""

from __future__ import annotations

from functools import cache

import numpy as np
from scipy.stats import norm

from jackpy.body.anthropometry import check_percentile, check_sex, data_rows, load_population
from jackpy.body.human import body_spec
from jackpy.body.skeleton import dof_names_of, joint_kind
from jackpy.peabody.model import Figure

#: coefficient of variation of strength within a sex, for the rows of strength.csv (no cited SD)
STRENGTH_CV = 0.25
#: lowest posture factor of a cosine curve (a numerical guard beyond the source's measured ranges)
POSTURE_FLOOR = 0.1
#: lowest strength as a fraction of the mean (1st-percentile guard of the normal model)
STRENGTH_FLOOR = 0.2
#: gravity (m/s^2) of the source's normalisation by body weight times stature
GRAVITY = 9.81
#: age (years) at which the age-dependent rows (strength_regression.csv) are evaluated [decision]
REFERENCE_AGE = 30.0


@cache
def strength_data() -> dict[tuple[str, str], tuple[float, float, float]]:
    """``{(joint kind, dof): (male_lower_Nm, male_upper_Nm, female_ratio)}`` of strength.csv."""
    return {(r["joint"], r["dof"]): (float(r["male_lower"]), float(r["male_upper"]), float(r["female_ratio"]))
            for r in data_rows("strength.csv")}


@cache
def posture_data() -> dict[tuple[str, str, str, str], tuple[float, float, float, float]]:
    """``{(joint kind, dof, "lower"|"upper", sex): (c1, c1_sd, c2, c3)}`` of strength_posture.csv."""
    return {(r["joint"], r["dof"], r["side"], r["sex"]): tuple(float(r[k]) for k in ("c1", "c1_sd", "c2", "c3"))
            for r in data_rows("strength_posture.csv")}


@cache
def regression_data() -> dict[tuple[str, str, str, str], tuple[float, float, float, float]]:
    """``{(joint kind, dof, "lower"|"upper", sex): (intercept, per year, per m, per kg)}`` of
    strength_regression.csv (N m)."""
    return {(r["joint"], r["dof"], r["side"], r["sex"]):
            tuple(float(r[k]) for k in ("intercept", "age_coef", "stature_coef", "mass_coef"))
            for r in data_rows("strength_regression.csv")}


def has_posture(kind: str, dof: str) -> bool:
    """Whether DOF ``dof`` of joint kind ``kind`` has cited posture-dependent strength."""
    return (kind, dof, "lower", "male") in posture_data()


def _median_body(sex: str) -> tuple[float, float]:
    pop = load_population("ansur2")
    return pop.value(sex, "mass", 50.0), pop.value(sex, "stature", 50.0)


def torque(kind: str, dof: str, sex: str, percentile: float, angle: float | None = None,
           mass_kg: float | None = None, stature_m: float | None = None) -> tuple[float, float]:
    """(toward-lower, toward-upper) peak isometric torque, N m, of one DOF for ``sex`` at ``percentile``.

    ``angle`` (rad, the DOF's displacement) evaluates the posture curve where the data have one;
    ``None`` gives each direction's peak over posture. ``mass_kg``/``stature_m`` scale the
    posture-dependent and regression rows (default: the sex's ANSUR II median body); the other
    rows ignore all three.
    """
    check_sex(sex)
    z = float(norm.ppf(check_percentile(percentile) / 100.0))
    m, h = _median_body(sex)
    m = m if mass_kg is None else float(mass_kg)
    h = h if stature_m is None else float(stature_m)
    if has_posture(kind, dof):
        out = []
        for side in ("lower", "upper"):
            c1, sd, c2, c3 = posture_data()[(kind, dof, side, sex)]
            shape = 1.0 if angle is None else max(POSTURE_FLOOR, float(np.cos(c2 * (float(angle) - c3))))
            out.append(max(STRENGTH_FLOOR * c1, c1 + z * sd) * m * GRAVITY * h * shape)
        return out[0], out[1]
    lo, hi, ratio = strength_data()[(kind, dof)]
    f = max(STRENGTH_FLOOR, 1.0 + STRENGTH_CV * z)
    out = []
    for side, t50 in (("lower", lo), ("upper", hi)):
        coef = regression_data().get((kind, dof, side, sex))
        if coef is not None:  # cited by sex and body size: no female ratio
            t50 = coef[0] + coef[1] * REFERENCE_AGE + coef[2] * h + coef[3] * m
        elif sex == "female":
            t50 *= ratio
        out.append(t50 * f)
    return out[0], out[1]


def strength_table(figure: Figure, sex: str | None = None, percentile: float | None = None,
                   at_posture: bool = False) -> dict[str, tuple[float, float]]:
    """Per DOF name (``joint[k]`` as :meth:`Figure.dof_names`): ``(lower_dir_Nm, upper_dir_Nm)``.

    Sex and percentile default to the figure's body specification. ``at_posture`` evaluates the
    posture curves at the figure's current joint angles (otherwise each direction's peak).
    """
    if sex is None or percentile is None:
        spec = body_spec(figure)
        sex = spec.sex if sex is None else sex
        percentile = spec.percentile if percentile is None else percentile
    out = {}
    for j in figure.joints.values():
        disp = np.asarray(j.displacement, dtype=float).reshape(-1)
        for k, name in enumerate(dof_names_of(j)):
            angle = float(disp[k]) if at_posture and k < disp.size else None
            out[f"{j.name}[{k}]"] = torque(joint_kind(j.name), name, sex, percentile, angle)
    return out
