"""Pronking (Sims Ch. 11): the quadruped pronks 3 m over rolling hills."""

from __future__ import annotations

import functools

import numpy as np

from creature_cases import creature, terrain
from jackpy.locomotion.config import PronkConfig
from jackpy.locomotion.pronk import FLIGHT, landing_speed_bound, pronk


@functools.lru_cache(maxsize=None)
def _pronk():
    return pronk(creature("quadruped"), terrain("rolling_hills"), (0.0, 3.0), config=PronkConfig(fps=15.0))


def test_pronks_three_metres_over_rolling_hills():
    r = _pronk()
    assert r.hops >= 8
    assert np.hypot(*(r.body_xz(-1) - r.goal)) < 0.2
    assert r.ik_error.max() < 1e-3


def test_flight_has_every_foot_off_the_ground():
    r = _pronk()
    T = r.terrain
    lift = r.feet[..., 1] - T.height(r.feet[..., 0], r.feet[..., 2])
    flight = np.array([p == FLIGHT for p in r.phase])
    # a foot that has not touched down yet is above the terrain; on uneven ground some feet touch
    # down before the others (the flight ends when all have)
    airborne = flight[:, None] & ~r.contact
    airborne[0] = False
    assert lift[airborne].min() > 0.0
    # and every flight phase has frames with every foot off the ground
    runs, cur = [], []
    for i, f in enumerate(flight):
        if f:
            cur.append(i)
        elif cur:
            runs.append(cur)
            cur = []
    assert len(runs) >= r.hops - 1
    for run in runs:
        assert any((~r.contact[i]).all() and lift[i].min() > 0.0 for i in run)


def test_landing_speed_is_bounded():
    r = _pronk()
    assert len(r.touchdown_speeds) >= r.hops - 1
    assert max(r.touchdown_speeds) <= landing_speed_bound(r.config)


def test_angular_momentum_is_conserved_in_flight():
    r = _pronk()
    runs, cur = [], []
    for step in r.steps:
        if step[1] == FLIGHT:
            cur.append(step)
        elif cur:
            runs.append(cur)
            cur = []
    assert len(runs) >= r.hops - 1
    for run in runs:
        # L = R I R^T omega from the recorded orientation and angular velocity
        Ls = [R @ r.inertia @ R.T @ w for _, _, _, _, _, R, w in run]
        assert np.allclose(Ls, Ls[0], atol=1e-12)


def test_phases_follow_the_event_rules():
    r = _pronk()
    order = {"pushing": "flight", "flight": "landing", "landing": "pushing"}
    prev = r.steps[0][1]
    for _, ph, *_ in r.steps[1:]:
        if ph != prev and ph != "standing":
            assert order[prev] == ph
        prev = ph
    landings = r.events.of("landing")
    feet = r.events.of("footstep")
    assert len(feet) >= len(r.legs) * len(landings)
