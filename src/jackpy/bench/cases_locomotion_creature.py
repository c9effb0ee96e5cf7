"""Benchmark row of creature locomotion.

- ``creature-walk``: per frame of walking the shipped hexapod 10 s over the rolling hills at 30 fps
  (body path, footstep planning with the forbidden raster, six-leg IK, forward kinematics);
  ``extra.frames_per_s``. Each sample is one whole walk's time over its frames (3 walks; quick: one
  2 s walk). Baseline: the six-leg IK alone (one :class:`LegSolver` solve of a frame's targets,
  warm from the frame before), so the ratio is the IK's share of a frame.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from jackpy.bench.runner import Case, Result, Timing

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "creatures"


def _walk_case(quick: bool) -> Result:
    from jackpy.locomotion.config import WalkConfig
    from jackpy.locomotion.creature_walk import walk
    from jackpy.locomotion.legs import LegSolver, find_legs
    from jackpy.locomotion.terrain import load
    from jackpy.peabody.reader import load as load_figures

    seconds, repeats = (2.0, 1) if quick else (10.0, 3)
    terrain = load(EXAMPLES / "rolling_hills.terrain.json")
    samples, frames = [], 0
    for _ in range(repeats):
        fig = load_figures(EXAMPLES / "hexapod.fig").figures["hexapod"]
        t0 = time.perf_counter()
        r = walk(fig, terrain, (0.0, 5.0), seconds=seconds, config=WalkConfig(fps=30.0))
        dt = time.perf_counter() - t0
        frames = len(r.postures)
        samples.append(dt / frames * 1e3)
    fig = load_figures(EXAMPLES / "hexapod.fig").figures["hexapod"]
    legs = find_legs(fig)
    solver = LegSolver(fig, legs)
    base = []
    for i in range(1, frames, max(1, frames // 60)):  # warm from the frame before, as in the walk
        fig.q = r.postures[i - 1].q
        fig.location = r.postures[i].location
        targets = list(r.feet[i])
        s = time.perf_counter()
        solver.solve(targets)
        base.append((time.perf_counter() - s) * 1e3)
    timing = Timing(np.array(samples))
    return Result("creature-walk", timing.median_ms, timing.p90_ms, float(np.median(base)),
                  {"frames": frames, "legs": 6, "frames_per_s": 1e3 / timing.median_ms, "motion_s": seconds})


CASES = [Case("creature-walk", _walk_case, "per frame of walking the hexapod 10 s over rolling hills, 30 fps")]
