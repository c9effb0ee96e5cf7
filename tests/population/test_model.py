"""The multivariate population model reproduces the ANSUR II tables and regresses like a normal model."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.body import ansur2
from jackpy.body.anthropometry import AnthropometryError
from jackpy.population.model import DEFAULT_DIMENSIONS, PopulationModel


def test_model_holds_the_ansur2_statistics() -> None:
    model = PopulationModel.ansur2()
    assert model.dims == DEFAULT_DIMENSIONS
    for sex in ("female", "male"):
        sm = model.sex(sex)
        for k, d in enumerate(sm.dims):
            assert sm.mean[k] == ansur2.stats(sex, d).mean and sm.sd[k] == ansur2.stats(sex, d).sd
        assert np.allclose(sm.corr, ansur2.correlations(sex, sm.dims))
        assert np.linalg.eigvalsh(sm.cov).min() > 0


def test_conditional_mean_is_the_regression_on_the_given_dimensions() -> None:
    sm = PopulationModel.ansur2().sex("male")
    i, j = sm.index("stature"), sm.index("span")
    tall = sm.mean[i] + 2 * sm.sd[i]
    filled = sm.conditional_mean({"stature": tall})
    assert filled["stature"] == tall
    # one given dimension: E[span | stature] = mean + r * sd_span * z
    assert filled["span"] == pytest.approx(sm.mean[j] + sm.corr[i, j] * sm.sd[j] * 2.0)
    assert sm.conditional_mean({}) == dict(zip(sm.dims, sm.mean))


def test_principal_axes_and_mahalanobis() -> None:
    sm = PopulationModel.ansur2().sex("female")
    w, v = sm.principal_axes()
    assert np.all(np.diff(w) <= 0) and np.allclose(v.T @ v, np.eye(len(w)))
    assert np.all(v[:, 0] > 0)  # the first component is overall size
    point = dict(zip(sm.dims, sm.mean + sm.sd * np.eye(len(sm.dims))[0]))
    assert sm.mahalanobis(point, ["stature"]) == pytest.approx(1.0)


def test_bad_dimensions_are_refused() -> None:
    with pytest.raises(AnthropometryError):
        PopulationModel.ansur2(("stature", "stature"))
    with pytest.raises(AnthropometryError):
        PopulationModel.ansur2(("stature", "shoe_size"))
    with pytest.raises(AnthropometryError):
        PopulationModel.ansur2().sex("male").index("neck_length")
