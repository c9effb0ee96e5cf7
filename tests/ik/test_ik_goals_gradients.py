"""Every goal's analytic gradient against central finite differences, at random and singular postures."""

import numpy as np
import pytest

from jackpy import ik
from jackpy.ik.goals.aim import aim_gradient_r
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import euler_xyz, translation


def _goals() -> dict[str, ik.Goal]:
    frame = translation(0.3, 1.2, 0.3) @ euler_xyz((0.3, -0.5, 1.0))
    return {
        "position": ik.Position("palm_left.tip", (0.4, 1.1, 0.2), chain="spine5"),
        "orientation": ik.Orientation("palm_left.tip", frame, cx=2.0, cy=0.5),
        "orientation_direction": ik.Orientation("palm_right.tip", frame, cy=0.0),
        "position_orientation": ik.PositionOrientation("palm_right.tip", frame, position_weight=0.3,
                                                       cx=ik.unit_factor(5.0, 0.01)),
        "aim": ik.Aim("head.tip", (0.2, 1.7, 1.0), axis=(0, 0, 1), c=1.5),
        "aim_close": ik.Aim("head.tip", (0.0, 1.9, 0.02), axis=(0, 1, 0)),
        "line": ik.Line("foot_left.tip", (0.1, 0.0, 0.2), (0.2, 1.0, 0.1)),
        "plane": ik.Plane("palm_left.tip", (0.0, 1.0, 0.3), (0.1, 0.3, 1.0)),
        "half_space": ik.HalfSpace("palm_left.tip", (0.0, 1.0, 0.0), (0.0, -1.0, 0.2)),
        "com": ik.CentreOfMass((0.05, 0.0, 0.02)),
        "and": ik.AllOf([ik.Position("head.tip", (0, 1.8, 0.1), weight=2.0),
                         ik.Plane("palm_right.tip", (0, 1, 0), (1, 0, 0))], weight=0.7),
        "or": ik.AnyOf([ik.HalfSpace("palm_left.tip", (0.5, 1, 0), (1, 0, 0)),
                        ik.HalfSpace("palm_left.tip", (0, 2.0, 0), (0, 1, 0), weight=3.0)]),
    }


def _check(fig, goal, q, rel=1e-5):
    fig.q = q
    p = ik.Problem(fig)
    p.add(goal)
    comp = p.compile()
    x, z, _, _ = comp.start()
    q0 = fig.q
    ev = comp.evaluate(x, q0, z)
    F, J = ev.levels[0]
    g = 2.0 * J.T @ F
    h = 1e-6
    fd = np.empty_like(z)
    for i in range(z.size):
        zp, zm = z.copy(), z.copy()
        zp[i] += h
        zm[i] -= h
        fd[i] = (comp.evaluate(x, q0, zp).potential(0) - comp.evaluate(x, q0, zm).potential(0)) / (2 * h)
    scale = max(1.0, np.abs(fd).max())
    assert np.allclose(g, fd, atol=rel * scale, rtol=1e-4), np.abs(g - fd).max()
    assert np.all(np.isfinite(g))


@pytest.mark.parametrize("name", list(_goals()))
def test_gradient_matches_finite_differences(name):
    fig = human_like_tree()
    rng = np.random.default_rng(abs(hash(name)) % 2**32)
    for _ in range(2):
        _check(fig, _goals()[name], rng.uniform(fig.lower, fig.upper) * 0.6)


@pytest.mark.parametrize("name", ["position", "orientation", "position_orientation", "aim", "line"])
def test_gradient_at_singular_posture(name):
    """Zero posture: arms and legs fully extended (a kinematic singularity)."""
    fig = human_like_tree()
    _check(fig, _goals()[name], np.zeros(fig.ndof))


def test_stiffness_scaled_gradient():
    fig = human_like_tree()
    p = ik.Problem(fig)
    goal = ik.Position("palm_left.tip", (0.4, 1.1, 0.2), chain="spine5")
    p.set_scale("shoulder_left", 0.5)
    p.set_scale("elbow_left", 0.0)
    p.add(goal)
    comp = p.compile()
    elbow = fig.joint_dof_slice("elbow_left").start
    assert elbow not in comp.cols
    _check(fig, goal, np.zeros(fig.ndof))


def test_aim_gradient_corrected_cubic():
    """§3.6-B: grad_r of the aim potential has |p-r|^3 below; the printed square does not match FD."""
    rng = np.random.default_rng(3)
    for _ in range(20):
        p, r = rng.normal(size=3), rng.normal(size=3)
        v = rng.normal(size=3)
        v /= np.linalg.norm(v)

        def P(rr, p=p, v=v):
            u = (p - rr) / np.linalg.norm(p - rr)
            return np.sum((u - v) ** 2)

        fd = np.array([(P(r + e) - P(r - e)) / 2e-7 for e in np.eye(3) * 1e-7])
        assert np.allclose(aim_gradient_r(p, r, v), fd, atol=1e-6)
        d = p - r
        literal = 2 * (d @ d * v - (d @ v) * d) / (d @ d)
        if abs(np.linalg.norm(d) - 1.0) > 0.1:
            assert not np.allclose(literal, fd, atol=1e-3)


def test_aim_at_target_point_is_finite():
    fig = human_like_tree()
    head = fig.site_world("head", "tip")[:3, 3]
    p = ik.Problem(fig)
    p.add(ik.Aim("head.tip", head))
    comp = p.compile()
    x, z, _, _ = comp.start()
    ev = comp.evaluate(x, fig.q, z)
    assert np.all(np.isfinite(ev.levels[0][1])) and ev.potential(0) == 0.0
