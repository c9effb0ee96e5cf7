"""Benchmark rows of motion over time.

- ``motion-bake``: per frame of baking a 10 s motion of two figures (a 50th-percentile man and a
  5th-percentile woman, every default behavior on: COM shifts, heel and foot motions stepping,
  reaches, head turns, a timed torso hold) at 30 fps; ``extra.frames_per_s``. Baseline: the same two
  figures' behavior loops stepped without a timeline (so the ratio is the timeline's overhead:
  < 1 means the motions cost more than the idle loops).
- ``bvh-import``: per frame of retargeting ``cmu_02_01_walk.bvh`` onto the standard male at 30 fps
  (three IK passes per frame: legs with planted feet, trunk and head, arms); ``extra.frames_per_s``.
  Baseline: one behavior-loop frame of the same figure standing (the ratio says how many
  interactive frames one imported frame costs, inverted).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from jackpy.bench.runner import Case, Result, Timing, time_calls

MOCAP = Path("/work/shared/data/mocap") / "cmu_02_01_walk.bvh"


def ten_second_timeline(duration: float = 10.0):
    """The two-figure motion of the ``motion-bake`` row (also used by its test)."""
    from jackpy.motion.kinds.arm import ArmMotion
    from jackpy.motion.kinds.com import COMMotion
    from jackpy.motion.kinds.foot import FootMotion
    from jackpy.motion.kinds.gaze import GazeMotion
    from jackpy.motion.kinds.heel import HeelMotion
    from jackpy.motion.timed import TimedBehavior
    from jackpy.motion.timeline import Timeline

    tl = Timeline(cast={"jack": {"human": "male:50", "position": [0.0, 0.0]},
                        "jill": {"human": "female:5", "position": [1.2, 0.0], "heading_deg": -20.0}})
    for fig in ("jack", "jill"):
        t = 0.0
        k = 0
        while t + 2.0 <= duration:
            side, other = ("right", "left") if k % 2 == 0 else ("left", "right")
            tl.add(COMMotion(figure=fig, t0=t, t1=t + 0.5, x=0.2 if side == "right" else 0.8, velocity_fn="ease"))
            tl.add(HeelMotion(figure=fig, side=side, t0=t + 0.3, t1=t + 0.6, height=0.03))
            tl.add(FootMotion(figure=fig, side=side, t0=t + 0.6, t1=t + 1.2, displacement=[0, 0, 0.15], height=0.06,
                              velocity_fn="ease"))
            tl.add(ArmMotion(figure=fig, side=other, t0=t + 0.2, t1=t + 1.6,
                             target={"point": [0.3 if other == "left" else -0.3, 1.15, 0.35 + 0.15 * k]},
                             weight_fn="ease"))
            tl.add(GazeMotion(figure=fig, t0=t, t1=t + 1.0, target={"point": [(-1) ** k * 1.0, 1.5, 2.0 + k]}))
            t += 2.0
            k += 1
        tl.add(TimedBehavior(fig, "torso", "hold", 1.0, 3.0))
    tl.duration = duration
    return tl


def _bake_case(quick: bool) -> Result:
    from jackpy.motion import cast
    from jackpy.motion.bake import Baker

    duration = 2.0 if quick else 10.0
    tl = ten_second_timeline(duration)
    env, loops = cast.build(tl)
    baker = Baker(tl, loops, env, 30.0)
    t0 = time.perf_counter()
    samples = []
    for i in range(baker.n_frames):
        s = time.perf_counter()
        baker.seek(i)
        samples.append((time.perf_counter() - s) * 1e3)
    total = time.perf_counter() - t0
    # baseline: the same figures' loops without a timeline
    env2, loops2 = cast.build(ten_second_timeline(duration))
    base = []
    for _ in range(min(60, baker.n_frames)):
        s = time.perf_counter()
        for loop in loops2.values():
            loop.step()
        base.append((time.perf_counter() - s) * 1e3)
    timing = Timing(np.array(samples))
    return Result("motion-bake", timing.median_ms, timing.p90_ms, float(np.median(base)),
                  {"frames": baker.n_frames, "figures": 2, "frames_per_s": baker.n_frames / total,
                   "motion_s": duration})


def _import_case(quick: bool) -> Result:
    from jackpy.motion import cast
    from jackpy.motion.bvh import read
    from jackpy.motion.retarget import SIDES, Retargeter, choose_map, targets_for

    bvh = read(str(MOCAP))
    fig = cast.make_figure("jack", {"human": "male:50"})
    loop = cast.loop_for(cast.make_figure("ref", {"human": "male:50"}))
    base = time_calls(loop.step, repeat=20, warmup=0).median_ms
    t0 = time.perf_counter()
    tg, _, _ = targets_for(fig, bvh, choose_map(bvh), 30.0)
    rt = Retargeter(fig)
    n = min(tg.hips.shape[0], 20 if quick else tg.hips.shape[0])
    samples = []
    for i in range(n):
        s = time.perf_counter()
        rt.solve_frame(tg, i, [x for x in SIDES if any(a <= i <= b for a, b in tg.stance[x])])
        samples.append((time.perf_counter() - s) * 1e3)
    total = time.perf_counter() - t0
    timing = Timing(np.array(samples))
    return Result("bvh-import", timing.median_ms, timing.p90_ms, base,
                  {"frames": n, "frames_per_s": n / total, "source": MOCAP.name})


CASES = [Case("motion-bake", _bake_case, "per frame of baking a 10 s two-figure motion, behaviors on, 30 fps"),
         Case("bvh-import", _import_case, "per frame of retargeting a CMU walk onto the standard male, 30 fps")]
