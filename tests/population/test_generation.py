"""Generated bodies reproduce the model, measured FROM the figures (jackpy.body.measure: surfaces
and sites by forward kinematics), not from the tables.

The acceptance check is over 5,000 Monte Carlo bodies with full figures (surfaces and masses). That
takes about 10 core-minutes, so by default this test measures 400 bodies (the population is
moment-matched, so the model's means, SDs and correlations are the sample's exactly and any
difference is the figures'); set JACKPY_POPULATION_BODIES=5000 to run the full check.
"""

from __future__ import annotations

import os
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

from jackpy.population.families import monte_carlo
from jackpy.population.generate import CONTROLLED, Body, make_figure, measure_controlled
from jackpy.population.model import PopulationModel

N = int(os.environ.get("JACKPY_POPULATION_BODIES", "400"))


def _measure(body: dict) -> list[float]:
    return measure_controlled(make_figure(Body.from_dict(body))).tolist()


@pytest.mark.timeout(3600)
def test_monte_carlo_bodies_measured_from_their_figures_reproduce_the_model() -> None:
    model = PopulationModel.ansur2(CONTROLLED)
    bodies = monte_carlo(model, N, sex_mix=0.5, seed=2026)
    with ProcessPoolExecutor(max_workers=min(os.cpu_count() or 1, 16)) as pool:
        measured = np.array(list(pool.map(_measure, [b.to_dict() for b in bodies], chunksize=8)))
    for sex in ("female", "male"):
        sm = model.sex(sex)
        m = measured[[b.sex == sex for b in bodies]]
        assert np.all(np.abs(m.mean(axis=0) / sm.mean - 1) < 0.01), (sex, m.mean(axis=0), sm.mean)
        assert np.all(np.abs(m.std(axis=0, ddof=1) / sm.sd - 1) < 0.01), (sex, m.std(axis=0, ddof=1), sm.sd)
        assert np.all(np.abs(np.corrcoef(m, rowvar=False) - sm.corr) < 0.03), (sex, np.corrcoef(m, rowvar=False) - sm.corr)


@pytest.mark.timeout(900)
def test_a_body_measures_what_it_asks_for() -> None:
    model = PopulationModel.ansur2(CONTROLLED)
    sm = model.sex("female")
    body = monte_carlo(model, 40, sex_mix=1.0, seed=3)[0]
    m = measure_controlled(make_figure(body))
    target = np.array([body.values[k] for k in CONTROLLED])
    assert np.all(np.abs(m - target) < 0.05 * sm.sd), (m - target) / sm.sd
