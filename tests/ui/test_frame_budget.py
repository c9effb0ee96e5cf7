"""The frame budget's decisions, from given frame costs (no clock): the box, the quality ladder."""

import pytest

from jackpy.ui.frame_budget import (
    LADDER,
    OVERRUN,
    RECOVER_FRACTION,
    RECOVER_FRACTION_SOLVING,
    RECOVER_FRAMES,
    SETTLE_FRAMES,
    FrameBudget,
)

DOC_BOX = 0.030


def run(fb: FrameBudget, frames: int, period: float, solve: float, behaviors: float = 0.0) -> None:
    for _ in range(frames):
        plan = fb.plan(DOC_BOX)
        fb.record(period, solve, plan.box_s, True, True, behaviors)


def test_the_box_is_what_the_target_period_leaves_besides_the_frames_other_costs():
    fb = FrameBudget(30.0, adaptive=True)
    run(fb, 5, period=0.025, solve=0.010)  # 15 ms besides the solve
    plan = fb.plan(DOC_BOX)
    assert plan.box_s == plan.limits.box_s == pytest.approx(1 / 30 - 0.015 - 0.001, abs=1e-9)
    assert plan.level == 0 and plan.render_scale == 1.0 and plan.limits.iterations is None


def test_the_box_never_exceeds_the_documents_nor_falls_below_the_floor():
    fb = FrameBudget(30.0, min_box_s=0.010, adaptive=True)
    run(fb, 3, period=0.004, solve=0.001)
    assert fb.plan(0.020).box_s == 0.020
    fb = FrameBudget(30.0, min_box_s=0.010, adaptive=True)
    run(fb, 1, period=0.060, solve=0.010)
    assert fb.plan(DOC_BOX).box_s == 0.010
    fb = FrameBudget(30.0, min_box_s=0.010, adaptive=True)  # the behaviors' own work: 8 ms
    run(fb, 6, period=0.030, solve=0.016, behaviors=0.008)
    assert fb.plan(DOC_BOX).box_s >= 0.016 - 1e-3


def test_frames_over_budget_step_the_quality_down_one_rung_at_a_time():
    fb = FrameBudget(30.0, adaptive=True)
    seen = [fb.plan(DOC_BOX)]
    for _ in range(len(LADDER) * SETTLE_FRAMES + 2):
        run(fb, 1, period=0.080, solve=0.010)  # the draw alone takes 70 ms
        seen.append(fb.plan(DOC_BOX))
    levels = [p.level for p in seen]
    assert levels[-1] == len(LADDER) - 1
    assert all(b - a in (0, 1) for a, b in zip(levels, levels[1:]))  # one rung per change
    changes = [k for k, (a, b) in enumerate(zip(levels, levels[1:])) if b != a]
    assert all(b - a >= SETTLE_FRAMES for a, b in zip(changes, changes[1:]))  # the estimates see each
    full, cheapest = seen[0], seen[-1]
    assert cheapest.render_scale < full.render_scale and cheapest.limits.iterations < 30
    assert cheapest.limits.passes < 3
    for a, b in zip(LADDER, LADDER[1:]):  # each rung is no dearer in any respect
        assert b.render_scale <= a.render_scale
        assert (b.iterations or 99) <= (a.iterations or 99) and (b.passes or 9) <= (a.passes or 9)


def test_calm_frames_step_the_quality_back_up():
    fb = FrameBudget(30.0, adaptive=True)
    run(fb, len(LADDER) * SETTLE_FRAMES + 2, period=0.080, solve=0.010)
    low = fb.level
    assert low == len(LADDER) - 1
    run(fb, RECOVER_FRAMES - 1, period=0.010, solve=0.004)
    assert fb.level == low
    run(fb, 1, period=0.010, solve=0.004)
    assert fb.level == low - 1
    run(fb, RECOVER_FRAMES * low, period=0.010, solve=0.004)
    assert fb.level == 0


def test_a_frame_that_neither_solved_nor_drew_measures_nothing():
    fb = FrameBudget(30.0, adaptive=True)
    run(fb, 3, period=0.020, solve=0.005)
    other = fb.other_s
    fb.record(0.250, 0.0, DOC_BOX, solved=False, drawn=False)  # the window slept on input
    assert fb.other_s == other and fb.level == 0


