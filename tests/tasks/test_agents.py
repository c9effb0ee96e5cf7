"""The same script for a 5th-percentile woman and a 95th-percentile man: different postures and
durations, both reported."""

import numpy as np
import pytest

from jackpy.tasks import commands as c
from jackpy.tasks.script import Script


def run(scene, sex, pct):
    s = Script()
    s.agent("Op", sex, pct, pace=1.5)
    s.add(c.LookAt("Op", "twf-3"))
    s.add(c.Turn("Op", "twf-3", state="2"))
    return s.run(scene)


@pytest.fixture(scope="module")
def both(panel_scene):
    return run(panel_scene, "female", 5), run(panel_scene, "male", 95)


def test_postures_and_durations_differ(both):
    small, large = both
    for r in (small, large):
        assert [x.status for x in r.reports] == ["done", "done"], [x.reason for x in r.reports]
        assert r.controls["ctrlpanel.twf_3"] == "2"
    qs, ql = small.loops["Op"].figure.q, large.loops["Op"].figure.q
    assert qs.shape == ql.shape and np.max(np.abs(qs - ql)) > np.radians(5)
    ds = [row.scaled_ms for row in small.rows]
    dl = [row.scaled_ms for row in large.rows]
    assert ds[0] != pytest.approx(dl[0]) and ds[1] != pytest.approx(dl[1])
    # same pace: the difference is the amplitudes of the bodies
    assert [row.pace for row in small.rows + large.rows] == [1.5] * (len(ds) + len(dl))
