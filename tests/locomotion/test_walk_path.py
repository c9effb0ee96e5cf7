"""Curved-path walking and footsteps from a path (issue 13)."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.locomotion import footsteps, walk_path
from jackpy.locomotion.walk_gait import rot_y
from tests.locomotion.walk_cases import FPS, S_END_HEADING, baked, figure_and_params


def _yaw_of(fig) -> float:
    """Heading of the feet (mean heel-to-toe direction, top view)."""
    fwd = sum(fig.site_world(f"{s}_foot", "toe")[:3, 3] - fig.site_world(f"{s}_foot", "heel")[:3, 3]
              for s in ("left", "right"))
    return float(np.arctan2(fwd[0], fwd[2]))


@pytest.mark.parametrize("kind,goal,heading", [("quarter", (2.0, 2.0), np.pi / 2), ("s-curve", (0.0, 6.0), None)])
def test_curves_turn_at_most_45_per_step_and_end_at_the_goal(kind, goal, heading):
    fig, p, steps, postures, targets = baked("male:50", kind)
    for a, b in zip(steps[1:], steps[2:]):
        assert abs((b.psi - a.psi + np.pi) % (2 * np.pi) - np.pi) <= np.radians(45.0) + 1e-9
    if heading is None:  # the S-curve ends at its last point, facing along its end tangent
        heading = S_END_HEADING
    postures[-1].apply_to(fig)
    c = fig.site_world("pelvis", "centre")[:3, 3]
    assert np.hypot(c[0] - goal[0], c[2] - goal[1]) < 0.05
    assert abs((_yaw_of(fig) - heading + np.pi) % (2 * np.pi) - np.pi) < np.radians(5.0)
    # the figure stands with its feet together at the end
    feet = [fig.site_world(f"{s}_foot", "heel")[:3, 3] for s in ("left", "right")]
    assert abs(np.linalg.norm(feet[0] - feet[1]) - 2 * p.foot.width) < 0.02


def test_straight_path_is_the_straight_walk_in_any_direction():
    """The 2-D layer on a straight path: the walk along heading psi from (x0, z0) is the walk along
    +z from the origin, rotated and moved (targets and centre line, to 1e-9 m)."""
    _, p = figure_and_params("male:50")
    base = walk_path.Walk(footsteps.straight(p, 2.5), p)
    psi, origin = 0.7, np.array([1.2, -0.4])
    moved = walk_path.Walk(footsteps.straight(p, 2.5, *origin, psi), p)
    M = np.eye(4)
    M[:3, :3] = rot_y(psi)
    M[:3, 3] = [origin[0], 0.0, origin[1]]
    assert base.duration == moved.duration
    for t in np.arange(0.0, base.duration, 1.0 / FPS):
        a, b = base.at(t), moved.at(t)
        assert np.allclose(M @ a.pelvis, b.pelvis, atol=1e-9)
        for s in ("left", "right"):
            assert a.phase[s] == b.phase[s]
            assert np.allclose(M @ a.feet[s], b.feet[s], atol=1e-9)


def test_straight_swing_bezier_is_the_straight_travel():
    """D1, D2, D3 collinear: a swing between two footsteps on one walking line keeps the ankle on
    that line (book §5.2.3), in any direction."""
    _, p = figure_and_params("male:50")
    psi = 0.4
    w = walk_path.Walk(footsteps.straight(p, 3.0, psi=psi), p)
    lat = np.array([np.cos(psi), -np.sin(psi)])
    steady = 0
    for t in np.arange(0.0, w.duration, 0.01):
        tg = w.at(t)
        for s in ("left", "right"):
            if tg.phase[s] != "swing":
                continue
            idx = w.by_side[s]
            nxt = next(j for j in idx if w.land[j] > t)
            prev = max(j for j in idx if j < nxt)
            line = float(np.dot(w.steps[prev].point, lat))
            if abs(float(np.dot(w.steps[nxt].point, lat)) - line) > 1e-12:
                continue  # the first and last steps change the base width
            ankle = tg.feet[s][:3, :3] @ p.foot.ankle + tg.feet[s][:3, 3]
            assert abs(float(np.dot(ankle[[0, 2]], lat)) - line) < 1e-9
            steady += 1
    assert steady > 50


def test_footsteps_alternate_and_keep_spacing():
    _, p = figure_and_params("female:5")
    steps = footsteps.from_path(p, [(0.0, 0.0), (1.0, 1.0), (2.0, 0.5)])
    for a, b in zip(steps[1:], steps[2:]):
        assert a.side != b.side
    # start and end standing: feet side by side, spaced twice the foot offset
    for a, b in ((steps[0], steps[1]), (steps[-2], steps[-1])):
        assert abs(np.hypot(a.x - b.x, a.z - b.z) - 2 * p.foot.width) < 1e-9
        assert a.psi == pytest.approx(b.psi)
    # no step longer than a stride
    for j in range(2, len(steps)):
        prev = max(k for k in range(j) if steps[k].side == steps[j].side)
        assert np.hypot(steps[j].x - steps[prev].x, steps[j].z - steps[prev].z) <= 2 * p.step_length + 1e-9


def test_turn_in_place_steps_at_most_45():
    _, p = figure_and_params("male:50")
    steps = footsteps.turn_in_place(p, (0.0, 0.0), 0.0, np.radians(120.0))
    assert steps[-1].psi == pytest.approx(np.radians(120.0))
    for a, b in zip(steps[1:], steps[2:]):
        assert abs(b.psi - a.psi) <= np.radians(45.0) + 1e-9


def test_banking_leans_into_the_turn_by_eq_5_13():
    """φ = arctan(κ v²/g): on the quarter circle (r = 2 m, a left turn) the centre site moves
    toward the centre by H·tan φ against the unbanked walk; on a straight path φ = 0."""
    import dataclasses

    from jackpy.locomotion.walk_gait import GRAVITY

    _, p = figure_and_params("male:50")
    a = np.linspace(0.0, np.pi / 2, 9)
    steps = footsteps.from_path(p, np.column_stack([2.0 - 2.0 * np.cos(a), 2.0 * np.sin(a)]), facing=np.pi / 2)
    banked, flat = walk_path.Walk(steps, p), walk_path.Walk(steps, dataclasses.replace(p, banking=False))
    centre = np.array([2.0, 0.0])
    for j in range(4, len(steps) - 3):  # the steady turning steps
        t, dt = 0.5 * (banked.land[j - 1] + banked.land[j]), 0.01
        c0 = flat.at(t).pelvis[[0, 2], 3]
        v = np.linalg.norm(flat.at(t + dt).pelvis[[0, 2], 3] - flat.at(t - dt).pelvis[[0, 2], 3]) / (2 * dt)
        r = np.linalg.norm(c0 - centre)
        shift = banked.at(t).pelvis[[0, 2], 3] - c0
        inward = float(np.dot(shift, (centre - c0) / r))
        assert inward > 0.0 and np.linalg.norm(shift) == pytest.approx(inward, rel=0.05)
        phi = np.arctan(inward / p.hip_height)
        assert phi == pytest.approx(np.arctan(v * v / (GRAVITY * r)), rel=0.3)
    straight = walk_path.Walk(footsteps.straight(p, 3.0), p)
    assert all(straight.bank(t) == 0.0 for t in np.arange(0.0, straight.duration, 0.05))
