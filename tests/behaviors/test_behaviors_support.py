"""Support polygon and the (x, z) balance parametrisation (behaviors.md §7 items 1, 2, 4)."""

import numpy as np
import pytest

from jackpy.behaviors.support import BalanceFrame, convex_hull, mean_yaw, signed_distance, wrap, yaw_of

# two 24 x 10 cm feet, reference points 20 cm apart (left at +x), facing +z
LEFT, RIGHT = np.array([0.1, 0.0]), np.array([-0.1, 0.0])


def feet_frame() -> BalanceFrame:
    pts = []
    for r in (LEFT, RIGHT):
        for dx in (-0.05, 0.05):
            for dz in (-0.1, 0.14):
                pts.append(r + (dx, dz))
    return BalanceFrame(LEFT, RIGHT, np.array([0.0, 1.0]), convex_hull(np.array(pts)))


def test_hull_is_ccw_and_contains_the_feet():
    bf = feet_frame()
    h = bf.hull
    assert len(h) == 4
    area = 0.5 * sum(h[i - 1][0] * h[i][1] - h[i][0] * h[i - 1][1] for i in range(len(h)))
    assert area == pytest.approx(0.3 * 0.24)
    assert signed_distance(np.zeros(2), h) == pytest.approx(-0.1)
    assert signed_distance(np.array([0.0, 0.24]), h) == pytest.approx(0.1)


def test_reference_points_and_midpoint():
    bf = feet_frame()
    assert bf.params(LEFT) == pytest.approx((0.0, 0.0))
    assert bf.params(RIGHT) == pytest.approx((1.0, 0.0))
    assert bf.params(0.5 * (LEFT + RIGHT)) == pytest.approx((0.5, 0.0))
    assert bf.params(0.7 * LEFT + 0.3 * RIGHT)[0] == pytest.approx(0.3)  # 30% on the right foot


def test_front_and_back_edges_and_beside():
    bf = feet_frame()
    assert bf.params(np.array([0.0, 0.14]))[1] == pytest.approx(1.0)
    assert bf.params(np.array([0.0, -0.1]))[1] == pytest.approx(-1.0)
    assert bf.params(np.array([0.2, 0.0]))[0] < 0.0
    assert bf.params(np.array([0.0, 0.3]))[1] > 1.0


def test_round_trip_inside_the_hull():
    bf = feet_frame()
    rng = np.random.default_rng(1)
    for _ in range(200):
        x, z = rng.uniform(0, 1), rng.uniform(-1, 1)
        assert bf.params(bf.point(x, z)) == pytest.approx((x, z), abs=1e-9)


def test_facing_decides_forward_and_degenerate_line():
    bf = BalanceFrame(LEFT, RIGHT, np.array([0.0, -1.0]), feet_frame().hull)
    assert bf.params(np.array([0.0, -0.1]))[1] == pytest.approx(1.0)
    together = BalanceFrame(np.zeros(2), np.zeros(2), np.array([0.0, 1.0]), feet_frame().hull)
    assert np.linalg.norm(together.line) > 0 and together.forward @ (0, 1) == pytest.approx(1.0)


def test_yaw_helpers():
    assert yaw_of(np.array([1.0, 0.0, 0.0])) == pytest.approx(np.pi / 2)
    assert np.degrees(mean_yaw(0.0, np.radians(40))) == pytest.approx(20.0)
    assert abs(np.degrees(wrap(mean_yaw(np.radians(170), np.radians(-170))))) == pytest.approx(180.0)