def test_overruns_count_solves_past_their_box_by_more_than_the_promise():
    fb = FrameBudget(30.0, adaptive=True)
    fb.record(0.03, OVERRUN * 0.010 * 0.99, 0.010, True)
    fb.record(0.03, 0.010, 0.010, False)  # no solve: nothing to count
    assert fb.overruns == 0 and fb.solves == 1
    fb.record(0.03, OVERRUN * 0.010 * 1.01, 0.010, True)
    assert fb.overruns == 1 and fb.solves == 2
    assert fb.worst_overrun == pytest.approx(OVERRUN * 1.01)
    assert "1 over" in fb.describe()


def test_without_adaptation_the_frame_loop_is_the_documents_own():
    fb = FrameBudget(30.0)
    assert not fb.adaptive
    run_plan = fb.plan(DOC_BOX)
    for _ in range(20):
        fb.record(0.200, 0.050, DOC_BOX, True)
    plan = fb.plan(DOC_BOX)
    assert run_plan.limits is None and plan.limits is None and plan.render_scale == 1.0 and plan.level == 0


def test_a_bad_target_is_refused():
    with pytest.raises(ValueError):
        FrameBudget(0.0)


def test_the_app_applies_the_plan_and_restores_the_loops_own_caps():
    """An App whose budget sits on the cheapest rung: its step solves with that rung's caps and a
    strict box, then the loops have their own settings back."""
    from jackpy.document.effectors import find_effectors
    from jackpy.ui.app import App
    from jackpy.ui.session import default_scene

    env, _ = default_scene()
    app = App(env, size=(640, 480))
    fb = app.frame_budget
    fb.adaptive, fb.level = True, len(LADDER) - 1
    fig = app.figure_of_interest()
    loop = app.loops[fig.name]
    own = (loop.max_iterations, loop.max_passes)
    seen = []
    step = loop.step

    def spy(deadline=None):
        seen.append((loop.max_iterations, loop.max_passes, deadline))
        return step(deadline=deadline)

    loop.step = spy
    g = app.ensure_goal(fig, find_effectors(fig)["right_hand"], "position")
    m = g.manip.copy()
    m[0, 3] += 0.1
    app.doc.move_goal(g, m)
    stats = app.step()
    assert stats.solved and seen and stats.level == len(LADDER) - 1
    q = LADDER[-1]
    assert all(it == q.iterations and ps == q.passes and d is not None for it, ps, d in seen)
    assert (loop.max_iterations, loop.max_passes) == own
    assert stats.box_s == pytest.approx(fb.box_s)


def test_the_last_rung_solves_one_frame_in_two_the_others_every_frame():
    fb = FrameBudget(30.0, adaptive=True)
    assert LADDER[-1].solve_every == 2 and all(q.solve_every == 1 for q in LADDER[:-1])
    assert [fb.plan(DOC_BOX).solve for _ in range(4)] == [True] * 4
    fb.level = len(LADDER) - 1
    assert [fb.plan(DOC_BOX).solve for _ in range(6)] == [False, True] * 3  # the last one solved
    assert FrameBudget(30.0).plan(DOC_BOX).solve  # without adaptation: always


def test_on_the_last_rung_a_drag_solves_every_other_frame_and_settles_on_every_frame():
    from jackpy.document.effectors import find_effectors
    from jackpy.ui.app import App, GoalTarget
    from jackpy.ui.session import default_scene

    env, _ = default_scene()
    app = App(env, size=(640, 480))
    fb = app.frame_budget
    fb.adaptive, fb.level = True, len(LADDER) - 1
    fb.record = lambda *a, **k: None  # hold the rung: this test is about the frame, not the ladder
    fig = app.figure_of_interest()
    g = app.ensure_goal(fig, find_effectors(fig)["right_hand"], "position")
    app.manipulator.attach(GoalTarget(app, g))
    app.manipulator.set_buttons({"left"}, False, False, app.ray(320, 240))
    assert app.manipulator.active
    solved, pending = [], []
    for _ in range(5):
        m = g.manip.copy()
        m[0, 3] += 0.02
        app.doc.move_goal(g, m)  # as the drag does, every frame
        solved.append(app.step().solved)
        pending.append(app.doc.needs_solve)
    assert solved == [True, False, True, False, True]
    assert all(pending[1::2])  # a frame between solves leaves the goal's move to the next one
    app.manipulator.set_buttons(set(), False, False, app.ray(320, 240))  # released
    m = g.manip.copy()
    m[0, 3] += 0.02
    app.doc.move_goal(g, m)
    assert not app.manipulator.active and app.doc.needs_solve
    assert app.step().solved  # the frame after a solving one: no drag, so it solves


