"""The document's step under the frame loop's limits, checked by counting (no timing asserted)."""

from jackpy.document import Document
from jackpy.document.document import SolveLimits
from jackpy.document.effectors import find_effectors
from jackpy.ui.session import default_scene


def dragged_document() -> Document:
    env, _ = default_scene()
    doc = Document(env)
    fig = doc.figure_of_interest()
    g = doc.ensure_goal(fig, find_effectors(fig)["right_hand"], "position")
    m = g.manip.copy()
    m[:3, 3] += [0.2, 0.1, 0.1]
    doc.move_goal(g, m)
    return doc


def test_a_strict_zero_box_runs_one_cut_frame_and_keeps_solving():
    doc = dragged_document()
    loop = next(iter(doc.loops.values()))
    own = (loop.max_iterations, loop.max_passes)
    stats = doc.step(0.0, SolveLimits(0.0, iterations=4, passes=1))
    assert stats.solved and stats.iterations == 1 and stats.timed_out and doc.needs_solve
    assert doc.last_report.passes == 1
    assert stats.box_s == 0.0 and 0.0 <= stats.behaviors_s <= stats.solve_s
    assert (loop.max_iterations, loop.max_passes) == own  # the caps held for that step only


def test_without_limits_the_box_counts_whole_frames():
    doc = dragged_document()
    doc.settings.ik_time_budget_s = 0.0
    stats = doc.step(0.0)
    assert stats.solved and stats.iterations == 1 and not stats.timed_out
    assert not doc.last_report.timed_out  # the frame ran to its end
