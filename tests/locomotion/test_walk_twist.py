"""The swing foot's twist decay (issue 13; [SH5] eq. 5.16): the swing foot turns from its toe-off
heading to its heel-strike heading along the book's parabola, most of it early in the swing."""

from __future__ import annotations

import numpy as np

from jackpy.locomotion import footsteps, walk_path
from jackpy.locomotion.walk_gait import DOUBLE_SUPPORT
from walk_cases import figure_and_params


def _yaw(T: np.ndarray) -> float:
    return float(np.arctan2(T[0, 2], T[2, 2]))


def test_swing_twist_decays_as_the_parabola_on_a_turn():
    _, p = figure_and_params("male:50")
    a = np.linspace(0.0, np.pi / 2, 9)
    steps = footsteps.from_path(p, np.column_stack([2.0 - 2.0 * np.cos(a), 2.0 * np.sin(a)]), facing=np.pi / 2)
    walk = walk_path.Walk(steps, p)
    checked = 0
    for j in range(4, len(steps) - 2):
        side, prev = steps[j].side, max(k for k in walk.by_side[steps[j].side] if k < j)
        turn = (steps[j].psi - steps[prev].psi + np.pi) % (2 * np.pi) - np.pi
        if abs(turn) < np.radians(3.0):
            continue
        t_s = walk.land[j - 1]
        t_to = t_s + 2.0 * DOUBLE_SUPPORT * (walk.land[j] - t_s)
        for u, left in ((0.25, 0.5625), (0.5, 0.25), (0.75, 0.0625)):
            T = walk.at(t_to + u * (walk.land[j] - t_to)).feet[side]
            rest = (_yaw(T) - steps[j].psi + np.pi) % (2 * np.pi) - np.pi
            assert abs(rest / -turn - left) < 1e-6  # (1 - u)² of the twist is left
        checked += 1
    assert checked >= 3


def test_no_twist_on_a_straight_walk():
    _, p = figure_and_params("female:5")
    steps = footsteps.straight(p, 2.0, psi=0.7)
    walk = walk_path.Walk(steps, p)
    for i in range(int(walk.duration * 10)):
        for T in walk.at(i / 10).feet.values():
            assert abs(_yaw(T) - 0.7) < 1e-9
