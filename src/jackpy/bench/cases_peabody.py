"""Benchmark: forward kinematics of the 69-segment, 136-DOF human-shaped tree and of the standard
human (74 segments, 137 DOFs).

Baseline: the straightforward implementation, one Python step per joint (and per DOF inside it)
walking the tree from the root, the way the book's formulas read.
"""

from __future__ import annotations

import numpy as np

from jackpy.bench.runner import Case, Result, time_calls
from jackpy.peabody.model import Figure
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import rigid_inverse


def per_joint_forward(figure: Figure, q: np.ndarray) -> dict[str, np.ndarray]:
    """Reference FK: a Python loop over joints and DOFs, breadth-first from the root segment."""
    figure.q = q
    root_seg, root_site = figure.root
    world = {root_seg: figure.location @ rigid_inverse(figure.site_location(root_seg, root_site))}
    pending = list(figure.joints.values())
    while pending:
        rest = []
        for j in pending:
            if j.from_seg in world and j.to_seg not in world:
                w_site = world[j.from_seg] @ figure.site_location(j.from_seg, j.from_site) @ j.transform()
                world[j.to_seg] = w_site @ rigid_inverse(figure.site_location(j.to_seg, j.to_site))
            elif j.to_seg in world and j.from_seg not in world:
                w_site = world[j.to_seg] @ figure.site_location(j.to_seg, j.to_site) @ rigid_inverse(j.transform())
                world[j.from_seg] = w_site @ rigid_inverse(figure.site_location(j.from_seg, j.from_site))
            else:
                rest.append(j)
        pending = rest
    return world


def _fk_case(quick: bool) -> Result:
    return _fk(human_like_tree(), "fk-human-136", quick)


def _fk_standard(quick: bool) -> Result:
    from jackpy.body import make_human

    return _fk(make_human("male", 50), "fk-standard-human", quick)


def _fk(figure: Figure, name: str, quick: bool) -> Result:
    rng = np.random.default_rng(0)
    q = rng.uniform(figure.lower, figure.upper)
    kin = figure.kinematics()
    loc = figure.location
    fast = time_calls(lambda: kin.forward(q, loc), repeat=200 if quick else 2000)
    base = time_calls(lambda: per_joint_forward(figure, q), repeat=20 if quick else 200)
    ref = per_joint_forward(figure, q)
    got = kin.forward(q, loc).segments
    err = max(np.abs(got[kin.segment_index[n]] - w).max() for n, w in ref.items())
    return Result(name, fast.median_ms, fast.p90_ms, base.median_ms,
                  {"segments": len(figure.segments), "dofs": figure.ndof, "max_err": float(err)})


CASES = [Case("fk-human-136", _fk_case, "FK of a 69-segment 136-DOF tree vs a per-joint Python loop"),
         Case("fk-standard-human", _fk_standard, "FK of the standard human (74 segments, 137 DOFs), same baseline")]
