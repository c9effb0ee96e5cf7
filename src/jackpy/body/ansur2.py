"""ANSUR II summary statistics and correlations, read from the shipped derived tables.

``data/ansur2_summary.csv`` and ``data/ansur2_correlations.csv`` are derived from the ANSUR II public
subject files (Gordon et al. 2014, NATICK/TR-15/007) by ``tools/derive_ansur2.py``; this module reads
only those shipped files. A dimension is named by its population-model key (``stature``, ``weight``,
``arm_length``, ...; see :func:`key_dimensions`) or by its ANSUR II measurement name
(``bideltoidbreadth``). Values are SI: metres for lengths, kilograms for weight.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import cache
from importlib import resources
from statistics import NormalDist

import numpy as np

from jackpy.body.anthropometry import AnthropometryError, check_percentile, check_sex, read_commented_csv

#: percentile points of the summary table
TABLE_PERCENTILES = (1.0, 5.0, 50.0, 95.0, 99.0)
_TO_SI = {"mm": 1e-3, "kg": 1.0}
_STANDARD_NORMAL = NormalDist()


@dataclass(frozen=True)
class MeasurementStats:
    """Sample statistics of one measurement of one sex (SI units: m or kg).

    ``key`` is the population-model name ('' for measurements outside the key set); ``measurement``
    is the ANSUR II name or formula (``acromionradialelength + radialestylionlength``).
    """

    key: str
    measurement: str
    unit: str
    n: int
    mean: float
    sd: float
    percentiles: dict[float, float]

    @property
    def name(self) -> str:
        return self.key or self.measurement


def _read(filename: str) -> tuple[dict[str, str], list[dict[str, str]]]:
    text = resources.files("jackpy.body").joinpath("data", filename).read_text(encoding="utf-8")
    header, lines = read_commented_csv(text)
    return header, list(csv.DictReader(lines))


@cache
def _summaries() -> dict[str, dict[str, MeasurementStats]]:
    tables: dict[str, dict[str, MeasurementStats]] = {"female": {}, "male": {}}
    for row in _read("ansur2_summary.csv")[1]:
        scale = _TO_SI[row["unit"]]
        stats = MeasurementStats(
            key=row["key"], measurement=row["measurement"], unit="kg" if row["unit"] == "kg" else "m",
            n=int(row["n"]), mean=float(row["mean"]) * scale, sd=float(row["sd"]) * scale,
            percentiles={p: float(row[f"p{int(p)}"]) * scale for p in TABLE_PERCENTILES})
        tables[row["sex"]][stats.name] = stats
    return tables


@cache
def _correlations() -> dict[str, tuple[list[str], np.ndarray]]:
    rows = _read("ansur2_correlations.csv")[1]
    out: dict[str, tuple[list[str], np.ndarray]] = {}
    for sex in ("female", "male"):
        mine = [r for r in rows if r["sex"] == sex]
        names = [r["dimension"] for r in mine]
        matrix = np.array([[float(r[c]) for c in names] for r in mine])
        matrix.setflags(write=False)
        out[sex] = (names, matrix)
    return out


def provenance() -> str:
    """The ``source`` and ``method`` header of the shipped summary table."""
    header = _read("ansur2_summary.csv")[0]
    return f"{header.get('source', '')} {header.get('method', '')}".strip()


def summary(sex: str) -> dict[str, MeasurementStats]:
    """All measurements of ``sex`` ('female' / 'male'), by key name (else ANSUR II name)."""
    return dict(_summaries()[check_sex(sex)])


def key_dimensions() -> list[str]:
    """Names of the key dimensions (rows/columns of the correlation tables)."""
    return list(_correlations()["male"][0])


def stats(sex: str, dim: str) -> MeasurementStats:
    """Statistics of one dimension, by key or ANSUR II measurement name."""
    table = _summaries()[check_sex(sex)]
    if dim in table:
        return table[dim]
    for s in table.values():
        if s.measurement == dim:
            return s
    raise AnthropometryError(f"ANSUR II has no dimension {dim!r} (keys: {', '.join(key_dimensions())})")


def correlations(sex: str, dims: list[str] | tuple[str, ...]) -> np.ndarray:
    """Pearson correlation matrix (len(dims), len(dims)) of key dimensions ``dims`` for ``sex``."""
    names, matrix = _correlations()[check_sex(sex)]
    index = {n: i for i, n in enumerate(names)}
    unknown = [d for d in dims if d not in index]
    if unknown:
        raise AnthropometryError(f"no ANSUR II correlations for {', '.join(map(repr, unknown))} "
                                 f"(key dimensions: {', '.join(names)})")
    idx = [index[d] for d in dims]
    return matrix[np.ix_(idx, idx)].copy()


def quantile(sex: str, dim: str, p: float) -> float:
    """Value (SI) of ``dim`` at percentile ``p`` (1..99) from the sample percentiles.

    Interpolates piecewise-linearly in standard-normal z between the tabulated P1/P5/P50/P95/P99,
    so a normally distributed measurement is reproduced exactly and skew is kept.
    """
    check_percentile(p)
    s = stats(sex, dim)
    z_points = [_STANDARD_NORMAL.inv_cdf(q / 100.0) for q in TABLE_PERCENTILES]
    values = [s.percentiles[q] for q in TABLE_PERCENTILES]
    return float(np.interp(_STANDARD_NORMAL.inv_cdf(p / 100.0), z_points, values))
