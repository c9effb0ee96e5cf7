"""Strength-guided lifting: the comfort level and the perceived exertion shape the path (book §5.3.8
Figs 5.22-5.24), and the perceived-exertion cone (spec §2.9.3)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from jackpy.body.human import make_human
from jackpy.planning.lifting import overhead_task, strength_guided_lift
from jackpy.planning.lifting_strategies import project_to_cone, weighted_step

LB = 0.45359237


def _deviation(result) -> float:
    """Largest distance (m) of the hand path from the straight start-goal line."""
    p = result.hand_path
    a, d = p[0], result.task.goal - p[0]
    return float((np.linalg.norm(np.cross(p - a, d), axis=1) / np.linalg.norm(d)).max())


def test_a_stricter_comfort_level_keeps_the_hand_closer() -> None:
    """30 lb with cl 0.5 against cl 0.85 (Fig 5.22): the stricter limit brings the hand nearer the
    body (measured 0.21 against 0.28 m)."""
    man = make_human("male", 50)
    strict = strength_guided_lift(man, overhead_task(man, 30 * LB, comfort=0.5))
    loose = strength_guided_lift(man, overhead_task(man, 30 * LB, comfort=0.85))
    assert strict.reached and loose.reached
    assert strict.horizontal_distance().mean() < loose.horizontal_distance().mean() - 0.02
    assert max(f.discomfort for f in loose.frames[1:] if f.strategy != "pull back") <= 0.85 + 1e-9


def test_low_perceived_exertion_keeps_the_path_straight() -> None:
    """5 lb with pe 0.05 against pe 0.30 (Fig 5.24): the narrow cone keeps the hand near the straight
    line (measured 0.9 against 4.2 cm of largest deviation)."""
    man = make_human("male", 50)
    narrow = strength_guided_lift(man, overhead_task(man, 5 * LB, exertion=0.05))
    wide = strength_guided_lift(man, overhead_task(man, 5 * LB, exertion=0.30))
    assert narrow.reached and wide.reached
    assert _deviation(narrow) < 0.5 * _deviation(wide)
    assert _deviation(narrow) < 0.02


unit = st.lists(st.floats(-1.0, 1.0), min_size=3, max_size=3).map(np.array).filter(lambda v: np.linalg.norm(v) > 1e-3)


@settings(max_examples=200, deadline=None)
@given(v=unit, axis=unit, beta=st.floats(0.0, np.pi / 2))
def test_cone_projection(v, axis, beta) -> None:
    axis = axis / np.linalg.norm(axis)
    out = project_to_cone(v, axis, beta)
    assert abs(np.linalg.norm(out) - 1.0) < 1e-9
    assert float(out @ axis) >= np.cos(beta) - 1e-9  # within the cone
    d = v / np.linalg.norm(v)
    if d @ axis >= np.cos(beta):
        np.testing.assert_allclose(out, d, atol=1e-12)  # inside: unchanged
    else:  # outside: on the surface, in the plane of v and the axis
        assert abs(float(out @ axis) - np.cos(beta)) < 1e-9
        assert abs(float(np.cross(axis, d) @ out)) < 1e-9


@settings(max_examples=100, deadline=None)
@given(jac=st.lists(st.floats(-1.0, 1.0), min_size=12, max_size=12).map(lambda x: np.array(x).reshape(3, 4)),
       w=st.lists(st.floats(0.05, 1.0), min_size=4, max_size=4).map(np.array),
       dp=st.lists(st.floats(-0.01, 0.01), min_size=3, max_size=3).map(np.array))
def test_weighted_step_moves_the_hand_as_asked(jac, w, dp) -> None:
    """On a well-conditioned Jacobian the weighted least-norm step moves the hand by ``dp`` (up to
    the damping), and no other step of the same hand motion has a smaller weighted norm."""
    s = np.linalg.svd(jac * np.sqrt(w), compute_uv=False)
    if s.min() < 0.3:
        return
    dx = weighted_step(jac, w, dp)
    np.testing.assert_allclose(jac @ dx, dp, atol=0.01 * np.linalg.norm(dp) + 1e-12)
    null = np.linalg.svd(jac)[2][-1]
    other = dx + 0.1 * null
    assert dx @ (dx / w) <= other @ (other / w) + 1e-15
