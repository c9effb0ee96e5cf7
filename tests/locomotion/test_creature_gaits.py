"""Gaits (Sims 9.2, 10.3): the automatic assignment reproduces the thesis's cases."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.locomotion.config import WalkConfig
from jackpy.locomotion.gaits import assign
from jackpy.locomotion.legs import Leg


def _legs(per_side: int, skip: tuple[int, int] | None = None) -> list[Leg]:
    legs = []
    for side in (1, -1):
        k = 0
        for i in range(per_side):
            if skip == (side, i):
                continue
            legs.append(Leg(f"{side}{i}", [], ("s", "f"), np.array([0.1 * side, 0, -0.2 * i]), np.zeros(3), side, k))
            k += 1
    return legs


def _down(gait, legs):
    return {g.name: float(gait.down[i]) for i, g in enumerate(legs)}


C = WalkConfig()


@pytest.mark.parametrize("n,gait,expected", [
    (1, "trot", {"10": 0.0, "-10": 0.5}),  # biped walk
    (1, "wave", {"10": 0.0, "-10": 0.0}),  # biped hop
    (2, "trot", {"10": 0.0, "11": 0.5, "-10": 0.5, "-11": 0.0}),  # quadruped trot: diagonal pairs
    (2, "wave", {"10": 0.5, "11": 0.0, "-10": 0.5, "-11": 0.0}),  # bound: fronts together, hinds together
    (3, "tripod", {"10": 0.0, "11": 0.5, "12": 0.0, "-10": 0.5, "-11": 0.0, "-12": 0.5}),
    (3, "wave", {"10": 2 / 3, "11": 1 / 3, "12": 0.0, "-10": 2 / 3, "-11": 1 / 3, "-12": 0.0}),  # back to front
])
def test_automatic_assignment(n, gait, expected):
    legs = _legs(n)
    assert _down(assign(legs, gait, C), legs) == pytest.approx(expected)


def test_auto_is_trot_up_to_four_legs_and_wave_beyond():
    assert assign(_legs(2), "auto", C).name == "trot"
    assert assign(_legs(3), "auto", C).name == "wave"
    assert assign(_legs(4), "pronk", C).down.tolist() == [0.0] * 8


def test_missing_leg_leaves_the_other_side_unchanged():
    full, lame = _legs(3), _legs(3, skip=(-1, 1))
    a, b = _down(assign(full, "wave", C), full), _down(assign(lame, "wave", C), lame)
    assert all(a[k] == b[k] for k in ("10", "11", "12"))


def test_cycle_time_scales_durations_not_fractions():
    legs = _legs(3)
    g1, g2 = assign(legs, "wave", C), assign(legs, "wave", C.with_(cycle_time=2.0))
    assert np.array_equal(g1.down, g2.down) and np.array_equal(g1.up, g2.up)
    for t in np.linspace(0, 3, 37):
        assert np.array_equal(g1.in_stance(t), g2.in_stance(2 * t))


@pytest.mark.parametrize("n,gait,duty", [(1, "trot", 0.5), (2, "trot", 0.6), (3, "trot", 0.5), (3, "wave", 1 / 3 + 1e-9),
                                         (4, "wave", 0.25 + 1e-9)])
def test_walking_always_has_a_foot_down(n, gait, duty):
    legs = _legs(n)
    g = assign(legs, gait, C.with_(duty_trot=duty, duty_wave=duty))
    assert all(g.in_stance(t).any() for t in np.linspace(0, 2, 401))


def test_biped_wave_is_a_hop_with_flight():
    legs = _legs(1)
    g = assign(legs, "wave", C.with_(duty_wave=0.6))
    assert any(not g.in_stance(t).any() for t in np.linspace(0, 1, 101))


def test_next_down_and_last_up():
    legs = _legs(2)
    g = assign(legs, "trot", C)
    for k in range(4):
        for t in np.linspace(0, 2, 23):
            td, tu = g.next_down(k, t), g.last_up(k, t)
            assert t <= td < t + g.cycle and t - g.cycle < tu <= t
            assert (td / g.cycle) % 1 == pytest.approx(g.down[k] % 1, abs=1e-9) or abs((td / g.cycle) % 1 - 1) < 1e-9
