"""Every goal's analytic gradient and whole Jacobian against central finite differences, at random
and singular postures (fixed seeds)."""

import zlib

import numpy as np
import pytest

import jackpy.behaviors  # noqa: F401  (defines the behaviors' goal kinds: every registered kind is checked)
from jackpy import ik
from jackpy.ik.goals import GOAL_TYPES, Distance, SiteGoal
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
        "distance_inside": Distance("palm_left.tip", (0.3, 1.3, 0.4), radius=0.05),
        "distance_outside": Distance("palm_right.tip", (-0.2, 1.0, 0.1), radius=2.0, mode="outside"),
        "distance_surface": Distance("head.tip", (0.1, 1.5, 0.2), radius=0.2, mode="surface"),
    }


def _seed(name: str) -> int:
    """A fixed seed per case (crc32: the same in every run, unlike ``hash``)."""
    return zlib.crc32(name.encode())


def _example(kind: str, rng: np.random.Generator) -> ik.Goal:
    """A goal of registered ``kind`` whose targets are away from the posture: site goals placed
    by a random frame (their own placement code), the others built by hand."""
    cls = GOAL_TYPES[kind]
    if issubclass(cls, SiteGoal):
        frame = translation(*rng.uniform([-0.4, 0.6, -0.4], [0.4, 1.6, 0.4])) @ euler_xyz(rng.uniform(-2, 2, 3))
        return cls.at_frame("palm_left.tip", frame, chain="spine5" if rng.random() < 0.5 else None)
    if kind == "centre-of-mass":
        return ik.CentreOfMass(rng.uniform(-0.2, 0.2, 3))
    if kind in ("all-of", "any-of"):
        a = _example("position", rng)
        b = ik.Plane("palm_right.tip", rng.uniform(-0.3, 0.3, 3) + [0, 1, 0], rng.normal(size=3), weight=2.0)
        return cls([a, b], weight=0.7)
    if kind == "limit-spring":
        from jackpy.behaviors.limit_springs import LimitSpring

        return LimitSpring("elbow_left", 0.0, 1.0, 3.0)
    raise AssertionError(f"goal kind {kind!r} has no example here: add one")


def _jacobian_check(fig, goal, q, h=1e-6):
    """The stacked residual's Jacobian against central differences of the residual, column by column."""
    fig.q = q
    p = ik.Problem(fig)
    p.add(goal)
    comp = p.compile()
    x, z, _, _ = comp.start()
    q0 = fig.q
    F, J = comp.evaluate(x, q0, z).levels[0]
    assert np.all(np.isfinite(J)) and J.shape == (F.size, z.size)
    fd = np.empty_like(J)
    for i in range(z.size):
        zp, zm = z.copy(), z.copy()
        zp[i] += h
        zm[i] -= h
        fd[:, i] = (comp.evaluate(x, q0, zp).levels[0][0] - comp.evaluate(x, q0, zm).levels[0][0]) / (2 * h)
    scale = max(1.0, np.abs(fd).max())
    assert np.allclose(J, fd, atol=1e-5 * scale, rtol=1e-4), np.abs(J - fd).max()


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
    rng = np.random.default_rng(_seed(name))
    for _ in range(2):
        _check(fig, _goals()[name], rng.uniform(fig.lower, fig.upper) * 0.6)


@pytest.mark.parametrize("name", list(_goals()))
def test_whole_jacobian_matches_finite_differences(name):
    fig = human_like_tree()
    rng = np.random.default_rng(_seed(name) + 1)
    for _ in range(2):
        _jacobian_check(fig, _goals()[name], rng.uniform(fig.lower, fig.upper) * 0.6)


@pytest.mark.parametrize("kind", sorted(GOAL_TYPES))
def test_every_registered_kind_whole_jacobian(kind):
    """Every class in GOAL_TYPES (the built-in ones and any another module defined), placed at
    random frames, at random postures: the whole Jacobian of its residual."""
    fig = human_like_tree()
    rng = np.random.default_rng(_seed(kind))
    for _ in range(3):
        _jacobian_check(fig, _example(kind, rng), rng.uniform(fig.lower, fig.upper) * 0.6)


def test_goal_kinds_round_trip_through_dicts():
    """to_dict/from_dict give back a goal with the same residual for every registered kind."""
    import json

    fig = human_like_tree()
    rng = np.random.default_rng(7)
    for kind in sorted(GOAL_TYPES):
        goal = _example(kind, rng)
        again = ik.Goal.from_dict(json.loads(json.dumps(goal.to_dict())))
        assert type(again) is type(goal) and again.name == goal.name
        for g in (goal, again):
            g.bind(fig)
        kin = fig.kinematics()
        fk = kin.forward(fig.q, fig.location)
        ctx = ik.goals.Context(kin, fk, np.flatnonzero(goal.chain_mask()))
        assert np.array_equal(goal.evaluate(ctx).f, again.evaluate(ctx).f), kind


def test_a_goal_kind_registers_itself_by_being_defined():
    class Above(SiteGoal):
        kind = "test-above"
        targets = ("height",)

        def __init__(self, site, height, chain=None, weight=1.0, name=None):
            super().__init__(site, chain, weight, name)
            self.height = float(height)

        def evaluate(self, ctx):
            return ik.goals.GoalEval(np.zeros(1), np.zeros((1, ctx.cols.size)))

    try:
        assert GOAL_TYPES["test-above"] is Above
        with pytest.raises(TypeError, match="already"):
            type("Other", (SiteGoal,), {"kind": "test-above"})
    finally:
        del GOAL_TYPES["test-above"]


def test_distance_modes():
    fig = human_like_tree()
    r = fig.site_world("palm_left", "tip")[:3, 3]
    kin = fig.kinematics()
    fk = kin.forward(fig.q, fig.location)
    for mode, radius, expect in (("inside", 0.05, 0.15), ("inside", 0.3, 0.0), ("outside", 0.3, 0.1),
                                 ("outside", 0.1, 0.0), ("surface", 0.3, 0.1), ("surface", 0.1, 0.1)):
        g = Distance("palm_left.tip", r + [0.2, 0.0, 0.0], radius=radius, mode=mode)
        g.bind(fig)
        e = g.evaluate(ik.goals.Context(kin, fk, np.flatnonzero(g.chain_mask())))
        assert abs(e.metres - expect) < 1e-12, (mode, radius)
    with pytest.raises(ValueError, match="mode"):
        Distance("palm_left.tip", r, mode="near")
    with pytest.raises(ValueError, match="radius"):
        Distance("palm_left.tip", r, radius=-1.0)


def test_distance_goal_is_met_by_the_solver():
    fig = human_like_tree()
    centre = fig.site_world("palm_left", "tip")[:3, 3] + [0.15, 0.25, 0.1]
    p = ik.Problem(fig)
    p.add(Distance("palm_left.tip", centre, radius=0.05, mode="inside", chain="spine5"))
    r = ik.solve(p)
    assert r.status == ik.ACHIEVED
    assert np.linalg.norm(fig.site_world("palm_left", "tip")[:3, 3] - centre) <= 0.05 + 1e-4


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
