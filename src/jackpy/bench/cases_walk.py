"""Benchmark row of human walking.

- ``walk-plan``: a 10 m walk of the standard male (2 m with ``--quick``) in the example
  workplace, from beside its desk away from it: the floor path around the workplace's objects
  (:func:`jackpy.locomotion.walk_to.walk_to`: obstacles, visibility graph, footsteps), the walk's
  targets and the bake at 30 fps; the median is per baked frame (targets + IK), ``extra`` has the
  planning time (path, footsteps and targets of every frame), the whole time and frames per
  second. Baseline: one behavior-loop frame of the same figure standing (the ratio: interactive
  frames per walk frame, inverted).
- ``walk-timeline``: the same walk (4 m with ``--quick``) as a walk motion on a timeline, baked by
  :class:`jackpy.motion.bake.Baker` at 30 fps (timeline step, the walk's IK, the behavior loop
  with its behaviors suspended, checkpoints); the median is per baked frame. Baseline: the same
  frames' targets and postures by the walk alone (the ratio is the timeline's overhead).
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


def _timeline_case(quick: bool) -> Result:
    from jackpy.locomotion import footsteps, walk_path
    from jackpy.locomotion.walk_gait import GaitParams
    from jackpy.locomotion.walk_solve import WalkSolver
    from jackpy.motion import cast
    from jackpy.motion.bake import Baker
    from jackpy.motion.kinds.walk import WalkMotion
    from jackpy.motion.timeline import Timeline

    distance = 4.0 if quick else 10.0
    ref = cast.make_figure("ref", {"human": "male:50"})
    p = GaitParams.for_figure(ref)
    steps = footsteps.straight(p, distance)
    solver = WalkSolver(ref, p)
    walk, alone = walk_path.Walk(steps, p), []
    for i in range(int(np.floor(walk.duration * 30.0 + 1e-9)) + 1):
        s = time.perf_counter()
        solver.pose(walk.at(i / 30.0))
        alone.append((time.perf_counter() - s) * 1e3)
    tl = Timeline(cast={"jack": {"human": "male:50"}})
    env, loops = cast.build(tl)
    tl.add(WalkMotion.of_steps("jack", steps, p))
    baker = Baker(tl, loops, env, fps=30.0)
    samples = []
    for _ in range(baker.n_frames):
        s = time.perf_counter()
        baker._step()
        samples.append((time.perf_counter() - s) * 1e3)
    timing = Timing(np.array(samples))
    return Result("walk-timeline", timing.median_ms, timing.p90_ms, float(np.median(alone)),
                  {"metres": distance, "frames": len(samples)})


CASES = [Case("walk-plan", _walk_case, "footsteps, targets and IK bake of a 10 m walk (30 fps)"),
         Case("walk-timeline", _timeline_case, "a 10 m walk as a walk motion baked on the timeline (30 fps)")]
