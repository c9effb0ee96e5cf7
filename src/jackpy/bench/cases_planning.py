"""Reach-planning benchmarks (issue 16).

- ``reach-collision``: collision-aware point reach (arm mode) of every reach site of the shipped
  example workplace by the 50th-percentile male: the multi-start collision-free arm search with its
  verdict (judge built inside: two clearance checkers). Baseline: the same reaches ignoring the
  workplace (one IK each), so the ratio (below 1) is the price of respecting the workplace.
"""

from __future__ import annotations

from pathlib import Path

from jackpy.bench.runner import Case, Result, time_calls

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "workplace" / "workplace.json"


def _reach_collision_case(quick: bool) -> Result:
    from jackpy.analysis.reach import point_reach
    from jackpy.body.human import make_human
    from jackpy.scene.workplace import load_workplace, resolve_target, stand_figure

    wp = load_workplace(EXAMPLE)
    f = make_human("male", 50)
    stand_figure(f, wp.stand)
    objs = list(wp.objects.values())
    targets = [resolve_target(wp.env, ref) for ref in wp.plan.reach]
    verdicts: dict[str, str] = {}

    def aware() -> None:
        for ref, (obj, p) in zip(wp.plan.reach, targets):
            verdicts[ref] = point_reach(f, p, "right", obstacles=objs, target_object=obj.name).describe()

    def plain() -> None:
        for _, p in targets:
            point_reach(f, p, "right")

    t = time_calls(aware, repeat=1 if quick else 3, warmup=0)
    base = time_calls(plain, repeat=1 if quick else 3, warmup=0)
    return Result("reach-collision", t.median_ms, t.p90_ms, base.median_ms,
                  {"targets": len(targets), **verdicts})


CASES = [Case("reach-collision", _reach_collision_case,
              "collision-aware point reach of the example workplace's sites (male 50) vs the plain IK")]
