"""Yaps scheduling: sequential by default, together(), After with a delay, With, explicit
durations, hooks, failures with reasons (a place that is not there)."""

import pytest

from jackpy.tasks import commands as c
from jackpy.tasks.schedule import After, With
from jackpy.tasks.script import Script


@pytest.fixture(scope="module")
def result(panel_scene):
    s = Script(fps=10)
    s.agent("John", "male", 50)
    s.agent("Jane", "female", 50)
    s.add(c.LookAt("John", "twf-1"), name="a", duration=0.4)
    with s.together():
        s.add(c.LookAt("John", "twf-2"), name="b", duration=0.5)
        s.add(c.LookAt("Jane", "twf-3"), name="c", duration=0.3)
    s.add(c.LookAt("Jane", "twf-2"), name="d", start=After("a", delay=0.25), duration=0.3)
    s.add(c.LookAt("John", "Jane"), name="e", start=With("d"), duration=0.3)
    s.add(c.WalkTo("Jane", "door"), name="w", on_failure=[c.LookAt("Jane", "John")],
          on_success=[c.LookAt("Jane", "twf-1")])
    return s.run(panel_scene)


def test_times(result):
    r = {x.name: x for x in result.reports}
    assert r["a"].start == 0.0
    # a look ends when the eyes are on the target: the explicit duration plus any settling frames
    assert 0.4 - 1e-9 <= r["a"].end <= 0.4 + 0.1 * 10
    assert r["b"].start == pytest.approx(r["a"].end) and r["c"].start == pytest.approx(r["a"].end)
    assert r["d"].start == pytest.approx(r["a"].end + 0.25)
    assert r["e"].start == pytest.approx(r["d"].start)
    assert r["w"].start == pytest.approx(r["e"].end)  # sequential: after the entry before it
    spans = {m.label + m.figure: round(m.t1 - m.t0, 9) for m in result.timeline.motions}
    assert spans["Look twf-1John"] == 0.4 and spans["Look twf-2John"] == 0.5 and spans["Look twf-3Jane"] == 0.3


def test_failure_reason_and_hooks(result):
    r = {x.name: x for x in result.reports}
    w = r["w"]
    assert w.status == "failed" and "nothing in the scene is called 'door'" in w.reason
    hooks = [x for x in result.reports if x.command == "Look John"]
    assert len(hooks) == 1 and hooks[0].status == "done"
    assert not any(x.command == "Look twf-1" and x.start > 0 for x in result.reports)
