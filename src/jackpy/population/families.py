"""Manikin families: boundary cases on the ellipse or ellipsoid enclosing an accommodation share,
plus the centre case, and Monte Carlo populations.

**Boundary cases** (the multivariate method of RAMSIS / IMMA manikin families; Bittner 2000,
Brolin et al. 2012): for ``k`` family dimensions with covariance ``C``, the region holding share
``p`` of a normal population is the ellipsoid ``(x - m)^T C^-1 (x - m) = r^2`` with
``r^2 = chi2.ppf(p, k)``. Two dimensions: ``n`` cases (default 8) evenly around the ellipse in the
principal-axis frame (axis ends and diagonals). More dimensions: PCA of the standardised
dimensions; the ellipsoid in the first ``components`` principal components (``r^2 = chi2.ppf(p,
components)``) with a case at each end of each axis. Every dimension outside the family's comes
from its regression on the family's (the normal model's conditional mean).

**Monte Carlo**: ``n`` bodies with share ``sex_mix`` female, drawn from each sex's multivariate
normal model with a seeded generator, **moment-matched** (each sex's sample is centred and
whitened, so its sample mean and covariance equal the model's exactly: a variance-reduction step
that keeps 5,000 bodies from carrying ~1 % sampling error in their SDs), in a seeded random order
of the sexes.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.stats import chi2

from jackpy.body.anthropometry import AnthropometryError, check_sex
from jackpy.population.generate import Body, make_body
from jackpy.population.model import PopulationModel, SexModel


def radius(share: float, k: int) -> float:
    """Mahalanobis radius of the ellipsoid holding ``share`` (0..1) of a ``k``-variate normal."""
    if not 0.0 < share < 1.0:
        raise AnthropometryError(f"accommodation share must be between 0 and 1 (exclusive), not {share}")
    return float(np.sqrt(chi2.ppf(share, k)))


def boundary_points(sm: SexModel, dims: Sequence[str], share: float, n: int = 8,
                    components: int | None = None) -> list[dict[str, float]]:
    """Boundary cases (SI values of ``dims``) of one sex; see the module docstring."""
    dims = tuple(dims)
    idx = [sm.index(d) for d in dims]
    mean, sd = sm.mean[idx], sm.sd[idx]
    w, v = sm.principal_axes(dims)
    if len(dims) == 2 and components is None:
        r = radius(share, 2)
        angles = 2 * np.pi * np.arange(n) / n
        unit = np.column_stack([np.cos(angles), np.sin(angles)])
    else:
        k = components or min(3, len(dims))
        if not 1 <= k <= len(dims):
            raise AnthropometryError(f"components must be between 1 and {len(dims)}, not {k}")
        r = radius(share, k)
        unit = np.vstack([s * np.eye(len(dims))[i] for i in range(k) for s in (1.0, -1.0)])[:, :k]
        w, v = w[:k], v[:, :k]
    z = (unit * r * np.sqrt(w)) @ v.T  # standard scores on the ellipsoid
    return [dict(zip(dims, mean + zi * sd)) for zi in z]


def family(model: PopulationModel, share: float = 0.9, dims: Sequence[str] = ("stature", "weight"),
           sexes: Sequence[str] = ("female", "male"), n: int = 8, components: int | None = None,
           centre: bool = True) -> list[Body]:
    """The family of boundary cases (and centre cases) of ``dims`` holding ``share`` of each sex."""
    bodies: list[Body] = []
    for sex in sexes:
        sm = model.sex(check_sex(sex))
        cases = [(f"boundary {k + 1}", p) for k, p in enumerate(boundary_points(sm, dims, share, n, components))]
        if centre:
            cases.append(("centre", {d: float(sm.mean[sm.index(d)]) for d in dims}))
        for label, values in cases:
            bodies.append(make_body(len(bodies), sex, sm.conditional_mean(values), label))
    return bodies


def monte_carlo(model: PopulationModel, n: int, sex_mix: float = 0.5, seed: int = 0) -> list[Body]:
    """``n`` Monte Carlo bodies, ``round(n * sex_mix)`` of them female (module docstring)."""
    if n < 1:
        raise AnthropometryError(f"the population needs at least one body, not {n}")
    if not 0.0 <= sex_mix <= 1.0:
        raise AnthropometryError(f"sex mix (share of women) must be between 0 and 1, not {sex_mix}")
    n_female = int(round(n * sex_mix))
    counts = {"female": n_female, "male": n - n_female}
    seeds = np.random.SeedSequence(seed).spawn(3)
    samples = {}
    for (sex, count), ss in zip(counts.items(), seeds[:2]):
        sm = model.sex(sex)
        samples[sex] = iter(_matched_normal(np.random.default_rng(ss), count, sm))
    order = np.array(["female"] * counts["female"] + ["male"] * counts["male"])
    np.random.default_rng(seeds[2]).shuffle(order)
    return [make_body(i, str(sex), next(samples[str(sex)])) for i, sex in enumerate(order)]


def _matched_normal(rng: np.random.Generator, count: int, sm: SexModel) -> list[dict[str, float]]:
    d = len(sm.dims)
    z = rng.standard_normal((count, d))
    if count > d + 1:
        z -= z.mean(axis=0)
        z = z @ np.linalg.inv(np.linalg.cholesky(np.cov(z, rowvar=False))).T
    x = sm.mean + z @ np.linalg.cholesky(sm.cov).T
    return [dict(zip(sm.dims, row)) for row in x]
