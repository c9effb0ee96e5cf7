"""The writer's rotation vectors (closed form away from a half turn) against scipy's."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from jackpy.peabody.notation import _rotvec, compose, decompose

unit = st.tuples(*[st.floats(-1, 1, allow_nan=False)] * 3).filter(lambda v: np.linalg.norm(v) > 1e-3)


@settings(max_examples=300, deadline=None)
@given(unit, st.one_of(st.floats(0, np.pi), st.floats(0, 1e-7), st.floats(np.pi - 1e-6, np.pi)))
def test_rotation_vector_matches_scipy(axis, angle):
    rv = np.asarray(axis) / np.linalg.norm(axis) * angle
    r = Rotation.from_rotvec(rv).as_matrix()
    got = _rotvec(r)
    assert np.allclose(Rotation.from_rotvec(got).as_matrix(), r, atol=1e-12)
    if angle < 3.0:
        assert np.allclose(got, Rotation.from_matrix(r).as_rotvec(), atol=1e-13)


@settings(max_examples=200, deadline=None)
@given(unit, st.floats(0, np.pi), st.tuples(*[st.floats(-2, 2, allow_nan=False)] * 3))
def test_decompose_composes_back(axis, angle, t):
    m = np.eye(4)
    m[:3, :3] = Rotation.from_rotvec(np.asarray(axis) / np.linalg.norm(axis) * angle).as_matrix()
    m[:3, 3] = t
    assert np.allclose(compose(decompose(m)), m, atol=1e-10)
