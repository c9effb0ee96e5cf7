"""Strength-guided lifting (issue 16, book §5.3): the load effect on the hand path, the added joint,
the strategies, the monitor's ratios against the strength module, work and energy, determinism."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.analysis.statics import Load, joint_torques
from jackpy.analysis.strength import dof_strengths, utilisation
from jackpy.body.human import make_human
from jackpy.body import strength as body_strength
from jackpy.body.strength import strength_table
from jackpy.planning.lifting import (AVAILABLE_TORQUE, PULL_BACK, REDUCING_MOMENT, LiftTask, overhead_task,
                                     strength_guided_lift)
from jackpy.planning.lifting_monitor import LiftingMonitor

LB = 0.45359237


@pytest.fixture(scope="module")
def figure():
    return make_human("male", 50)


@pytest.fixture(scope="module")
def lifts(figure):
    """The book's overhead placement (§5.3.6) with 10, 20 and 30 lb, pe 0.30, cl 0.50."""
    return {lb: strength_guided_lift(figure, overhead_task(figure, lb * LB)) for lb in (10, 20, 30)}


def test_heavier_load_brings_the_hand_closer_to_the_body(lifts) -> None:
    mean = {lb: float(r.horizontal_distance().mean()) for lb, r in lifts.items()}
    assert all(r.reached for r in lifts.values()), {lb: r.reason for lb, r in lifts.items()}
    # measured: 0.32, 0.24, 0.20 m of mean horizontal grip-to-shoulder distance
    assert mean[20] < mean[10] - 0.01, mean
    assert mean[30] < mean[20] - 0.01, mean
    # the light lift stays near the straight line (start and goal are 30 cm in front of the shoulder)
    assert mean[10] > 0.27, mean


def test_light_load_never_moves_the_waist(lifts) -> None:
    light = lifts[10]
    assert light.waist_added_at is None
    assert light.waist_motion() == 0.0
    assert {f.chain for f in light.frames} == {"hand-shoulder"}
    assert PULL_BACK not in light.strategies_used()


def test_very_heavy_load_recruits_the_waist(figure) -> None:
    """The lightest load of 25, 30, 35, 40 lb that the arm alone cannot place (measured: 25 lb):
    with the added joint the waist leans and the load arrives (book §5.3.6: pull back first, Fig
    5.17; the added joint, Fig 5.18)."""
    for lb in (25, 30, 35, 40):
        arm_only = strength_guided_lift(figure, overhead_task(figure, lb * LB, allow_waist=False))
        if not arm_only.reached:
            break
    assert not arm_only.reached and arm_only.waist_motion() == 0.0
    assert np.linalg.norm(arm_only.frames[-1].hand - arm_only.task.goal) > 0.02
    heavy = strength_guided_lift(figure, overhead_task(figure, lb * LB))
    assert heavy.reached, (lb, heavy.reason)
    assert heavy.waist_added_at is not None
    assert np.degrees(heavy.waist_motion()) > 2.0  # measured 2.9 deg of trunk lean at 25 lb, 12 at 30
    assert heavy.strategy_log[0][1] == PULL_BACK  # the start posture is already beyond the comfort level
    assert heavy.frames[-1].chain == "hand-waist"
    # the frames before the waist joined are the arm-only lift's
    np.testing.assert_array_equal(heavy.hand_path[:heavy.waist_added_at + 1],
                                  arm_only.hand_path[:heavy.waist_added_at + 1])


def test_comfort_is_kept_while_heading_for_the_goal(lifts) -> None:
    """Every available-torque or reducing-moment step ends within the comfort level (eq. 5.19); only
    pull back may start from beyond it, and it lowers the discomfort."""
    for r in lifts.values():
        for a, b in zip(r.frames[:-1], r.frames[1:]):
            if b.strategy in (AVAILABLE_TORQUE, REDUCING_MOMENT):
                assert b.discomfort <= b.limit + 1e-9
    heavy = lifts[30]
    pulls = [k for k, f in enumerate(heavy.frames) if f.strategy == PULL_BACK]
    assert pulls and heavy.frames[0].discomfort > heavy.task.comfort
    assert heavy.frames[pulls[-1]].discomfort < heavy.frames[0].discomfort


