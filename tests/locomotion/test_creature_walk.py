"""Acceptance: each shipped creature walks 5 m over each shipped terrain (issue 14)."""

from __future__ import annotations

import numpy as np
import pytest

from creature_cases import NAMES, TERRAINS, shipped_walk, terrain

CASES = [(n, t) for n in NAMES for t in TERRAINS]


def _stance_runs(stance: np.ndarray):
    """(leg, first frame, last frame) of every stance interval."""
    n, m = stance.shape
    for k in range(m):
        i = 0
        while i < n:
            if stance[i, k]:
                j = i
                while j + 1 < n and stance[j + 1, k]:
                    j += 1
                yield k, i, j
                i = j + 1
            else:
                i += 1


@pytest.mark.parametrize("name,terrain_name", CASES)
def test_reaches_the_goal(name, terrain_name):
    r = shipped_walk(name, terrain_name)
    start = r.body_xz(0)
    assert np.hypot(*(r.goal - start)) == pytest.approx(5.0)
    assert np.hypot(*(r.body_xz(-1) - r.goal)) < 0.20


@pytest.mark.parametrize("name,terrain_name", CASES)
def test_stance_feet_on_the_terrain_and_still(name, terrain_name):
    r = shipped_walk(name, terrain_name)
    T = terrain(terrain_name)
    feet, st = r.feet, r.stance
    gap = np.abs(feet[..., 1] - T.height(feet[..., 0], feet[..., 2]))
    assert gap[st].max() < 0.005
    runs = list(_stance_runs(st))
    assert len(runs) > 5 * len(r.legs)  # every foot stepped many times
    for k, i, j in runs:
        moved = np.linalg.norm(feet[i:j + 1, k] - feet[i, k], axis=1).max()
        assert moved < 0.005, (k, i, j, moved)


@pytest.mark.parametrize("name,terrain_name", CASES)
def test_no_foot_lands_in_a_forbidden_zone(name, terrain_name):
    r = shipped_walk(name, terrain_name)
    T = terrain(terrain_name)
    steps = r.events.of("footstep")
    assert steps
    for e in steps:
        assert not T.is_forbidden(e.location[0], e.location[2]), e
    st = r.stance
    assert not np.any(T.is_forbidden(r.feet[..., 0][st], r.feet[..., 2][st]))
    if terrain_name == "steps":  # the banks were really in the way: some footholds were moved back
        moved = [l for l in r.landings if np.linalg.norm(l.foothold - l.desired) > 1e-9]
        assert moved and all(T.is_forbidden(l.desired[0], l.desired[2]) for l in moved)


@pytest.mark.parametrize("name,terrain_name", CASES)
def test_body_never_penetrates_the_terrain(name, terrain_name):
    r = shipped_walk(name, terrain_name)
    T = terrain(terrain_name)
    fig = r.figure
    seg = fig.segments[fig.root_segment()]
    verts = seg.psurf.posed_mesh().vertices
    for p in r.postures[::3]:
        w = (p.location[:3, :3] @ verts.T).T + p.location[:3, 3]
        assert np.min(w[:, 1] - T.height(w[:, 0], w[:, 2])) > 0.0
    assert r.body_clearance.min() > 0.0


@pytest.mark.parametrize("name,terrain_name", CASES)
def test_stance_feet_are_the_gait_schedules(name, terrain_name):
    r = shipped_walk(name, terrain_name)
    T = terrain(terrain_name)
    g = r.gait
    for i, t in enumerate(r.times):
        phase = (t / g.cycle) % 1.0
        expected = ((phase - g.down) % 1.0) < ((g.up - g.down) % 1.0)
        assert np.array_equal(r.stance[i], expected)
    mid = (r.swing_u > 0.2) & (r.swing_u < 0.8) & ~r.stance
    assert mid.any()
    lift = r.feet[..., 1] - T.height(r.feet[..., 0], r.feet[..., 2])
    assert lift[mid].min() > 0.005  # swing feet are off the ground


@pytest.mark.parametrize("name,terrain_name", CASES)
def test_leg_ik_error_is_small(name, terrain_name):
    r = shipped_walk(name, terrain_name)
    assert r.ik_error.max() < 1e-3


def test_the_static_hexapod_figure_walks_with_a_shorter_stride():
    """``figures/hexapod.fig`` (hips turn only 25 degrees) walks with a shorter stride and no other
    change: any N-legged Peabody figure, legs from its graph."""
    from creature_cases import ROOT

    from jackpy.locomotion.config import WalkConfig
    from jackpy.locomotion.creature_walk import walk
    from jackpy.locomotion.terrain import Terrain
    from jackpy.peabody.reader import load

    fig = load(ROOT / "figures" / "hexapod.fig").figures["hexapod"]
    r = walk(fig, Terrain.flat(6.0, 0.25), (0.0, 1.0), config=WalkConfig(fps=10.0, speed=0.1, cycle_time=0.7))
    assert np.hypot(*(r.body_xz(-1) - r.goal)) < 0.2
    assert np.abs(r.feet[..., 1])[r.stance].max() < 0.005
    assert r.ik_error.max() < 1e-3
