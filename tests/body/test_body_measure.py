"""Acceptance: dimensions measured FROM generated figures (FK of surfaces and sites, survey postures)
against ANSUR II values derived from the public data (the shipped summary + correlation tables of
``jackpy.body.ansur2``, not the population file the figure is built from).

A figure "at percentile P" has stature and weight at P; every other dimension is the regression on
both, so the expectation for a dimension d is ANSUR II's conditional mean
``mean_d + sd_d (beta_s z_s + beta_w z_w)`` from the tables' means, SDs and correlations."""

from statistics import NormalDist

import numpy as np
import pytest

from jackpy.body import ansur2
from jackpy.body.human import make_human
from jackpy.body.measure import MEASURES, measure, measure_all
from jackpy.errors import FigureError

#: measure name -> ANSUR II key dimension; eye height standing is checked against stature minus the
#: head above the eyes measured sitting (ANSUR II has no standing eye height)
KEYS = {"sitting_height": "sitting_height", "eye_height_sitting": "eye_height_sitting",
        "acromial_height": "acromial_height", "knee_height_sitting": "knee_height_sitting",
        "buttock_knee_length": "buttock_knee_length", "hip_breadth_sitting": "hip_breadth_sitting",
        "chest_breadth": "chest_breadth", "bideltoid_breadth": "bideltoid_breadth", "arm_span": "span",
        "hand_length": "hand_length", "foot_length": "foot_length"}
TOLERANCE = {"hand_length": 0.010, "foot_length": 0.010}


def _z_weight(sex: str, p: float) -> float:
    """z of the lognormal weight quantile at p within the sample's mean and SD."""
    w = ansur2.stats(sex, "weight")
    s2 = np.log1p((w.sd / w.mean) ** 2)
    value = np.exp(np.log(w.mean) - s2 / 2 + NormalDist().inv_cdf(p / 100) * np.sqrt(s2))
    return (value - w.mean) / w.sd


def expected(sex: str, key: str, p: float) -> float:
    zs, zw = NormalDist().inv_cdf(p / 100), _z_weight(sex, p)
    r = ansur2.correlations(sex, [key, "stature", "weight"])
    rds, rdw, rsw = r[0, 1], r[0, 2], r[1, 2]
    bs = (rds - rdw * rsw) / (1 - rsw ** 2)
    bw = (rdw - rds * rsw) / (1 - rsw ** 2)
    st = ansur2.stats(sex, key)
    return st.mean + st.sd * (bs * zs + bw * zw)


@pytest.fixture(scope="module", params=[(s, p) for s in ("male", "female") for p in (5, 50, 95)],
                ids=lambda sp: f"{sp[0]}-p{sp[1]}")
def measured(request):
    sex, p = request.param
    fig = make_human(sex, p, footwear="barefoot")
    return sex, p, fig, measure_all(fig)


def test_stature_within_one_percent(measured):
    sex, p, _, m = measured
    st = ansur2.stats(sex, "stature")
    want = st.mean + st.sd * NormalDist().inv_cdf(p / 100)
    assert abs(m["stature"] - want) <= 0.01 * want


def test_weight_is_the_lognormal_quantile(measured):
    sex, p, _, m = measured
    w = ansur2.stats(sex, "weight")
    assert m["weight"] == pytest.approx(w.mean + w.sd * _z_weight(sex, p), rel=1e-3)


@pytest.mark.parametrize("name", list(KEYS))
def test_dimension_against_ansur2(measured, name):
    sex, p, _, m = measured
    want = expected(sex, KEYS[name], p)
    tol = TOLERANCE.get(name, 0.020)
    assert abs(m[name] - want) <= tol, f"{name}: measured {m[name] * 1000:.1f} mm, ANSUR II {want * 1000:.1f} mm"


def test_eye_height_standing(measured):
    sex, p, _, m = measured
    head_above_eye = expected(sex, "sitting_height", p) - expected(sex, "eye_height_sitting", p)
    st = ansur2.stats(sex, "stature")
    want = st.mean + st.sd * NormalDist().inv_cdf(p / 100) - head_above_eye
    assert abs(m["eye_height_standing"] - want) <= 0.020


def test_measuring_keeps_the_posture(male50):
    q, loc = male50.q, male50.location.copy()
    measure(male50, "sitting_height")
    assert np.array_equal(male50.q, q) and np.array_equal(male50.location, loc)


def test_shoe_is_longer_than_the_foot():
    shod, bare = make_human("female", 50), make_human("female", 50, footwear="barefoot")
    extra = measure(shod, "foot_length") - measure(bare, "foot_length")
    assert 0.015 <= extra <= 0.020
    assert shod.segment("left_foot").attribute != bare.segment("left_foot").attribute


def test_unknown_measure_is_an_error(male50):
    with pytest.raises(FigureError, match="unknown measure"):
        measure(male50, "inseam")
    assert "weight" in MEASURES
