"""The compiled site rows (``Context.stacked_jacobian``/``point_jacobian``) equal the numpy reference."""

import numpy as np
import pytest

from jackpy.ik.goals import base
from jackpy.ik.goals.base import Context
from jackpy.peabody.synthetic import human_like_tree


@pytest.mark.skipif(not Context.compiled, reason="numba not installed")
def test_compiled_rows_match_numpy() -> None:
    fig = human_like_tree()
    kin = fig.kinematics()
    rng = np.random.default_rng(11)
    cols = np.sort(rng.choice(kin.ndof, size=kin.ndof // 2, replace=False))
    for _ in range(20):
        q = rng.uniform(fig.lower, fig.upper)
        fk = kin.forward(q, fig.location)
        fast = Context(kin, fk, cols)
        slow = Context(kin, fk, cols)
        slow.compiled = False
        for seg in rng.choice(len(kin.segment_names), size=5):
            k = int(rng.integers(1, 4))
            v, w = rng.normal(size=(k, 3)), rng.uniform(0.1, 2.0, size=k)
            for point in (False, True):
                assert np.allclose(fast.stacked_jacobian(seg, v, w, point), slow.stacked_jacobian(seg, v, w, point),
                                   rtol=0, atol=1e-13)
            p = rng.normal(size=3)
            assert np.allclose(fast.point_jacobian(seg, p), slow.point_jacobian(seg, p), rtol=0, atol=1e-13)


def test_reference_path_is_plain_numpy() -> None:
    assert Context.compiled == (base._site_rows_compiled is not None)
