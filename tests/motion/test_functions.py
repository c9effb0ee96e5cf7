"""Weight and velocity functions (behaviors.md §4.2-4.3; §7 items 14-15)."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.motion.functions import (VELOCITY_FUNCTIONS, WEIGHT_FUNCTIONS, normalised_time, progress, velocity,
                                     weight_factor)

U = np.linspace(0.0, 1.0, 101)


def test_weight_functions_at_start_middle_end():
    assert [weight_factor("constant", u) for u in (0, 0.5, 1)] == [1, 1, 1]
    assert [weight_factor("increase", u) for u in (0, 1)] == [0, 1]
    assert [weight_factor("decrease", u) for u in (0, 1)] == [1, 0]
    assert weight_factor("ease", 0) == pytest.approx(0, abs=1e-15)
    assert weight_factor("ease", 0.5) == pytest.approx(1)
    assert weight_factor("ease", 1) == pytest.approx(0, abs=1e-15)
    # increase rises and decrease falls monotonically; ease peaks halfway
    assert np.all(np.diff([weight_factor("increase", u) for u in U]) > 0)
    assert np.all(np.diff([weight_factor("decrease", u) for u in U]) < 0)
    assert int(np.argmax([weight_factor("ease", u) for u in U])) == 50


@pytest.mark.parametrize("name", VELOCITY_FUNCTIONS)
def test_velocity_profiles_go_from_0_to_1_monotonically(name):
    s = np.array([progress(name, u) for u in U])
    assert s[0] == 0 and s[-1] == pytest.approx(1)
    assert np.all(np.diff(s) > 0)
    # progress is the integral of the velocity function
    v = np.array([velocity(name, u) for u in U])
    assert np.trapezoid(v, U) == pytest.approx(1, abs=1e-3)
    assert np.allclose(np.gradient(s, U)[1:-1], v[1:-1], atol=2e-2)


def test_velocity_shapes():
    assert velocity("increase", 0) == 0 and velocity("increase", 1) > velocity("increase", 0.5)
    assert velocity("decrease", 1) == 0 and velocity("decrease", 0) > velocity("decrease", 0.5)
    assert velocity("ease", 0) == 0 and velocity("ease", 1) == pytest.approx(0, abs=1e-15)
    assert int(np.argmax([velocity("ease", u) for u in U])) == 50
    assert progress("increase", 0.5) == 0.25 and progress("decrease", 0.5) == 0.75
    assert progress("ease", 0.5) == pytest.approx(0.5)


def test_unknown_names_and_normalised_time():
    with pytest.raises(ValueError, match="weight function"):
        weight_factor("bounce", 0.5)
    with pytest.raises(ValueError, match="velocity function"):
        progress("bounce", 0.5)
    assert normalised_time(1.5, 1.0, 2.0) == 0.5
    assert normalised_time(0.0, 1.0, 2.0) == 0.0 and normalised_time(3.0, 1.0, 2.0) == 1.0
    assert normalised_time(1.0, 1.0, 1.0) == 1.0
    assert set(WEIGHT_FUNCTIONS) == {"constant", "increase", "decrease", "ease"}
