"""Acceptance: ranges of motion read by FK from the generated figure against AAOS (1965)."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from jackpy.body.human import make_human
from jackpy.body.spine import SPINE_ANGLES

#: AAOS (1965) thoracolumbar and cervical ranges, degrees: (lower direction, upper direction)
THORACOLUMBAR = {"flexion": (25.0, 80.0), "lateral": (35.0, 35.0), "axial": (45.0, 45.0)}
CERVICAL = {"flexion": (45.0, 45.0), "lateral": (45.0, 45.0), "axial": (60.0, 60.0)}
#: world axis of each spine rotation in the zero pose (flexion: about x, lateral: about z, axial: y)
AXIS = {"flexion": 0, "lateral": 2, "axial": 1}


def _relative_angle(fig, a, b, axis):
    w = fig.world_transforms()
    rv = Rotation.from_matrix(w[a][:3, :3].T @ w[b][:3, :3]).as_rotvec()
    return abs(np.degrees(rv[axis]))


@pytest.fixture(scope="module")
def fig():
    return make_human("male", 50)


@pytest.mark.parametrize("angle", SPINE_ANGLES)
def test_thoracolumbar_range_by_fk(fig, angle):
    g = fig.groups["spine"]
    k = g.angle_names.index(angle)
    for bound, want in zip((g.lower, g.upper), THORACOLUMBAR[angle]):
        theta = np.zeros(3)
        theta[k] = bound[k]
        g.set_angles(fig, theta)
        got = _relative_angle(fig, "pelvis", "t1", AXIS[angle])
        assert got == pytest.approx(want, abs=10.0)
        assert got == pytest.approx(want, abs=0.5)  # the data sum to AAOS exactly
    g.set_angles(fig, np.zeros(3))


@pytest.mark.parametrize("angle", ["flexion", "lateral", "axial"])
def test_cervical_range_by_fk(fig, angle):
    q0 = fig.q
    for j in ("c7_t1", "atlanto_occipital"):
        joint = fig.joint(j)
        k = ["axial", "lateral", "flexion"].index(angle)
        d = np.zeros(3)
        d[k] = joint.dofs[k].upper
        joint.displacement = d
    got = _relative_angle(fig, "t1", "head", AXIS[angle])
    assert got == pytest.approx(CERVICAL[angle][1], abs=10.0)
    fig.q = q0
