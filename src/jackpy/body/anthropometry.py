"""Anthropometric populations: percentile tables per sex and dimension, read from package CSV files.

A population file ``data/population_<name>.csv`` holds, per sex and dimension, the mean, the SD, the
correlations with stature and weight, the least-squares regression on stature and weight
(``a + b_stature * stature + b_weight * weight``) and, for reading, the values at the percentiles
1, 5, 25, 50, 75, 95, 99. Percentile <-> value uses the **normal quantile** of the mean and SD
(**lognormal** for ``mass``), not linear interpolation between the table points (book §2.6.1: body
size is not linear in percentile). Values are returned in SI units: metres for lengths (the files
hold millimetres), kilograms for ``mass``. Dimension names are ``part.measure`` (``thigh.length``,
``hip.breadth``) plus the globals ``stature``, ``mass`` and ``eye_height``; see docs/body.md.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import cache
from importlib import resources

import numpy as np
from scipy.stats import norm

from jackpy.errors import JackpyError

#: the percentile points every population table gives
PERCENTILES = np.array([1.0, 5.0, 25.0, 50.0, 75.0, 95.0, 99.0])
SEXES = ("female", "male")
_UNIT_TO_SI = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "kg": 1.0}


class AnthropometryError(JackpyError):
    """Unknown population, sex or dimension, or a percentile or value out of range."""


@dataclass(frozen=True)
class Dimension:
    """One dimension of one sex (SI units): ``values`` (7,) at :data:`PERCENTILES`, ``mean`` and ``sd``;
    ``regression`` = ``(a, b_stature, b_weight)`` (value = a + b_stature * stature_m + b_weight * mass_kg)
    or ``None`` when the file gives none; ``lognormal`` for body mass."""

    name: str
    unit: str
    values: np.ndarray
    measure: str
    mean: float = float("nan")
    sd: float = float("nan")
    regression: tuple[float, float, float] | None = None
    lognormal: bool = False

    def _log_params(self) -> tuple[float, float]:
        s2 = np.log1p((self.sd / self.mean) ** 2)
        return float(np.log(self.mean) - s2 / 2), float(np.sqrt(s2))

    def value(self, percentile: float) -> float:
        """Value at ``percentile`` (1..99): normal quantile of mean and SD (lognormal for mass);
        tables without mean/SD interpolate their points in standard-normal z."""
        z = float(norm.ppf(check_percentile(percentile) / 100.0))
        if not np.isfinite(self.sd):
            return float(np.interp(z, norm.ppf(PERCENTILES / 100.0), self.values))
        if self.lognormal:
            mu, sigma = self._log_params()
            return float(np.exp(mu + z * sigma))
        return self.mean + z * self.sd

    def percentile(self, value: float) -> float:
        """Inverse of :meth:`value`, clamped to 1..99."""
        if not np.isfinite(self.sd):
            z = float(np.interp(value, self.values, norm.ppf(PERCENTILES / 100.0)))
        elif self.lognormal:
            mu, sigma = self._log_params()
            z = (np.log(max(value, 1e-12)) - mu) / sigma
        else:
            z = (value - self.mean) / self.sd
        return float(np.clip(100.0 * norm.cdf(z), 1.0, 99.0))

    def predict(self, stature: float, mass: float) -> float:
        """Regression value (SI) for a body of ``stature`` metres and ``mass`` kg; the mean without one."""
        if self.regression is None:
            return self.mean if np.isfinite(self.mean) else float(self.values[3])
        a, bs, bw = self.regression
        return float(a + bs * stature + bw * mass)


@dataclass(frozen=True)
class Population:
    """A population's tables: ``dims[sex][name]`` -> :class:`Dimension`; ``source`` from the file."""

    name: str
    title: str
    source: str
    dims: dict[str, dict[str, Dimension]]

    def dimension(self, sex: str, name: str) -> Dimension:
        table = self.dims.get(check_sex(sex), {})
        if name not in table:
            raise AnthropometryError(f"population {self.name!r} has no dimension {name!r} "
                                     f"(known: {', '.join(sorted(table))})")
        return table[name]

    def value(self, sex: str, name: str, percentile: float) -> float:
        """Dimension ``name`` at ``percentile`` (SI units)."""
        return self.dimension(sex, name).value(percentile)

    def percentile(self, sex: str, name: str, value: float) -> float:
        """Percentile of ``value`` (SI units) for dimension ``name``."""
        return self.dimension(sex, name).percentile(value)

    def names(self, sex: str) -> list[str]:
        return list(self.dims[check_sex(sex)])


def check_sex(sex: str) -> str:
    if sex not in SEXES:
        raise AnthropometryError(f"sex must be one of {', '.join(SEXES)}, not {sex!r}")
    return sex


def check_percentile(p: float) -> float:
    if not (np.isfinite(p) and 1.0 <= p <= 99.0):
        raise AnthropometryError(f"percentile must be between 1 and 99, not {p}")
    return float(p)


def available_populations() -> list[str]:
    """Names of the populations shipped in the package."""
    files = resources.files("jackpy.body").joinpath("data").iterdir()
    return sorted(f.name[len("population_"):-4] for f in files
                  if f.name.startswith("population_") and f.name.endswith(".csv"))


def read_commented_csv(text: str) -> tuple[dict[str, str], list[str]]:
    """Split a data file into its ``# key: value`` header (``#   `` lines continue a value) and CSV lines."""
    header: dict[str, str] = {}
    lines = []
    for line in text.splitlines():
        if not line.startswith("#"):
            lines.append(line)
        elif line.startswith("#   ") and header:
            last = next(reversed(header))
            header[last] += " " + line[1:].strip()
        else:
            key, _, val = line[1:].partition(":")
            header[key.strip()] = val.strip()
    return header, lines


def data_rows(filename: str) -> list[dict[str, str]]:
    """The CSV rows of ``jackpy/body/data/<filename>`` (comment lines skipped)."""
    text = resources.files("jackpy.body").joinpath("data", filename).read_text()
    return list(csv.DictReader(read_commented_csv(text)[1]))


@cache
def load_population(name: str = "ansur2") -> Population:
    """Load a shipped population by name (cached; the result is immutable)."""
    if name not in available_populations():
        raise AnthropometryError(f"unknown population {name!r} (available: {', '.join(available_populations())})")
    text = resources.files("jackpy.body").joinpath("data", f"population_{name}.csv").read_text()
    header, lines = read_commented_csv(text)
    dims: dict[str, dict[str, Dimension]] = {s: {} for s in SEXES}
    for row in csv.DictReader(lines):
        scale = _UNIT_TO_SI[row["unit"]]
        values = np.array([float(row[f"p{int(p)}"]) for p in PERCENTILES]) * scale
        unit = "kg" if row["unit"] == "kg" else "m"
        mean = float(row["mean"]) * scale if row.get("mean") else float("nan")
        sd = float(row["sd"]) * scale if row.get("sd") else float("nan")
        reg = None
        if row.get("a"):  # file: a in the row's unit, b_stature per mm of stature, b_weight per kg
            reg = (float(row["a"]) * scale, float(row["b_stature"]) * scale / 1e-3, float(row["b_weight"]) * scale)
        dims[row["sex"]][row["dimension"]] = Dimension(row["dimension"], unit, values, row["measure"], mean, sd,
                                                       reg, row["dimension"] == "mass")
    return Population(name, header.get("title", name), header.get("source", ""), dims)
