"""Joint strength: per DOF, the peak torque of the two opposing muscle groups (book §2.6.6).

Four data files, the source of every value named in them (summary in ``docs/strength.md``):

* ``data/strength_posture.csv`` - hip, knee and ankle flexion/extension of young adults by sex, with
  their between-subject SDs and posture curves (Anderson, Madigan & Nussbaum 2007, Table 3):
  ``T(θ, P) = (c1 + z(P)·c1_sd) · m·g·h · max(POSTURE_FLOOR, cos(c2·(θ - c3)))``, floored at 20 % of
  the mean (m body mass in kg, h stature in m, θ the DOF angle in rad).
* ``data/strength.csv`` - every other DOF and direction by sex: the mean, its SD where the source
  gives one, and the row's source (``UNCITED`` where none backs it).
* ``data/strength_regression.csv`` - elbow and wrist flexors from body size (Harbo, Brincks &
  Andersen 2012): ``T50 = I + A·age + H·h + W·m`` (age :data:`REFERENCE_AGE`).
* ``data/strength_curves.csv`` - torque against angle (Kamon 1981): shoulder elevation and elbow
  flexion. ``T(θ) = T · curve(θ) / max(curve)``, linear between the points and held beyond them.

Percentile P of the rows of strength.csv and strength_regression.csv: ``mean + z(P)·SD`` where an SD
is cited, otherwise ``mean · (1 + cv·z(P))`` with ``cv =`` :func:`default_cv`; floored at 20 % of the
mean.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np
from scipy.stats import norm

from jackpy.body.anthropometry import check_percentile, check_sex, data_rows, load_population
from jackpy.body.human import body_spec
from jackpy.body.skeleton import dof_names_of, joint_kind
from jackpy.peabody.model import Figure

#: lowest posture factor of a cosine curve (a numerical guard beyond the source's measured ranges)
POSTURE_FLOOR = 0.1
#: lowest strength as a fraction of the mean (1st-percentile guard of the normal model)
STRENGTH_FLOOR = 0.2
#: gravity (m/s^2) of the source's normalisation by body weight times stature
GRAVITY = 9.81
#: age (years) at which the age-dependent rows (strength_regression.csv) are evaluated [decision]
REFERENCE_AGE = 30.0
#: the source key of rows whose mean is the regression of strength_regression.csv
REGRESSION_SOURCE = "HARBO2012"
SIDES = ("lower", "upper")

Key = tuple[str, str, str, str]  # (joint kind, dof, "lower"|"upper", sex)

#: the strength rows of the neck (strength.csv's NECK2007 / NECKROT_F220 rows, measured at the head)
NECK_KIND = "atlanto_occipital"


def strength_kind(joint: str) -> str:
    """The joint kind whose strength rows a human joint uses: :func:`joint_kind`, except that the
    cervical joints (``c7_t1``, the neck's base, which :func:`joint_kind` counts as ``spine`` for
    its DOF names and the spine group) take the neck's rows, not the trunk's."""
    kind = joint_kind(joint)
    if kind == "spine" and joint.startswith("c"):
        return NECK_KIND
    return kind


@dataclass(frozen=True)
class StrengthRow:
    """One direction of one DOF for one sex (strength.csv): mean and SD in N m (``None``: the mean
    is the regression of strength_regression.csv / no SD cited) and the source key."""

    mean: float | None
    sd: float | None
    source: str


def _number(text: str) -> float | None:
    return float(text) if text.strip() else None


@cache
def strength_rows() -> dict[Key, StrengthRow]:
    """``{(joint kind, dof, side, sex): StrengthRow}`` of strength.csv, female ratios applied."""
    raw = {(r["joint"], r["dof"], r["side"], r["sex"]): r for r in data_rows("strength.csv")}
    out: dict[Key, StrengthRow] = {}
    for key, r in raw.items():
        mean, ratio = _number(r["mean_Nm"]), _number(r["ratio_of_male"])
        if mean is None and ratio is not None:
            male = _number(raw[key[:3] + ("male",)]["mean_Nm"])
            if male is None:
                raise ValueError(f"strength.csv: {key}: ratio_of_male needs a male mean_Nm")
            mean = male * ratio
        if mean is None and r["source"] != REGRESSION_SOURCE:
            raise ValueError(f"strength.csv: {key}: no mean_Nm, ratio_of_male or {REGRESSION_SOURCE} regression")
        out[key] = StrengthRow(mean, _number(r["sd_Nm"]), r["source"])
    return out


@cache
def posture_data() -> dict[Key, tuple[float, float, float, float]]:
    """``{(joint kind, dof, "lower"|"upper", sex): (c1, c1_sd, c2, c3)}`` of strength_posture.csv."""
    return {(r["joint"], r["dof"], r["side"], r["sex"]): tuple(float(r[k]) for k in ("c1", "c1_sd", "c2", "c3"))
            for r in data_rows("strength_posture.csv")}


@cache
def regression_data() -> dict[Key, tuple[float, float, float, float]]:
    """``{(joint kind, dof, "lower"|"upper", sex): (intercept, per year, per m, per kg)}`` of
    strength_regression.csv (N m)."""
    return {(r["joint"], r["dof"], r["side"], r["sex"]):
            tuple(float(r[k]) for k in ("intercept", "age_coef", "stature_coef", "mass_coef"))
            for r in data_rows("strength_regression.csv")}


@cache
def curve_data() -> dict[Key, tuple[np.ndarray, np.ndarray]]:
    """``{(joint kind, dof, side, sex): (angles rad ascending, torques N m)}`` of strength_curves.csv."""
    points: dict[Key, list[tuple[float, float]]] = {}
    for r in data_rows("strength_curves.csv"):
        points.setdefault((r["joint"], r["dof"], r["side"], r["sex"]), []).append(
            (np.radians(float(r["angle_deg"])), float(r["torque_Nm"])))
    return {k: tuple(np.array(c) for c in zip(*sorted(v))) for k, v in points.items()}


@cache
def default_cv() -> float:
    """Coefficient of variation given to rows with no cited SD: the mean SD/mean of every row whose
    SD is cited (strength_posture.csv's c1_sd/c1 and strength.csv's sd_Nm/mean_Nm) [decision]."""
    cvs = [sd / c1 for c1, sd, _, _ in posture_data().values()]
    cvs += [r.sd / r.mean for r in strength_rows().values() if r.sd is not None and r.mean]
    return float(np.mean(cvs))


def has_posture(kind: str, dof: str, include_curves: bool = False) -> bool:
    """Whether DOF ``dof`` of joint kind ``kind`` has cited posture-dependent strength (either side):
    the cosine rows of strength_posture.csv and, with ``include_curves``, the angle curves of
    strength_curves.csv (shoulder elevation, elbow flexion). :func:`torque` applies both whenever it
    is given an angle; ``include_curves`` defaults to False so that callers written before the curves
    (planning's lifting monitor) keep their results until they opt in."""
    tables = (posture_data(), curve_data()) if include_curves else (posture_data(),)
    return any((kind, dof, side, "male") in table for table in tables for side in SIDES)


def source_of(kind: str, dof: str, side: str, sex: str) -> str:
    """The source key of one direction's strength (``UNCITED`` where no source backs it)."""
    if (kind, dof, side, sex) in posture_data():
        return "ANDERSON2007"
    return strength_rows()[(kind, dof, side, sex)].source


def posture_factor(kind: str, dof: str, side: str, sex: str, angle: float) -> float:
    """``curve(angle) / max(curve)`` of strength_curves.csv (1 where the row has no curve); ``angle``
    in rad, the end values held beyond the curve's points."""
    curve = curve_data().get((kind, dof, side, sex))
    if curve is None:
        return 1.0
    angles, torques = curve
    return float(np.interp(float(angle), angles, torques) / torques.max())


@cache
def _median_body(sex: str) -> tuple[float, float]:
    pop = load_population("ansur2")
    return pop.value(sex, "mass", 50.0), pop.value(sex, "stature", 50.0)


@cache
def _z(percentile: float) -> float:
    """The normal quantile of a checked percentile (cached: one per figure size)."""
    return float(norm.ppf(percentile / 100.0))


def _spread(mean: float, sd: float | None, z: float) -> float:
    value = mean + z * sd if sd is not None else mean * (1.0 + default_cv() * z)
    return max(STRENGTH_FLOOR * mean, value)


def torque(kind: str, dof: str, sex: str, percentile: float, angle: float | None = None,
           mass_kg: float | None = None, stature_m: float | None = None) -> tuple[float, float]:
    """(toward-lower, toward-upper) peak isometric torque, N m, of one DOF for ``sex`` at ``percentile``.

    ``angle`` (rad, the DOF's displacement) evaluates the posture curves where the data have one;
    ``None`` gives each direction's peak over posture. ``mass_kg``/``stature_m`` scale the
    posture-dependent and regression rows (default: the sex's ANSUR II median body); the other
    rows ignore both.
    """
    check_sex(sex)
    z = _z(float(check_percentile(percentile)))
    m, h = _median_body(sex)
    m = m if mass_kg is None else float(mass_kg)
    h = h if stature_m is None else float(stature_m)
    out = []
    for side in SIDES:
        key = (kind, dof, side, sex)
        if key in posture_data():
            c1, sd, c2, c3 = posture_data()[key]
            shape = 1.0 if angle is None else max(POSTURE_FLOOR, float(np.cos(c2 * (float(angle) - c3))))
            out.append(max(STRENGTH_FLOOR * c1, c1 + z * sd) * m * GRAVITY * h * shape)
            continue
        row = strength_rows()[key]
        mean = row.mean
        if row.source == REGRESSION_SOURCE:
            i, a, hc, w = regression_data()[key]
            mean = i + a * REFERENCE_AGE + hc * h + w * m
        shape = 1.0 if angle is None else posture_factor(kind, dof, side, sex, angle)
        out.append(_spread(mean, row.sd, z) * shape)
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
            out[f"{j.name}[{k}]"] = torque(strength_kind(j.name), name, sex, percentile, angle)
    return out