def test_monitor_ratios_match_the_strength_module(figure) -> None:
    """The monitor's ratio of each DOF equals |joint torque| / strength of the acting group as the
    analysis modules compute them (independent path: strength table, utilisation)."""
    f = make_human("male", 50)
    g = f.groups["right_shoulder_complex"]
    g.set_angles(f, np.array([1.2, 0.9, 0.1]))
    f.joint("right_elbow").displacement = np.array([0.8])
    f.groups["spine"].set_angles(f, np.array([0.2, 0.0, 0.0]))
    joints = ["right_shoulder", "right_elbow"] + list(f.groups["spine"].joints)
    mon = LiftingMonitor(f, "right_palm", "grip", 12.0, joints)
    from jackpy.peabody.groups import VariableMap
    ratios = mon.ratios_at(VariableMap(f).x())
    tau = joint_torques(f, [Load.held_mass(f, "right_palm", "grip", 12.0)])
    u = utilisation(f, tau, dof_strengths(strength_table(f)))
    names = f.dof_names()
    expected = np.array([u[names.index(n)] for n in mon.monitored_names])
    np.testing.assert_allclose(ratios, expected, rtol=1e-9)
    # flexor or extensor by the sign of the torque: the elbow holds the load with its flexors (the
    # group toward the upper limit), not its extensors
    k = mon.monitored_names.index("right_elbow[0]")
    elbow = tau[names.index("right_elbow[0]")]
    flexors, extensors = body_strength.torque("elbow", "flexion", "male", 50.0)[::-1]
    assert elbow > 0 and flexors != extensors
    assert ratios[k] == pytest.approx(elbow / flexors)


def test_work_and_energy_follow_eq_5_20(figure, lifts) -> None:
    r = lifts[20]
    for a, b in list(zip(r.frames[:-1], r.frames[1:]))[::7]:
        tau = joint_torques(figure, [Load.held_mass(figure, "right_palm", "grip", r.task.load_kg)], q=a.q)
        assert b.work == pytest.approx(float(tau @ (b.q - a.q)), rel=1e-9, abs=1e-12)
    works = np.array([f.work for f in r.frames])
    energy = np.cumsum(np.abs(works))
    np.testing.assert_allclose([f.energy for f in r.frames], energy, rtol=1e-9, atol=1e-12)
    assert np.all(np.diff(r.times) >= 0.0) and r.times[-1] > 0.0


def test_lift_is_deterministic_and_leaves_the_figure(figure) -> None:
    q0 = figure.q.copy()
    task = overhead_task(figure, 6.0)
    a, b = strength_guided_lift(figure, task), strength_guided_lift(figure, task)
    np.testing.assert_array_equal(a.hand_path, b.hand_path)
    assert a.strategy_log == b.strategy_log
    np.testing.assert_array_equal(figure.q, q0)


def test_goal_and_start_are_honoured(figure, lifts) -> None:
    for r in lifts.values():
        assert np.linalg.norm(r.frames[0].hand - r.task.start) < 2e-3
        assert np.linalg.norm(r.frames[-1].hand - r.task.goal) <= r.task.tolerance


@pytest.mark.parametrize("kwargs", [{"load_kg": -1.0}, {"comfort": 0.0}, {"comfort": 1.5}, {"exertion": -0.1},
                                    {"hand": "middle"}, {"step": 0.0}, {"load_kg": float("nan")}])
def test_bad_task_is_refused(kwargs) -> None:
    args = {"load_kg": 5.0, "goal": np.zeros(3)} | kwargs
    with pytest.raises(ValueError):
        LiftTask(**args)
