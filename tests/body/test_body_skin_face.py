"""The fuller face (jackpy.body.skin_face) on the generated head."""

import numpy as np

from jackpy.body.mesh_loft import signed_volume
from jackpy.body.sass import spec_for
from jackpy.body.shapes import _head
from jackpy.body.skeleton import build_skeleton
from jackpy.body.skin_face import refine_face


def test_the_face_is_reshaped_and_the_cranium_kept():
    spec = spec_for("female", 5)
    sk = build_skeleton(spec, "f")
    plain = _head(spec, sk)
    face = refine_face(plain, spec.stature, sk.points["view"], spec.dims["eyes.breadth"])
    assert np.array_equal(face.faces, plain.faces) and signed_volume(face) > 0
    v0, v1 = plain.vertices, face.vertices
    assert v1[:, 1].max() == v0[:, 1].max()  # the vertex (stature landmark) is untouched
    back = v0[:, 2] < 0.5 * (v0[:, 2].min() + v0[:, 2].max())
    assert np.array_equal(v0[back], v1[back])  # the back of the head is untouched
    eye_y = sk.points["view"][1]
    jaw = (v0[:, 1] < eye_y - 0.08) & (v0[:, 2] > sk.points["view"][2] - 0.05)
    assert np.ptp(v1[jaw, 0]) > 1.1 * np.ptp(v0[jaw, 0])  # a wider jaw, not a point
    brow = (np.abs(v0[:, 1] - eye_y - 0.017) < 0.004) & (np.abs(np.abs(v0[:, 0]) - 0.03) < 0.01) & ~back
    assert (v1[brow, 2] - v0[brow, 2]).max() > 0.003  # a brow ridge over the eyes
