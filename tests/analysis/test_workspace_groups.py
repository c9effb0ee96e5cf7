"""Joint groups in the reachable-workspace sampler: group angles sampled within their box and
linear limits, mapped through the (batched) driver; the coupled shoulder changes the arm's workspace."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.analysis.workspace import Chain, reachable_workspace

import jackpy.body.human as body  # noqa: E402  (a broken import fails, never skips)


@pytest.fixture(scope="module")
def human():
    return body.make_human("male", 50)


def _u(chain, n=4000, seed=3):
    return np.random.default_rng(seed).random((n, chain.sample_dims))


def test_arm_chain_samples_the_shoulder_complex_and_forearm_in_group_angles(human):
    chain = Chain.to_site(human, "right_clavicle", "right_palm", "grip")
    assert [s.group.name for s in chain.groups] == ["right_shoulder_complex", "right_forearm"]
    assert chain.sample_dims == len(chain.dofs) - 8 + 3 + 1  # 6 shoulder + 2 twist members -> 3 + 1 angles
    s = chain.sample(_u(chain))
    g = human.groups["right_shoulder_complex"]
    theta = s.angles[g.name]
    assert 0.7 * 4000 < len(theta) < 4000  # the linear cuts reject some of the box
    assert g.feasible_rows(theta).all()
    assert np.all(theta @ g.A.T <= g.b + 1e-12)
    # member values are exactly the single-sample driver's, in the chain's columns
    slot = chain.groups[0]
    for i in range(0, len(theta), 97):
        np.testing.assert_allclose(s.values[i, slot.cols], g.driver(theta[i])[slot.outs], atol=1e-12)
    fore = human.groups["right_forearm"]
    for i in range(0, len(theta), 211):
        np.testing.assert_allclose(s.values[i, chain.groups[1].cols],
                                   fore.driver(s.angles[fore.name][i]), atol=1e-12)
    # and every sampled member value is within the member joints' own limits
    assert np.all(s.values >= chain.lower - 1e-9) and np.all(s.values <= chain.upper + 1e-9)


def test_sampled_points_match_forward_kinematics_through_the_driver(human):
    chain = Chain.to_site(human, "right_clavicle", "right_palm", "grip")
    s = chain.sample(_u(chain, 50))
    pts = chain.points(s.values)
    g = human.groups["right_shoulder_complex"]
    f = human
    q0, a0 = f.q, g.angles.copy()
    try:
        for theta, v, p in zip(s.angles[g.name], s.values, pts):
            q = q0.copy()
            q[chain.dofs] = v
            f.q = q
            g.set_angles(f, theta)  # the single-sample path writes the same member values
            np.testing.assert_allclose(f.site_world("right_palm", "grip")[:3, 3], p, atol=1e-9)
    finally:
        f.q = q0
        g.angles = a0


def test_clavicle_moves_with_the_arm_and_the_coupled_workspace_differs(human):
    coupled = Chain.to_site(human, "right_clavicle", "right_palm", "grip")
    free = Chain.to_site(human, "right_clavicle", "right_palm", "grip", coupled=False)
    assert free.groups == [] and free.sample_dims == len(free.dofs)
    s = coupled.sample(_u(coupled))
    g = human.groups["right_shoulder_complex"]
    phi_c = s.values[:, coupled.groups[0].cols[0]]  # clavicle elevation follows the arm's elevation
    elevation = s.angles[g.name][:, 0]
    assert np.corrcoef(elevation, phi_c)[0, 1] > 0.9 and np.ptp(phi_c) > np.radians(15)
    ws_c = reachable_workspace(coupled, 32)
    ws_f = reachable_workspace(free, 32)
    assert ws_c.converged and ws_f.converged
    differ = np.count_nonzero(ws_c.occupied != ws_f.occupied)
    assert differ > 0.05 * ws_f.occupied.sum()
    assert ws_c.volume() != pytest.approx(ws_f.volume(), rel=0.05)


def test_group_only_partly_in_the_chain_falls_back_to_member_limits(human):
    chain = Chain.to_site(human, "right_shoulder", "right_palm", "grip")  # clavicle outside
    assert [s.group.name for s in chain.groups] == ["right_forearm"]


def test_driver_without_batch_is_evaluated_once_per_unique_grid_sample(human):
    chain = Chain.to_site(human, "l5_s1", "right_palm", "grip")
    slots = {s.group.name: s for s in chain.groups}
    assert not slots["spine"].batched and slots["right_shoulder_complex"].batched
    sampler = chain.sampler(max_driver_calls=64)  # 4 levels per torso angle
    s = sampler(_u(chain, 3000))
    spine = human.groups["spine"]
    assert sampler.driver_calls <= 64
    theta = s.angles["spine"]
    assert len(np.unique(theta, axis=0)) <= 64 and spine.feasible_rows(theta).all()
    for i in range(0, len(theta), 301):
        np.testing.assert_allclose(s.values[i, slots["spine"].cols], spine.driver(theta[i])[slots["spine"].outs],
                                   atol=1e-12)
