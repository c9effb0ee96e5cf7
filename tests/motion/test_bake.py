"""Baking: deterministic (same bits) and incremental (a scrub re-simulates from the nearest kept
state, not from 0); two figures with behaviors on."""

from __future__ import annotations

import numpy as np

from jackpy.motion import cast
from jackpy.motion.bake import Baker
from jackpy.motion.kinds.arm import ArmMotion
from jackpy.motion.kinds.com import COMMotion
from jackpy.motion.kinds.foot import FootMotion
from jackpy.motion.kinds.gaze import GazeMotion
from jackpy.motion.kinds.heel import HeelMotion
from jackpy.motion.timed import TimedBehavior
from jackpy.motion.timeline import Timeline


def two_figure_timeline() -> Timeline:
    tl = Timeline(cast={"jack": {"human": "male:50", "position": [0.0, 0.0], "heading_deg": 0.0},
                        "jill": {"human": "female:5", "position": [1.0, 0.0], "heading_deg": 30.0}})
    for fig in ("jack", "jill"):
        tl.add(COMMotion(figure=fig, t0=0.0, t1=0.4, x=0.2))
        tl.add(HeelMotion(figure=fig, side="right", t0=0.2, t1=0.5, height=0.04))
        tl.add(FootMotion(figure=fig, side="right", t0=0.5, t1=0.9, displacement=[0, 0, 0.25], local=False,
                          height=0.06))
        tl.add(ArmMotion(figure=fig, side="left", t0=0.1, t1=0.9, target={"point": [0.3, 1.2, 0.4]},
                         weight_fn="ease"))
        tl.add(GazeMotion(figure=fig, t0=0.0, t1=0.8, target={"point": [0.5, 1.5, 2.0]}))
    tl.add(TimedBehavior("jill", "torso", "hold", 0.3, 0.7))
    tl.duration = 1.0
    return tl


def bake_once():
    tl = two_figure_timeline()
    env, loops = cast.build(tl)
    b = Baker(tl, loops, env, 30.0, checkpoint_every=10)
    return b, b.bake(), loops


def test_bake_is_deterministic_to_the_bit():
    _, a, _ = bake_once()
    _, b, _ = bake_once()
    assert len(a) == len(b) == 31
    for fa, fb in zip(a, b):
        for name in fa:
            assert fa[name].same(fb[name])
    # the figures did move
    assert not np.array_equal(a[0]["jack"].q, a[-1]["jack"].q)


def test_scrub_resimulates_from_the_nearest_kept_state():
    baker, frames, loops = bake_once()
    baked = [{n: p for n, p in f.items()} for f in frames]
    for target in (25, 7, 19, 30, 0):
        before = baker.simulated
        baker.seek(target)
        nearest = max(k for k in baker.checkpoints if k <= target) if target >= 10 else -1
        assert baker.simulated - before <= target - nearest  # never from 0 past a kept state
        for name, loop in loops.items():
            now = type(baked[target][name]).of(loop.figure)
            assert now.same(baked[target][name]), (target, name)


def test_invalidate_rebakes_from_an_edit():
    baker, frames, loops = bake_once()
    old = [f["jack"] for f in frames]
    baker.timeline.motions[0].x = 0.8  # an edit of the first COM motion
    baker.invalidate(0.0)
    new = baker.bake()
    assert len(new) == len(old)
    assert not new[-1]["jack"].same(old[-1])
