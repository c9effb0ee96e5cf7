"""The multivariate population model: per sex, the means, standard deviations and correlations of the
key body dimensions (ANSUR II, :mod:`jackpy.body.ansur2`), as a multivariate normal distribution.

Dimensions are the population-model keys of the ANSUR II tables (``stature``, ``weight``,
``sitting_height``, ``span``, ``bideltoid_breadth``, ``hip_breadth_sitting``, ``foot_length``, ...);
values are SI (metres, kilograms). The model answers Mahalanobis distances, principal axes and the
conditional mean of any key dimension given others (the regression used to fill in the dimensions a
family or a user leaves open).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from jackpy.body import ansur2
from jackpy.body.anthropometry import AnthropometryError, SEXES, check_sex

#: the dimensions a sweep's bodies vary in by default (each is set on the figure and measured from it)
DEFAULT_DIMENSIONS = ("stature", "weight", "sitting_height", "span", "bideltoid_breadth",
                      "hip_breadth_sitting", "foot_length")


@dataclass(frozen=True)
class SexModel:
    """One sex's multivariate normal model of ``dims``: ``mean`` and ``sd`` (SI), ``corr`` (d, d)."""

    sex: str
    dims: tuple[str, ...]
    mean: np.ndarray
    sd: np.ndarray
    corr: np.ndarray

    @cached_property
    def cov(self) -> np.ndarray:
        """Covariance matrix (SI units squared)."""
        return self.corr * np.outer(self.sd, self.sd)

    def index(self, dim: str) -> int:
        try:
            return self.dims.index(dim)
        except ValueError:
            raise AnthropometryError(f"the population model has no dimension {dim!r} "
                                     f"(dimensions: {', '.join(self.dims)})") from None

    def z(self, values: Mapping[str, float]) -> np.ndarray:
        """Standard scores of a full set of values (one per model dimension)."""
        return (np.array([values[d] for d in self.dims]) - self.mean) / self.sd

    def mahalanobis(self, values: Mapping[str, float], dims: Sequence[str] | None = None) -> float:
        """Mahalanobis distance of ``values`` from the mean over ``dims`` (default: all)."""
        dims = tuple(dims or self.dims)
        idx = [self.index(d) for d in dims]
        x = np.array([values[d] for d in dims]) - self.mean[idx]
        return float(np.sqrt(x @ np.linalg.solve(self.cov[np.ix_(idx, idx)], x)))

    def principal_axes(self, dims: Sequence[str] | None = None) -> tuple[np.ndarray, np.ndarray]:
        """PCA of the standardised ``dims``: eigenvalues (descending) and unit eigenvectors (columns)
        of their correlation matrix."""
        idx = [self.index(d) for d in (dims or self.dims)]
        w, v = np.linalg.eigh(self.corr[np.ix_(idx, idx)])
        order = np.argsort(w)[::-1]
        v = v[:, order]
        v *= np.where(v.sum(axis=0) < 0, -1.0, 1.0)  # sign: components point towards larger bodies
        return w[order], v

    def conditional_mean(self, given: Mapping[str, float]) -> dict[str, float]:
        """Every dimension's expected value given the ``given`` ones (regression of the normal model);
        the given values are returned unchanged."""
        known = [self.index(d) for d in given]
        if not known:
            return dict(zip(self.dims, map(float, self.mean)))
        rest = [i for i in range(len(self.dims)) if i not in known]
        x = np.array([given[self.dims[i]] for i in known]) - self.mean[known]
        c = self.cov
        fill = self.mean[rest] + c[np.ix_(rest, known)] @ np.linalg.solve(c[np.ix_(known, known)], x)
        out = {d: float(given[d]) for d in given}
        out.update({self.dims[i]: float(v) for i, v in zip(rest, fill)})
        return {d: out[d] for d in self.dims}


@dataclass(frozen=True)
class PopulationModel:
    """The multivariate model of ``dims`` for both sexes (:class:`SexModel` per sex)."""

    dims: tuple[str, ...]
    sexes: dict[str, SexModel]
    source: str

    def sex(self, sex: str) -> SexModel:
        return self.sexes[check_sex(sex)]

    @classmethod
    def ansur2(cls, dims: Sequence[str] = DEFAULT_DIMENSIONS) -> PopulationModel:
        """The model of ``dims`` (key dimensions of the ANSUR II tables) from the shipped tables."""
        dims = tuple(dims)
        if len(set(dims)) != len(dims) or not dims:
            raise AnthropometryError(f"population dimensions must be distinct and not empty: {dims}")
        sexes = {}
        for sex in SEXES:
            stats = [ansur2.stats(sex, d) for d in dims]
            sexes[sex] = SexModel(sex, dims, np.array([s.mean for s in stats]), np.array([s.sd for s in stats]),
                                  ansur2.correlations(sex, dims))
        return cls(dims, sexes, ansur2.provenance())
