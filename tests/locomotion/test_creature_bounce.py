"""Bouncing polyhedra (Sims Ch. 12): a cube dropped on a slope bounces and comes to rest; its
energy never rises with bounciness < 1."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from jackpy.locomotion.bounce import cube, drop
from jackpy.locomotion.rigid_body import RigidBody, point_mass_inertia
from jackpy.locomotion.terrain import Terrain

SLOPE = np.radians(15.0)


def _slope() -> Terrain:
    return Terrain.from_function(lambda x, z: np.tan(SLOPE) * z, (-4.0, 4.0), (-6.0, 4.0), 0.25)


@pytest.mark.parametrize("b,seconds", [(0.5, 3.5), (0.8, 1.5)])
def test_energy_never_rises(b, seconds):
    r = drop(cube(0.2), _slope(), (0.0, 0.8, 0.0), bounciness=b, seconds=seconds,
             R=Rotation.from_rotvec([0.3, 0.2, 0.1]).as_matrix())
    assert r.bounces >= 2
    assert np.diff(r.energy).max() <= 1e-9 * abs(r.energy[0])
    assert r.energy[-1] < r.energy[0] - 1.0


def test_cube_on_a_slope_bounces_and_comes_to_rest():
    T = _slope()
    r = drop(cube(0.2), T, (0.0, 0.8, 0.0), bounciness=0.5, seconds=3.5,
             R=Rotation.from_rotvec([0.3, 0.2, 0.1]).as_matrix())
    assert r.bounces >= 2
    assert r.rest_time is not None and r.rest_time < 3.5
    p = r.positions[-1]
    assert np.allclose(r.positions[-5:], p)  # held still
    # resting on the slope: the centre about half an edge above the surface (face down, within a
    # tilt), and nothing below it
    gap = (p[1] - T.height(p[0], p[2])) * np.cos(SLOPE)
    assert 0.09 < gap < 0.15
    frames = [e.frame for e in r.events.of("bounce")]
    assert frames == sorted(frames)


def test_rigid_body_free_flight():
    """Free fall is exact; a torque-free body keeps its angular momentum (full tensor)."""
    pts = np.array([[0.3, 0, 0], [-0.3, 0, 0], [0, 0.1, 0], [0, -0.1, 0], [0, 0, 0.05], [0, 0, -0.05]])
    I = point_mass_inertia(np.ones(6), pts)
    body = RigidBody(6.0, I, (0, 2, 0), omega=(1.0, 2.0, 0.5))
    L0 = body.L.copy()
    for _ in range(240):
        body.step(1 / 240)
        assert np.allclose(body.world_inertia() @ body.omega, L0, atol=1e-12)
    assert body.P[1] == pytest.approx(2 - 0.5 * 9.81, abs=1e-12)
    n = np.array([1.0, 2.0, -0.5]) / np.linalg.norm([1.0, 2.0, -0.5])
    assert n @ I @ n == pytest.approx(sum(np.linalg.norm(np.cross(n, p)) ** 2 for p in pts))


def test_forces_through_the_com_do_not_turn_the_body():
    body = RigidBody(2.0, np.diag([0.1, 0.2, 0.3]), (0, 1, 0))
    body.step(0.01, [(np.array([1.0, 30.0, 0.0]), body.P.copy())])
    assert np.allclose(body.omega, 0.0)
    body.step(0.01, [(np.array([0.0, 1.0, 0.0]), body.P + [0.5, 0, 0])])
    assert body.omega[2] > 0  # L x F = x x y = +z (errata 5: tau = L x F)
