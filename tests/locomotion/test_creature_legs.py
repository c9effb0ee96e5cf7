"""Legs of any N-legged figure from its graph, and leg IK with Sims' full-extension fallback."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from creature_cases import creature
from jackpy.errors import FigureError
from jackpy.locomotion.legs import LegSolver, find_legs, full_extension_solve
from jackpy.peabody.reader import load

ROOT = Path(__file__).resolve().parents[2]


def test_the_static_hexapod_figure_has_six_legs():
    fig = load(ROOT / "figures" / "hexapod.fig").figures["hexapod"]
    legs = find_legs(fig)
    assert [g.name for g in legs] == ["shin_l1", "shin_l2", "shin_l3", "shin_r1", "shin_r2", "shin_r3"]
    assert [g.side for g in legs] == [1, 1, 1, -1, -1, -1] and [g.order for g in legs] == [0, 1, 2] * 2
    assert legs[0].joints == ["hip_l1", "knee_l1"] and legs[0].foot == ("shin_l1", "foot")
    assert np.allclose(legs[0].hip_body, [0.15, 0.0, 0.22])


@pytest.mark.parametrize("name,n", [("hexapod", 6), ("quadruped", 4), ("biped", 2)])
def test_shipped_creatures_legs_skip_head_and_tail(name, n):
    legs = find_legs(creature(name))
    assert len(legs) == n
    assert all(g.full_length > np.linalg.norm(g.neutral_body - g.hip_body) for g in legs)


def test_named_legs_and_no_legs():
    fig = creature("quadruped")
    assert [g.name for g in find_legs(fig, ["leg_l1_2"])] == ["leg_l1_2"]
    with pytest.raises(FigureError):
        find_legs(fig, ["leg_l1_1"])  # not a leaf: no leg ends there
    chair = load(ROOT / "figures" / "chair.fig")  # one rigid segment
    with pytest.raises(FigureError):
        find_legs(next(iter(chair.figures.values())))


def test_leg_solver_reaches_targets():
    fig = creature("hexapod")
    legs = find_legs(fig)
    solver = LegSolver(fig, legs)
    targets = [(fig.location @ np.append(g.neutral_body + [0, 0.03, 0.05], 1))[:3] for g in legs]
    assert solver.solve(targets).max() < 1e-4


@pytest.mark.parametrize("fraction", [0.98, 0.999, 1.0, 1.2])
def test_full_extension_fallback(fraction):
    fig = creature("hexapod")
    leg = find_legs(fig)[0]
    hip = (fig.location @ np.append(leg.hip_body, 1))[:3]
    d = leg.neutral_body - leg.hip_body
    goal = hip + d / np.linalg.norm(d) * leg.full_length * fraction
    q = full_extension_solve(fig, leg, goal, fig.q)
    assert np.all(np.isfinite(q))
    fig.q = q
    foot = fig.site_world(*leg.foot)[:3, 3]
    if fraction <= 1.0:
        assert np.linalg.norm(foot - goal) < 1e-3 * leg.full_length
    else:  # unreachable: as far as it goes, towards the goal
        assert np.linalg.norm(foot - hip) == pytest.approx(leg.full_length, rel=1e-3)
        assert np.dot((foot - hip) / leg.full_length, d / np.linalg.norm(d)) > 0.99
