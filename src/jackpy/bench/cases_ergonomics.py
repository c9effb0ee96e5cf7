"""Ergonomics benchmark: the live assessments of one workbench frame.

- ``ergonomics-frame``: RULA + REBA + the L5/S1 low-back load of the 50th-percentile male, the
  right arm and the trunk in a new posture every call (50 postures posed before timing, as while
  dragging), given the frame's forward pass (the workbench has it: FK runs before the analyses),
  one posture measurement shared by the three (:func:`jackpy.ergonomics.assess`). Target: 2 ms;
  extra ``with_fk_ms``: the same with its own forward pass. Baseline: the three methods called one
  at a time, each with its own forward pass and posture measurement.
"""

from __future__ import annotations

import numpy as np

from jackpy.bench.runner import Case, Result, time_calls

TARGET_MS = 2.0


def _frame_case(quick: bool) -> Result:
    from jackpy.body import make_human
    from jackpy.ergonomics import Task, assess
    from jackpy.ergonomics.base import method
    from jackpy.ergonomics.posture import measure

    f = make_human("male", 50)
    task = Task(load_kg=8.0)
    names = ["rula", "reba", "lowback"]
    arm = f.groups["right_shoulder_complex"]
    spine = f.groups["spine"]
    kin = f.kinematics()
    poses = []
    for k in range(50):
        arm.set_angles(f, np.radians([30.0 + 2.5 * k, 90.0, 0.0]))
        spine.set_angles(f, np.radians([0.8 * k, 0.0, 5.0]))
        poses.append((f.q, kin.forward(f.q, f.location)))
    step = {"i": 0}

    def next_pose():
        step["i"] = (step["i"] + 1) % len(poses)
        q, fk = poses[step["i"]]
        return q, fk

    holder: dict = {}

    def ours() -> None:
        holder["r"] = assess(f, names, task, fk=next_pose()[1])

    def with_fk() -> None:
        q, _ = next_pose()
        assess(f, names, task, fk=kin.forward(q, f.location))

    def separate() -> None:
        q, _ = next_pose()
        for n in names:
            fk = kin.forward(q, f.location)
            method(n).assess(f, task, measure(f, fk), fk)

    repeat = 100 if quick else 500
    t = time_calls(ours, repeat=repeat, warmup=10)
    w = time_calls(with_fk, repeat=repeat, warmup=10)
    b = time_calls(separate, repeat=repeat, warmup=10)
    r = holder["r"]
    return Result("ergonomics-frame", t.median_ms, t.p90_ms, b.median_ms,
                  {"target_ms": TARGET_MS, "within_target": t.median_ms <= TARGET_MS, "with_fk_ms": w.median_ms,
                   "rula": r["rula"].score, "reba": r["reba"].score,
                   "lowback_N": round(float(r["lowback"].score)),
                   "baseline": "the three methods one at a time, each with its own FK and measurement"})


CASES = [Case("ergonomics-frame", _frame_case, "RULA + REBA + L5/S1 low back per frame on the standard human (<= 2 ms)")]
