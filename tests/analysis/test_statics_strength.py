"""Static joint torques (hand calculation, potential-energy derivative) and the strength displays."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.analysis.statics import G, Load, joint_torques
from jackpy.analysis.strength import (
    BLUE, GREEN, PURPLE, RED, WHITE, DofStrength, joint_utilisation, strength_bars, strength_colour,
    torque_vertex_colours, utilisation,
)
from jackpy.peabody import Dof, Figure, Joint, Mesh, Psurf, Segment
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import translation

X, Y, Z = np.eye(3)
UPPER, FORE, HAND = (0.30, 2.0), (0.26, 1.2), (0.09, 0.4)  # (length m, mass kg)


def straight_arm() -> Figure:
    """Base fixed at the origin; shoulder R(x)*R(z) (type order), elbow R(z); the arm lies along +x."""
    f = Figure("arm")
    base = Segment("base")
    base.add_site("shoulder")
    f.add_segment(base)
    for name, (length, mass) in zip(("upper", "fore", "hand"), (UPPER, FORE, HAND)):
        s = Segment(name, mass=mass, com=np.array([length / 2, 0, 0]))
        s.add_site("base")
        s.add_site("tip", translation(length, 0, 0))
        f.add_segment(s)
    f.add_joint(Joint("shoulder", "base", "shoulder", "upper", "base", [Dof("R", X), Dof("R", Z)]))
    f.add_joint(Joint("elbow", "upper", "tip", "fore", "base", [Dof("R", Z, -2.5, 0.1)]))
    f.add_joint(Joint("wrist", "fore", "tip", "hand", "base", [Dof("R", Z)]))
    f.root = ("base", "shoulder")
    return f


def test_arm_straight_out_holding_5kg_matches_hand_calculation():
    f = straight_arm()
    load = Load.held_mass(f, "hand", "tip", 5.0)
    tau = joint_torques(f, [load])
    (l1, m1), (l2, m2), (l3, m3) = UPPER, FORE, HAND
    shoulder = G * (m1 * l1 / 2 + m2 * (l1 + l2 / 2) + m3 * (l1 + l2 + l3 / 2) + 5.0 * (l1 + l2 + l3))
    elbow = G * (m2 * l2 / 2 + m3 * (l2 + l3 / 2) + 5.0 * (l2 + l3))
    names = f.dof_names()
    # +z rotation lifts a +x arm, so the joints must push positive
    assert tau[names.index("shoulder[1]")] == pytest.approx(shoulder, rel=0.02)
    assert tau[names.index("shoulder[1]")] == pytest.approx(shoulder, rel=1e-12)
    assert tau[names.index("elbow[0]")] == pytest.approx(elbow, rel=1e-12)
    assert tau[names.index("shoulder[0]")] == pytest.approx(0.0, abs=1e-12)  # axis along the arm


def test_arm_hanging_down_needs_no_torque_and_moment_load_passes_through():
    f = straight_arm()
    f.joint("shoulder").displacement = np.array([0.0, -np.pi / 2])
    assert np.allclose(joint_torques(f), 0.0, atol=1e-12)
    tau = joint_torques(f, [Load("hand", moment=np.array([0.0, 0.0, 3.0]))])
    np.testing.assert_allclose(tau, [0.0, -3.0, -3.0, -3.0], atol=1e-12)


def _potential(f: Figure, q: np.ndarray, loads: list[Load]) -> float:
    kin = f.kinematics()
    fk = kin.forward(q, f.location)
    v = G * float(kin.mass @ kin.segment_coms(fk)[:, 1])
    for load in loads:
        w = fk.segments[kin.segment_index[load.segment]]
        v -= float(load.force @ (w[:3, :3] @ load.point + w[:3, 3]))
    return v


@pytest.mark.parametrize("root", [("pelvis", "base"), ("foot_left", "ball"), ("palm_right", "tip")])
def test_torques_are_the_derivative_of_potential_energy(root):
    f = human_like_tree()
    f.reroot(*root)
    rng = np.random.default_rng(3)
    f.q = rng.uniform(f.lower, f.upper) * 0.5
    loads = [Load("palm_left", np.array([0.0, -0.05, 0.0]), np.array([3.0, -40.0, 10.0]))]
    tau = joint_torques(f, loads)
    q0, eps = f.q, 1e-6
    fd = np.array([(_potential(f, q0 + eps * e, loads) - _potential(f, q0 - eps * e, loads)) / (2 * eps)
                   for e in np.eye(f.ndof)])
    np.testing.assert_allclose(tau, fd, atol=1e-5)


def test_utilisation_picks_the_acting_muscle_group_and_colours():
    f = straight_arm()
    tau = joint_torques(f, [Load.held_mass(f, "hand", "tip", 5.0)])
    names = f.dof_names()
    table = {"shoulder[1]": DofStrength(positive=tau[1] * 2, negative=1.0),
             "elbow[0]": DofStrength(positive=tau[2] / 2, negative=500.0),
             "wrist[0]": DofStrength(positive=0.0, negative=0.0)}
    u = utilisation(f, tau, table)
    assert np.isnan(u[names.index("shoulder[0]")])
    assert u[1] == pytest.approx(0.5) and u[2] == pytest.approx(2.0) and u[3] == np.inf
    ju = joint_utilisation(f, u)
    assert ju["shoulder"] == pytest.approx(0.5) and ju["elbow"] == pytest.approx(2.0)
    np.testing.assert_allclose(strength_colour(0.0), WHITE)
    np.testing.assert_allclose(strength_colour(1.0), BLUE)
    np.testing.assert_allclose(strength_colour(0.5), (WHITE + BLUE) / 2)
    np.testing.assert_allclose(strength_colour(np.array([1.5, np.nan])), [RED, WHITE])


def test_strength_bar_parts_follow_the_book():
    f = straight_arm()
    tau = np.array([0.0, 30.0, -20.0, 10.0])
    table = {"shoulder[0]": DofStrength(50, 50), "shoulder[1]": DofStrength(80, 5),
             "elbow[0]": DofStrength(100, 15), "wrist[0]": DofStrength(10, 10)}
    bars = {b.dof: b for b in strength_bars(f, tau, table)}
    assert bars["shoulder[0]"].parts == ((50, GREEN),) and not bars["shoulder[0]"].over
    assert bars["shoulder[1]"].parts[0][0] == 30 and bars["shoulder[1]"].parts[1] == (50, GREEN)
    assert bars["elbow[0]"].over and bars["elbow[0]"].parts[0] == (15, GREEN)
    assert bars["elbow[0]"].parts[1][0] == pytest.approx(5)
    assert bars["wrist[0]"].parts == ((10, PURPLE),)


def test_vertex_colours_fade_from_the_joint():
    f = straight_arm()
    box = Mesh(np.array([[0, 0, 0], [0.3, 0, 0], [0.15, 0.02, 0]]), np.array([[0, 1, 2]]))
    f.segment("upper").psurf = Psurf("upper.pss", mesh=box)
    cols = torque_vertex_colours(f, {"shoulder": 1.0, "elbow": float("nan")}, spread=0.2)
    np.testing.assert_allclose(cols["upper"][0], BLUE)  # at the shoulder centre
    np.testing.assert_allclose(cols["upper"][1], WHITE)  # 30 cm away
    assert set(cols) == {"upper"}