def test_the_last_rung_steps_up_when_its_solving_frames_would_fit_every_frame():
    """On the last rung a drag alternates a solving frame (24 ms) and a draw-only frame (14 ms) at
    a 33 ms target: the rung above solves every frame at the same caps, so its frames would take
    24 ms; the budget goes up although every other frame is over RECOVER_FRACTION of the target.
    Solving frames over RECOVER_FRACTION_SOLVING keep it down."""
    target = 1 / 30
    assert LADDER[-2].iterations == LADDER[-1].iterations and LADDER[-2].passes == LADDER[-1].passes
    assert LADDER[-2].render_scale == LADDER[-1].render_scale and LADDER[-2].solve_every == 1

    def drag(fb: FrameBudget, frames: int, solving: float, drawing: float = 0.014) -> None:
        for _ in range(frames):
            plan = fb.plan(DOC_BOX)
            if plan.solve:
                fb.record(solving, 0.010, plan.box_s, True, True)
            else:
                fb.record(drawing, 0.0, plan.box_s, False, True)

    for solving, up in ((0.024, True), (RECOVER_FRACTION_SOLVING * target + 0.002, False)):
        assert RECOVER_FRACTION * target < solving
        fb = FrameBudget(30.0, adaptive=True)
        fb.level = len(LADDER) - 1
        drag(fb, 2 * RECOVER_FRAMES - 2, solving)  # RECOVER_FRAMES - 1 solving frames
        assert fb.level == len(LADDER) - 1
        drag(fb, 2, solving)
        assert (fb.level == len(LADDER) - 2) == up
        if up:  # and the rung above, solving every frame in 24 ms, stays
            run(fb, 3 * RECOVER_FRAMES, period=0.024, solve=0.010)
            assert fb.level == len(LADDER) - 2


def test_a_restarted_frame_clock_keeps_a_gap_out_of_the_budget():
    """Time the App did not spend on its own frames (another App's, a blocking dialog) is not a
    frame: after ``restart_frame_clock`` the next step's period counts from the restart."""
    import time

    from jackpy.document.effectors import find_effectors
    from jackpy.ui.app import App
    from jackpy.ui.session import default_scene

    gap = 0.5
    others = []
    for restart in (False, True):
        env, _ = default_scene()
        app = App(env, size=(320, 240))
        app.frame_budget.adaptive = True
        fig = app.figure_of_interest()
        g = app.ensure_goal(fig, find_effectors(fig)["right_hand"], "position")

        def solving_step() -> None:  # a frame that solves is a frame the budget measures
            m = g.manip.copy()
            m[0, 3] += 0.005
            app.doc.move_goal(g, m)
            app.step()

        solving_step()
        solving_step()
        time.sleep(gap)
        if restart:
            app.restart_frame_clock()
        solving_step()  # records the period that ended here: the gap's, or from the restart
        others.append(app.frame_budget.other_s)
    assert others[0] >= gap > others[1]


def test_the_last_rung_stays_while_the_smallest_box_is_squeezed_out():
    """Solving frames under RECOVER_FRACTION_SOLVING of the target, but the frame's other costs plus
    the smallest box (twice the behaviors' own work) leave no room for a solve on every frame: the
    rung above would step straight back down, so the budget stays."""
    fb = FrameBudget(30.0, adaptive=True)
    fb.level = len(LADDER) - 1
    for _ in range(3 * RECOVER_FRAMES):
        plan = fb.plan(DOC_BOX)
        if plan.solve:  # 20 ms frames, 12 ms of them the behaviors: the smallest box is 24 ms
            fb.record(0.020, 0.014, plan.box_s, True, True, behaviors_s=0.012)
        else:  # 14 ms of drawing: the other costs (>= 11 ms) + 24 + 1 > 33.3
            fb.record(0.014, 0.0, plan.box_s, False, True)
    assert 0.020 < RECOVER_FRACTION_SOLVING / 30.0 and fb.level == len(LADDER) - 1
