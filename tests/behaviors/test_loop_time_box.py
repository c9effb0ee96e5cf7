"""The behavior loop's time box, checked by counting what the loop does (no timing asserted)."""

import time

import numpy as np
import jackpy.behaviors.loop as loop_module
from jackpy.behaviors import BehaviorLoop, manipulation
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.body.human import make_human


def reaching_loop():
    fig = make_human("male", 50)
    loop = BehaviorLoop(fig, human_anatomy(fig))
    palm = fig.site_world(*human_anatomy(fig).hands["right"].palm)
    manipulation.move_hand(loop, "right", position=palm[:3, 3] + [0.25, 0.15, 0.2])
    return loop


def spy_solves(monkeypatch):
    calls = []
    real = loop_module.solve

    def solve(problem, **kw):
        result = real(problem, **kw)
        calls.append((kw.get("time_budget_s"), result.status, kw.get("max_iterations")))
        return result

    monkeypatch.setattr(loop_module, "solve", solve)
    return calls


def test_a_passed_deadline_ends_the_com_loop_after_its_first_pass(monkeypatch):
    calls = spy_solves(monkeypatch)
    loop = reaching_loop()
    fig, palm = loop.figure, human_anatomy(loop.figure).hands["right"].palm
    goal = loop.state.hands["right"].goal[:3, 3]
    before = np.linalg.norm(fig.site_world(*palm)[:3, 3] - goal)
    report = loop.step(deadline=time.perf_counter() - 1.0)
    assert report.passes == 1 and report.timed_out
    body, limbs = calls  # one body pass, then the limbs pass (head and arms in one solve)
    assert body[0] == 0.0 and body[1] in ("time_limit", "achieved")
    # the limbs get their counted floor, unboxed, so the dragged hand moves even in a spent box
    assert limbs[0] is None and limbs[2] == loop_module.LIMB_FLOOR_ITERATIONS
    assert np.linalg.norm(fig.site_world(*palm)[:3, 3] - goal) < before


def test_without_a_deadline_no_solve_gets_a_budget_and_nothing_times_out(monkeypatch):
    calls = spy_solves(monkeypatch)
    loop = reaching_loop()
    report = loop.step()
    assert calls and all(b is None for b, _, _ in calls)
    assert not report.timed_out and "time_limit" not in {s for _, s, _ in calls}


def test_the_time_box_attribute_bounds_every_step(monkeypatch):
    calls = spy_solves(monkeypatch)
    loop = reaching_loop()
    loop.time_box_s = 0.0
    reports = [loop.step() for _ in range(3)]
    assert all(r.passes == 1 and r.timed_out for r in reports)
    # every body pass boxed; limbs passes left nothing run their counted floor
    assert all(b is not None or it == loop_module.LIMB_FLOOR_ITERATIONS for b, _, it in calls)
    assert any(b is not None for b, _, _ in calls)
    assert np.all(loop.figure.q >= loop.figure.lower - 1e-9) and np.all(loop.figure.q <= loop.figure.upper + 1e-9)
