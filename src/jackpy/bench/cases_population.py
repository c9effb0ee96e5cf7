"""Population sweep benchmark.

- ``sweep-throughput``: the example workplace's reach + view study (two reach targets, two view
  targets) over Monte Carlo bodies (skeleton-only figures built from parameters in the workers).
  ``median_ms``: wall time per body on a local pool of 2 workers; baseline: the same bodies
  evaluated one after another in this process. Extra: bodies per second per worker with 1 and 2
  workers, the speed-up of 2 workers over 1 in the same run (pool start-up included; the
  calibration and the mean bodies' reach solutions are done before timing, as a sweep does them
  once), and bodies per CPU-second of the serial run (process time: what one free core would do,
  whatever else loads the machine).
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from jackpy.bench.runner import Case, Result

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "workplace"


def _context():
    from jackpy.population.evaluate import SweepContext
    from jackpy.population.study import load_study
    from jackpy.scene.workplace import load_workplace

    return SweepContext(load_workplace(EXAMPLE / "workplace.json"), load_study(EXAMPLE / "study.json")).prepare()


def _sweep_case(quick: bool) -> Result:
    from jackpy.population.evaluate import evaluate_body
    from jackpy.population.run import population_bodies
    from jackpy.population.sweep import run_sweep

    n = 16 if quick else 64
    repeat = 1 if quick else 3
    bodies = population_bodies(n, sex_mix=0.5, seed=1)
    ctx = _context()

    def pool(workers: int) -> float:
        with tempfile.TemporaryDirectory() as tmp:
            t0 = time.perf_counter()
            run_sweep(ctx, bodies, tmp, workers=workers, progress=False)
            return time.perf_counter() - t0

    one = [pool(1) for _ in range(repeat)]
    two = [pool(2) for _ in range(repeat)]
    t0, c0 = time.perf_counter(), time.process_time()
    for b in bodies:
        evaluate_body(ctx, b)
    serial, cpu = time.perf_counter() - t0, time.process_time() - c0
    t1, t2 = float(np.median(one)), float(np.median(two))
    return Result("sweep-throughput", 1e3 * t2 / n, 1e3 * max(two) / n, 1e3 * serial / n,
                  {"bodies": n, "bodies_per_s_per_worker_1": n / t1, "bodies_per_s_per_worker_2": n / (2 * t2),
                   "speedup_2_vs_1": t1 / t2, "bodies_per_cpu_s": n / cpu, "goal_per_core": 20, "study": "reach x2 + view x2",
                   "baseline": "same bodies serially in-process"})


CASES = [Case("sweep-throughput", _sweep_case,
              "example workplace reach + view study: bodies/s per worker, 2 workers vs 1")]
