"""WalkTo (issue 13): the task layer walks an agent round the scene's objects to stand in front of
an object, as a walk motion on the timeline that plays back to the same place."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from jackpy.motion import cast
from jackpy.motion.bake import Baker
from jackpy.motion.kinds.walk import WalkMotion
from jackpy.tasks import commands as c
from jackpy.tasks.script import Script

PUT = Path(__file__).resolve().parents[2] / "examples" / "tasks" / "put" / "put.json"
#: the table's floor footprint (x0, z0, x1, z1), m
TABLE = (0.05, 0.15, 0.85, 0.75)


@pytest.fixture(scope="module")
def walked():
    s = Script(fps=10)
    s.agent("John", "male", 50, position=(1.5, -1.0), heading_deg=0)
    s.add(c.WalkTo("John", "table"), name="w")
    s.add(c.WalkTo("John", "nowhere"), name="bad", on_failure=[c.WalkTo("John", (1.5, -1.0), facing_deg=180.0)])
    return s.run(PUT)


def test_walk_to_an_object_stands_in_front_of_it_facing_it(walked):
    w = walked.report("w")
    assert w.status == "done" and w.checks["Walk to table: error_m"] < 0.05
    m = next(m for m in walked.timeline.motions if isinstance(m, WalkMotion) and m.label == "Walk to table")
    assert m.figure == "John" and m.t0 == pytest.approx(0.0) and w.end >= m.t1
    steps = m.plan["steps"]
    x, z = 0.5 * (np.array(steps[-1][:2]) + np.array(steps[-2][:2]))
    # in front of the table's near edge (z0), beyond the body's half-width, facing +z (toward it)
    assert TABLE[0] <= x <= TABLE[2]
    assert 0.25 < TABLE[1] - z < 0.4
    assert abs(steps[-1][2]) < np.radians(5.0)


def test_a_place_that_is_not_there_fails_with_the_reason_and_its_hook_runs(walked):
    bad = walked.report("bad")
    assert bad.status == "failed" and "nowhere" in bad.reason
    back = next(r for r in walked.reports if r.command.startswith("Walk to (1.5"))
    assert back.status == "done"
    fig = walked.loops["John"].figure
    c0 = fig.site_world("pelvis", "centre")[:3, 3]
    assert np.hypot(c0[0] - 1.5, c0[2] + 1.0) < 0.05


def test_the_task_timeline_plays_back_to_the_goal(walked):
    tl = walked.timeline
    m = next(m for m in tl.motions if m.label == "Walk to table")
    env, loops = cast.build(tl, PUT)
    baker = Baker(tl, loops, env, fps=10)
    end = baker.seek(baker.frame_at(m.t1) + 1)["John"]
    fig = env.figures["John"]
    end.apply_to(fig)
    c0 = fig.site_world("pelvis", "centre")[:3, 3]
    steps = m.plan["steps"]
    goal = 0.5 * (np.array(steps[-1][:2]) + np.array(steps[-2][:2]))
    assert np.hypot(c0[0] - goal[0], c0[2] - goal[1]) < 0.05
