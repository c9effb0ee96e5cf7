"""Benchmark row of human walking.

- ``walk-plan``: a 10 m walk of the standard male (2 m with ``--quick``) in the example
  workplace, from beside its desk away from it: the floor path around the workplace's objects
  (:func:`jackpy.locomotion.walk_to.walk_to`: obstacles, visibility graph, footsteps), the walk's
  targets and the bake at 30 fps; the median is per baked frame (targets + IK), ``extra`` has the
  planning time (path, footsteps and targets of every frame), the whole time and frames per
  second. Baseline: one behavior-loop frame of the same figure standing (the ratio: interactive
  frames per walk frame, inverted).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from jackpy.bench.runner import Case, Result, Timing, time_calls

WORKPLACE = Path(__file__).resolve().parents[3] / "examples" / "workplace" / "workplace.json"


def _walk_case(quick: bool) -> Result:
    from jackpy.locomotion import walk_path
    from jackpy.locomotion.walk_gait import GaitParams
    from jackpy.locomotion.walk_solve import WalkSolver
    from jackpy.locomotion.walk_to import walk_to
    from jackpy.motion import cast
    from jackpy.scene.workplace import load_workplace

    distance = 2.0 if quick else 10.0
    fig = cast.make_figure("jack", {"human": "male:50", "position": [0.0, -1.0], "heading_deg": 180.0})
    loop = cast.loop_for(cast.make_figure("ref", {"human": "male:50"}))
    base = time_calls(loop.step, repeat=20, warmup=0).median_ms
    objects = list(load_workplace(WORKPLACE).objects.values())
    t0 = time.perf_counter()
    p = GaitParams.for_figure(fig)
    steps, _, _ = walk_to(fig, p, (0.0, -1.0 - distance), objects, start=(0.0, -1.0))
    walk = walk_path.Walk(steps, p)
    frames = walk.frames(30.0)
    plan_ms = (time.perf_counter() - t0) * 1e3
    solver = WalkSolver(fig, p)
    samples = []
    for tg in frames:
        s = time.perf_counter()
        solver.pose(tg)
        samples.append((time.perf_counter() - s) * 1e3)
    total = time.perf_counter() - t0
    timing = Timing(np.array(samples))
    return Result("walk-plan", timing.median_ms, timing.p90_ms, base,
                  {"metres": distance, "steps": len(steps) - 2, "frames": len(frames), "plan_ms": plan_ms,
                   "total_s": total, "frames_per_s": len(frames) / total})


CASES = [Case("walk-plan", _walk_case, "footsteps, targets and IK bake of a 10 m walk (30 fps)")]
