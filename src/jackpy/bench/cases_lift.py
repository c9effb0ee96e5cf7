"""Strength-guided lifting benchmarks (issue 16, book §5.3).

- ``lift-30lb``: the book's overhead placement of 30 lb (13.6 kg) by the 50th-percentile male with
  pe 0.30, cl 0.50 (:func:`jackpy.planning.lifting.overhead_task`), the whole strength-guided path
  (spec §6.2 item 29 asks < 1 s on a 2-core machine; the book took < 10 s in 1991). Baseline: one
  plain IK reach from the same start to the same goal (the arm chain), so the ratio (below 1) is the
  price of a strength-guided path over a bare reach posture.
- ``lift-monitor``: one condition-monitor report (static torques, strengths, ratios and the hand
  Jacobian at a posture). Baseline: one forward kinematics pass of the same figure.
"""

from __future__ import annotations

import copy

from jackpy.bench.runner import Case, Result, time_calls


def _lift_case(quick: bool) -> Result:
    from jackpy import ik
    from jackpy.analysis.parts import figure_parts
    from jackpy.body.human import make_human
    from jackpy.planning.lifting import overhead_task, place_start, strength_guided_lift

    f = make_human("male", 50)
    task = overhead_task(f, 13.6078)
    out = {}

    def lift() -> None:
        out["r"] = strength_guided_lift(f, task)

    start = copy.deepcopy(f)
    place_start(start, task)
    h = figure_parts(start).hands["right"]

    def reach() -> None:
        g = copy.deepcopy(start)
        problem = ik.Problem(g)
        problem.add(ik.Position(f"{h.segment}.{h.site}", task.goal, chain=h.start_joint))
        problem.lock("right_wrist", "right_forearm")
        ik.solve(problem, max_iterations=200, tol_position=1e-4)

    t = time_calls(lift, repeat=1 if quick else 3, warmup=0)
    base = time_calls(reach, repeat=3 if quick else 10, warmup=1)
    r = out["r"]
    return Result("lift-30lb", t.median_ms, t.p90_ms, base.median_ms,
                  {"reached": r.reached, "steps": len(r.frames) - 1, "strategies": ", ".join(r.strategies_used()),
                   "mean_hand_shoulder_cm": round(float(r.horizontal_distance().mean()) * 100, 1),
                   "waist_deg": round(float(r.waist_motion()) * 57.29577951308232, 1)})


def _monitor_case(quick: bool) -> Result:
    import numpy as np

    from jackpy.body.human import make_human
    from jackpy.planning.lifting import arm_variables
    from jackpy.planning.lifting_monitor import LiftingMonitor

    f = make_human("male", 50)
    mon = LiftingMonitor(f, "right_palm", "grip", 13.6, ["right_shoulder", "right_elbow"] + f.groups["spine"].joints)
    x = mon.vmap.x()
    active = np.array(arm_variables(mon.vmap, "right"))
    kin = f.kinematics()
    t = time_calls(lambda: mon.state(x, active), repeat=50 if quick else 300)
    base = time_calls(lambda: kin.forward(f.q, f.location), repeat=50 if quick else 300)
    return Result("lift-monitor", t.median_ms, t.p90_ms, base.median_ms, {"monitored_dofs": len(mon.monitored)})


CASES = [Case("lift-30lb", _lift_case, "strength-guided overhead placement of 30 lb (male 50) vs one plain IK reach"),
         Case("lift-monitor", _monitor_case,
              "one condition-monitor report (torques, strengths, ratios) vs one FK pass")]
