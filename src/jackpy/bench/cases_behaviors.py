"""Benchmark row ``behaviors-frame``: one full behavior frame (feet, balance, pelvis, torso, gaze,
two hands, springs, stepping watch) on the standard human during a scripted hand drag.

Baseline: none (the target is a median of at most 8 ms per frame).
"""

from __future__ import annotations

import numpy as np

from jackpy.bench.runner import Case, Result, time_calls


def _frame_case(quick: bool) -> Result:
    from jackpy.behaviors import BehaviorLoop
    from jackpy.behaviors import manipulation as m
    from jackpy.behaviors.anatomy import human_anatomy
    from jackpy.body.human import make_human

    figure = make_human("male", 50)
    a = human_anatomy(figure)
    loop = BehaviorLoop(figure, a)
    palms = {s: figure.site_world(*h.palm)[:3, 3].copy() for s, h in a.hands.items()}
    view = figure.site_world(*a.view)[:3, 3]
    m.move_eyes(loop, view + np.array([0.2, -0.3, 1.0]))
    k = [0]

    def frame() -> None:
        t = k[0] * 0.05
        k[0] += 1
        for s, sx in (("left", 1.0), ("right", -1.0)):
            m.move_hand(loop, s, position=palms[s] + np.array([0.05 * sx * np.sin(t), 0.15 + 0.1 * np.sin(t),
                                                               0.2 + 0.1 * np.cos(t)]))
        loop.step()

    timing = time_calls(frame, repeat=30 if quick else 200, warmup=3)
    return Result("behaviors-frame", timing.median_ms, timing.p90_ms, None,
                  {"dofs": figure.ndof, "target_median_ms": 8.0})


def _lean_case(quick: bool) -> Result:
    """Frames while a hand is dragged out of reach with ``lean`` (stepping off, so every timed frame
    leans): the drag runs 30 frames to 0.7 m beyond the arm, then holds there."""
    from jackpy.behaviors import BehaviorLoop
    from jackpy.behaviors import manipulation as m
    from jackpy.behaviors.anatomy import human_anatomy
    from jackpy.body.human import make_human

    figure = make_human("male", 50)
    a = human_anatomy(figure)
    loop = BehaviorLoop(figure, a)
    loop.behavior("stepping").enabled = False
    h = a.hands["right"]
    target = figure.site_world(*h.shoulder)[:3, 3] + np.array([0.0, -0.1, 1.3])
    palm = figure.site_world(*h.palm)[:3, 3].copy()
    k = [0]

    def frame() -> None:
        k[0] += 1
        u = min(1.0, k[0] / 30)
        m.move_hand(loop, "right", position=(1 - u) * palm + u * target, lean=True)
        loop.step()

    timing = time_calls(frame, repeat=40 if quick else 60, warmup=8)  # from the frame the lean starts
    return Result("behaviors-lean-frame", timing.median_ms, timing.p90_ms, None,
                  {"lean_deg": float(np.degrees(np.linalg.norm(loop.behavior("hands").lean))),
                   "target_median_ms": 15.0})


CASES = [Case("behaviors-frame", _frame_case, "full behavior frame on the standard human during a two-hand drag"),
         Case("behaviors-lean-frame", _lean_case, "behavior frame while a hand is dragged out of reach (lean)")]
