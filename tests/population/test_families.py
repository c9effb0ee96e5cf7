"""Families: boundary cases on the ellipse/ellipsoid of the accommodation share (checked
analytically); Monte Carlo populations: seeded, sex mix, moments matched."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import chi2

from jackpy.body.anthropometry import AnthropometryError
from jackpy.population.families import boundary_points, family, monte_carlo, radius
from jackpy.population.model import PopulationModel

MODEL = PopulationModel.ansur2()


@pytest.mark.parametrize("sex", ["female", "male"])
def test_90_percent_stature_weight_family_lies_on_the_90_percent_ellipse(sex: str) -> None:
    sm = MODEL.sex(sex)
    cases = boundary_points(sm, ("stature", "weight"), 0.90, n=8)
    assert len(cases) == 8
    i, j = sm.index("stature"), sm.index("weight")
    cov = sm.cov[np.ix_([i, j], [i, j])]
    for c in cases:
        x = np.array([c["stature"], c["weight"]]) - sm.mean[[i, j]]
        d2 = x @ np.linalg.solve(cov, x)
        assert chi2.cdf(d2, 2) == pytest.approx(0.90, abs=1e-9)
        assert d2 == pytest.approx(-2 * np.log(0.1))  # the 2-D chi-square quantile in closed form
    # the axis ends: the first case is the end of the major axis, opposite cases mirror each other
    pts = np.array([[c["stature"], c["weight"]] for c in cases])
    assert np.allclose(pts[:4] + pts[4:], 2 * sm.mean[[i, j]])


def test_family_bodies_keep_their_boundary_values_and_have_a_centre() -> None:
    bodies = family(MODEL, 0.9, ("stature", "weight"), sexes=("male",))
    assert [b.label for b in bodies] == [f"boundary {k}" for k in range(1, 9)] + ["centre"]
    sm = MODEL.sex("male")
    for b in bodies[:8]:
        assert sm.mahalanobis(b.values, ["stature", "weight"]) == pytest.approx(radius(0.9, 2))
    assert bodies[8].values["stature"] == pytest.approx(sm.mean[0])
    # the family's other dimensions are their regression on stature and weight
    filled = sm.conditional_mean({"stature": bodies[0].values["stature"], "weight": bodies[0].values["weight"]})
    assert bodies[0].values["span"] == pytest.approx(filled["span"])


def test_pca_family_on_the_ellipsoid_of_its_components() -> None:
    sm = MODEL.sex("female")
    cases = boundary_points(sm, MODEL.dims, 0.95, components=3)
    assert len(cases) == 6
    r = radius(0.95, 3)
    for c in cases:
        assert sm.mahalanobis(c) == pytest.approx(r)


def test_monte_carlo_is_seeded_mixed_and_moment_matched() -> None:
    a = monte_carlo(MODEL, 200, sex_mix=0.3, seed=7)
    b = monte_carlo(MODEL, 200, sex_mix=0.3, seed=7)
    c = monte_carlo(MODEL, 200, sex_mix=0.3, seed=8)
    assert [x.values for x in a] == [x.values for x in b]
    assert [x.values for x in a] != [x.values for x in c]
    assert sum(x.sex == "female" for x in a) == 60
    assert [x.index for x in a] == list(range(200))
    for sex in ("female", "male"):
        sm = MODEL.sex(sex)
        x = np.array([[v.values[d] for d in sm.dims] for v in a if v.sex == sex])
        assert np.allclose(x.mean(axis=0), sm.mean, rtol=1e-12)
        assert np.allclose(np.cov(x, rowvar=False), sm.cov, rtol=1e-9, atol=1e-12)


def test_bad_population_requests() -> None:
    with pytest.raises(AnthropometryError):
        radius(1.0, 2)
    with pytest.raises(AnthropometryError):
        monte_carlo(MODEL, 0)
    with pytest.raises(AnthropometryError):
        monte_carlo(MODEL, 10, sex_mix=1.5)
