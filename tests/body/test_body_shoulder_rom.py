"""Shoulder ranges of motion read by FK from the generated figure against AAOS (1965): flexion 180,
extension 60, abduction 180, horizontal flexion 135 and horizontal extension 45 (issue 19 item 2).

The limit search moves along one group angle to the edge of the group's feasible set
(``JointGroup.is_feasible``: box plus the linear rows ``A z <= b``), then measures the arm by FK.
Behind the body the limit is non-convex (two limit pieces, jackpy.body.shoulder), so extension,
horizontal extension and abduction all meet AAOS.
"""

import numpy as np
import pytest

from jackpy.body.human import make_human

SIDE = "left"
#: left arm in the zero pose's world frame: y up, +z forward, +x the figure's left (lateral)
UP, FORWARD, LATERAL = np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0])


@pytest.fixture(scope="module")
def fig():
    return make_human("male", 50)


def _arm(fig) -> np.ndarray:
    v = fig.site_world(f"{SIDE}_forearm", "base")[:3, 3] - fig.site_world(f"{SIDE}_upper_arm", "base")[:3, 3]
    return v / np.linalg.norm(v)


def _edge(g, fixed: dict[int, float], k: int, start: float, stop: float) -> float:
    """Farthest feasible value of group angle ``k`` from ``start`` toward ``stop`` (radians)."""
    def ok(v):
        th = np.zeros(3)
        for i, x in fixed.items():
            th[i] = x
        th[k] = v
        return g.is_feasible(th)
    assert ok(start)
    if ok(stop):
        return stop
    a, b = start, stop
    for _ in range(60):
        m = 0.5 * (a + b)
        a, b = (m, b) if ok(m) else (a, m)
    return a


def _pose(fig, phi, theta):
    g = fig.groups[f"{SIDE}_shoulder_complex"]
    g.set_angles(fig, np.array([phi, theta, 0.0]))
    return _arm(fig)


def _elevation_deg(arm):
    return float(np.degrees(np.arccos(np.clip(-arm @ UP, -1.0, 1.0))))


def _horizontal_deg(arm):
    """Angle of the arm in the horizontal plane from the lateral direction, + forward (deg)."""
    return float(np.degrees(np.arctan2(arm @ FORWARD, arm @ LATERAL)))


def test_flexion_and_abduction_reach_180(fig):
    g = fig.groups[f"{SIDE}_shoulder_complex"]
    for theta in (np.pi / 2, 0.0):  # forward (flexion), lateral (abduction)
        phi = _edge(g, {1: theta}, 0, 0.0, np.pi)
        assert _elevation_deg(_pose(fig, phi, theta)) == pytest.approx(180.0, abs=10.0)


def test_extension_behind_the_body_is_60(fig):
    g = fig.groups[f"{SIDE}_shoulder_complex"]
    theta = -np.pi / 2  # the arm swings backward in the sagittal plane
    phi = _edge(g, {1: theta}, 0, 0.0, np.pi)
    arm = _pose(fig, phi, theta)
    assert arm @ FORWARD < 0 and abs(arm @ LATERAL) < 1e-6
    assert _elevation_deg(arm) == pytest.approx(60.0, abs=10.0)


def test_horizontal_flexion_at_90_elevation_is_135(fig):
    g = fig.groups[f"{SIDE}_shoulder_complex"]
    theta = _edge(g, {0: np.pi / 2}, 1, 0.0, np.pi)
    arm = _pose(fig, np.pi / 2, theta)
    assert _elevation_deg(arm) == pytest.approx(90.0, abs=1e-6)
    assert _horizontal_deg(arm) == pytest.approx(135.0, abs=10.0)


def test_horizontal_extension_at_90_elevation_is_aaos_45(fig):
    g = fig.groups[f"{SIDE}_shoulder_complex"]
    theta = _edge(g, {0: np.pi / 2}, 1, 0.0, -np.pi)
    arm = _pose(fig, np.pi / 2, theta)
    assert _elevation_deg(arm) == pytest.approx(90.0, abs=1e-6)
    assert -_horizontal_deg(arm) == pytest.approx(45.0, abs=10.0)


def test_the_limit_behind_the_body_is_not_convex(fig):
    """Extension and abduction are allowed, their midpoint in (theta, phi) is not: a convex limit
    (box plus linear rows) could not give AAOS extension, horizontal extension and abduction at once."""
    g = fig.groups[f"{SIDE}_shoulder_complex"]
    ext, abd = np.radians([60.0, -90.0, 0.0]), np.radians([180.0, 0.0, 0.0])
    assert g.is_feasible(ext) and g.is_feasible(abd)
    assert not g.is_feasible(0.5 * (ext + abd))


def test_ik_reaches_behind_the_body_and_then_up_sideways(fig):
    """One IK problem, solved frame after frame (warm, as the document does): first a hand target
    behind the body (the extension piece), then up at 150 deg in the frontal plane (the abduction
    piece, outside the first one); the solver re-chooses the piece at each solve's start."""
    from jackpy import ik

    f = make_human("male", 50)
    g = f.groups[f"{SIDE}_shoulder_complex"]
    sh = f.site_world(f"{SIDE}_upper_arm", "base")[:3, 3]
    reach = np.linalg.norm(f.site_world(f"{SIDE}_palm", "base")[:3, 3] - sh)
    behind = sh + 0.95 * reach * np.array([0.0, -np.cos(np.radians(55)), -np.sin(np.radians(55))])
    side_up = sh + 0.95 * reach * np.array([np.sin(np.radians(150)), -np.cos(np.radians(150)), 0.0])
    prob = ik.Problem(f)
    goal = prob.add(ik.Position(f"{SIDE}_palm.base", behind, chain=f"{SIDE}_clavicle"))
    for target in (behind, side_up):
        goal.target = target
        for _ in range(6):  # frames: each solve starts from the last posture
            ik.solve(prob)
        assert g.is_feasible(g.angles)
        assert np.linalg.norm(f.site_world(f"{SIDE}_palm", "base")[:3, 3] - target) < 0.03
