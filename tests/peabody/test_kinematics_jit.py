"""The compiled forward pass equals the numpy reference (segments, DOF axes and points)."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.body import make_human
from jackpy.peabody.kinematics_jit import AVAILABLE
from jackpy.peabody.model import Dof, Figure, Joint, Segment
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import translation


def _with_translations() -> Figure:
    f = Figure("slides")
    for i in range(4):
        s = f.add_segment(Segment(f"s{i}"))
        s.add_site("base")
        s.add_site("tip", translation(0.2, 0.1, 0))
    f.add_joint(Joint("a", "s0", "tip", "s1", "base", [Dof("T", (1, 0, 0), -1, 1), Dof("R", (0, 1, 1))]))
    f.add_joint(Joint("b", "s1", "tip", "s2", "base", [Dof("R", (1, 0, 0)), Dof("T", (0, 1, 0), -1, 1),
                                                         Dof("R", (0, 0, 1))]))
    f.add_joint(Joint("c", "s2", "tip", "s3", "base", [Dof("T", (0, 0, 1), -1, 1)]))
    f.root = ("s2", "base")  # joints a and b traversed up
    return f


@pytest.mark.skipif(not AVAILABLE, reason="numba is not installed: the numpy path is the only one")
@pytest.mark.parametrize("make", [lambda: make_human("female", 5), human_like_tree, _with_translations])
def test_compiled_forward_equals_numpy(make) -> None:
    fig = make()
    segs = list(fig.segments)
    fig.reroot(segs[len(segs) // 2], next(iter(fig.segments[segs[len(segs) // 2]].sites)))
    kin = fig.kinematics()
    assert kin.use_jit
    rng = np.random.default_rng(0)
    for _ in range(10):
        q = rng.uniform(fig.lower, fig.upper)
        a, b = kin.forward(q, fig.location), kin.forward_numpy(q, fig.location)
        assert np.abs(a.segments - b.segments).max() < 1e-12
        assert np.abs(a.dof_axes - b.dof_axes).max() < 1e-12
        assert np.abs(a.dof_origins - b.dof_origins).max() < 1e-12
