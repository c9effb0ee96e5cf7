"""The motion file: round trip to the bit, errors with file:line:col or key path, fuzzed input."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from jackpy.errors import ParseError
from jackpy.motion import motion_file
from jackpy.motion.keyframes import KeyTrack
from jackpy.motion.kinds.com import COMMotion
from jackpy.motion.kinds.foot import FootMotion
from jackpy.motion.timed import TimedBehavior
from jackpy.motion.timeline import Timeline


def small_timeline() -> Timeline:
    tl = Timeline([COMMotion(figure="jack", t0=0.0, t1=0.3, x=0.3, weight_fn="ease"),
                   FootMotion(figure="jack", side="right", t0=0.3, t1=0.6, displacement=[0, 0, 0.2], height=0.1)],
                  [TimedBehavior("jack", "torso", "hold", 0.1, 0.4)],
                  [KeyTrack("jack", "head", [(0.0, [0, 1.6, 2]), (0.6, [1, 1.6, 2])], "cubic")],
                  cast={"jack": {"human": "female:5", "position": [0.5, 0.0], "heading_deg": 10.0}})
    return tl


def test_timeline_round_trip():
    tl = small_timeline()
    again = Timeline.from_dict(json.loads(json.dumps(tl.to_dict())))
    assert again.to_dict() == tl.to_dict()
    assert again.duration == tl.duration == 0.6


def test_baked_file_round_trip_to_the_bit(tmp_path):
    from jackpy.commands.motion import bake_motion_file

    mf, _, _ = bake_motion_file(motion_file.MotionFile(small_timeline()), None, 20.0)
    path = tmp_path / "walk.motion.json"
    motion_file.save(mf, path)
    back = motion_file.load(path)
    assert back.fps == 20.0 and back.n_frames == 13
    a, b = mf.baked["jack"], back.baked["jack"]
    assert a.dofs == b.dofs and a.roots == b.roots and a.human == "female:5"
    assert np.array_equal(a.q, b.q) and np.array_equal(a.location, b.location) and np.array_equal(a.root, b.root)
    assert not list(tmp_path.glob("*.tmp*"))


def write(tmp_path, text):
    p = tmp_path / "bad.motion.json"
    p.write_text(text)
    return p


def test_syntax_error_has_line_and_column(tmp_path):
    p = write(tmp_path, '{"jackpy_motion": 1,\n "timeline": {"motions": [}\n}')
    with pytest.raises(ParseError, match=r"bad\.motion\.json:2:27"):
        motion_file.load(p)


@pytest.mark.parametrize("timeline,where", [
    ({"motions": [{"kind": "foot", "figure": "jack", "side": "middle"}]}, "timeline.motions[0]: foot motion: side"),
    ({"motions": [{"kind": "fly"}]}, "timeline.motions[0].kind: expected one of"),
    ({"motions": [{"kind": "com", "figure": "jack", "t0": "soon"}]}, "timeline.motions[0].t0: expected a number"),
    ({"motions": [{"kind": "com", "figure": "jack", "speed": 3}]}, "timeline.motions[0].speed: unknown field"),
    ({"timed": [{"figure": "jack", "control": "torso", "value": "hold", "t0": 2, "t1": 1}]}, "timeline.timed[0]"),
    ({"keyframes": [{"figure": "jack", "part": "pelvis", "keys": [{"t": 0, "value": [1, 2]}]}]},
     "timeline.keyframes[0].keys[0].value"),
    ({"figures": {"jack": {"position": [1]}}}, "timeline.figures.jack.position"),
])
def test_schema_errors_name_the_key_path(tmp_path, timeline, where):
    p = write(tmp_path, json.dumps({"jackpy_motion": 1, "timeline": timeline}))
    with pytest.raises(ParseError) as exc:
        motion_file.load(p)
    assert str(exc.value).startswith(f"{p}: {where}")


def test_baked_section_is_checked(tmp_path):
    bad = {"jackpy_motion": 1, "baked": {"fps": 30, "frames": 2, "figures": {"jack": {
        "dofs": ["a.0"], "roots": ["pelvis.centre"], "root": [0, 0], "location": [[0] * 16, [0] * 16],
        "q": [[0.1], ["x"]]}}}}
    with pytest.raises(ParseError, match=r"baked\.figures\.jack\.q\[1\]\[0\]: expected a number"):
        motion_file.load(write(tmp_path, json.dumps(bad)))
    with pytest.raises(ParseError, match="not a jackpy motion file|expected 1"):
        motion_file.load(write(tmp_path, json.dumps({"jackpy_scene": 1})))


json_values = st.recursive(st.none() | st.booleans() | st.floats(allow_nan=False) | st.integers() | st.text(max_size=5),
                           lambda c: st.lists(c, max_size=4) | st.dictionaries(st.text(max_size=6), c, max_size=4),
                           max_leaves=20)
keys = st.sampled_from(["motions", "timed", "keyframes", "figures", "duration", "span"])


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(timeline=st.dictionaries(keys, json_values, max_size=4), kind=st.sampled_from(["com", "foot", "arm", "heel"]),
       motion=st.dictionaries(st.sampled_from(["figure", "t0", "t1", "side", "x", "height", "target", "weight"]),
                              json_values, max_size=5))
def test_fuzzed_files_give_only_parse_errors(tmp_path, timeline, kind, motion):
    timeline = dict(timeline)
    timeline["motions"] = [{"kind": kind, **motion}]
    p = write(tmp_path, json.dumps({"jackpy_motion": 1, "timeline": timeline}))
    try:
        motion_file.load(p)
    except ParseError as exc:
        assert str(exc).startswith(str(p))
