"""Joint groups: a three-joint finger driven by one curl angle, with linear limits."""

import numpy as np
import pytest

from jackpy.errors import FigureError
from jackpy.peabody import (
    Dof,
    Figure,
    Joint,
    JointGroup,
    LinearDriver,
    Segment,
    VariableMap,
)
from jackpy.peabody.transforms import translation


def finger() -> Figure:
    f = Figure("finger")
    for n, length in (("palm", 0.08), ("p1", 0.045), ("p2", 0.028), ("p3", 0.02)):
        s = Segment(n, mass=0.01)
        s.add_site("base")
        s.add_site("tip", translation(0, 0, length))
        f.add_segment(s)
    for jn, a, b in (("mcp", "palm", "p1"), ("pip", "p1", "p2"), ("dip", "p2", "p3")):
        f.add_joint(Joint(jn, a, "tip", b, "base", [Dof("R", [1, 0, 0], np.radians(-10), np.radians(100))]))
    f.root = ("palm", "base")
    # one curl angle c: mcp = 0.5 c, pip = 0.3 c, dip = 0.2 c; limited by 0 <= c and c <= 160 deg,
    # plus a linear row expressing the same upper limit (A c <= b)
    g = JointGroup("curl", ["mcp", "pip", "dip"], ["curl"], LinearDriver(np.array([[0.5], [0.3], [0.2]])),
                   lower=[0.0], upper=[np.radians(200)], A=[[1.0]], b=[np.radians(160)])
    f.add_group(g)
    return f


def test_driver_sets_member_joints():
    f = finger()
    f.groups["curl"].set_angles(f, np.radians([100.0]))
    assert np.allclose(np.degrees(f.q), [50.0, 30.0, 20.0])


def test_linear_limit_rejects_infeasible_angles():
    f = finger()
    with pytest.raises(FigureError, match="curl"):
        f.groups["curl"].set_angles(f, np.radians([170.0]))
    assert f.groups["curl"].is_feasible(np.radians([160.0]))


def test_variable_map_chain_rule_and_constraints():
    f = finger()
    vm = VariableMap(f)
    assert vm.nx == 1 and vm.names == ["curl.curl"]
    x = np.radians([90.0])
    assert np.allclose(vm.q(x), np.radians([45, 27, 18]))
    assert np.allclose(vm.dq_dx(x), [[0.5], [0.3], [0.2]])
    A, b = vm.linear_constraints()
    assert A.shape == (1, 1) and np.isclose(b[0], np.radians(160))
    vm.apply(x)
    tip = f.site_world("p3", "tip")[:3, 3]
    # a curled finger's tip comes back towards the palm: below the straight position on z
    assert tip[2] < 0.08 + 0.045 + 0.028 + 0.02 - 0.01


def test_joint_in_two_groups_is_rejected():
    f = finger()
    g = JointGroup("again", ["dip"], ["a"], LinearDriver(np.ones((1, 1))), lower=[0], upper=[1])
    with pytest.raises(FigureError, match="dip"):
        f.add_group(g)


def test_batch_evaluation_matches_single_samples():
    from jackpy.body.shoulder import SHOULDER_LOWER, SHOULDER_UPPER, ShoulderDriver
    from jackpy.peabody.groups import driver_batch

    rng = np.random.default_rng(4)
    lin = LinearDriver(np.array([[0.5], [0.3], [0.2]]), offset=[0.1, 0.0, -0.1])
    th = rng.uniform(0, 2, (50, 1))
    np.testing.assert_allclose(lin.batch(th), [lin(t) for t in th], atol=1e-15)
    sh = ShoulderDriver()
    th = rng.uniform(SHOULDER_LOWER, SHOULDER_UPPER, (500, 3))
    th[:5, 0] = np.radians([131.4, 130.0, 0.0, 180.0, 131.0])  # both pieces of Otani's betas
    np.testing.assert_allclose(sh.batch(th), [sh(t) for t in th], atol=1e-12)

    class NoBatch:
        def __call__(self, theta):
            return np.array([theta[0], 2 * theta[0]])

    np.testing.assert_allclose(driver_batch(NoBatch(), th[:7, :1]), np.c_[th[:7, 0], 2 * th[:7, 0]])
    np.testing.assert_allclose(driver_batch(sh, th[:7]), sh.batch(th[:7]))


def test_feasible_rows_applies_box_and_linear_limits():
    g = finger().groups["curl"]
    rows = g.feasible_rows(np.radians([[-1.0], [0.0], [150.0], [165.0], [210.0]]))
    assert rows.tolist() == [False, True, True, False, False]
    assert all(r == g.is_feasible(t) for r, t in zip(rows, np.radians([[-1.0], [0.0], [150.0], [165.0], [210.0]])))
