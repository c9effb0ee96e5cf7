"""BVH reading: the public files' conventions, errors with file:line:col, fuzzed input."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from jackpy.errors import ParseError
from jackpy.motion.bvh import BVHJoint, format_bvh, parse, read

MOCAP = Path(__file__).resolve().parents[3] / "shared" / "data" / "mocap"
if not MOCAP.exists():
    MOCAP = Path("/work/shared/data/mocap")

SMALL = """HIERARCHY
ROOT Hips
{
\tOFFSET 0 0 0
\tCHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation 
\tJOINT Leg
\t{
\t\tOFFSET 0 -10 0
\t\tCHANNELS 3 Zrotation Xrotation Yrotation
\t\tEnd Site
\t\t{
\t\t\tOFFSET 0 -5 0
\t\t}
\t}
}
MOTION
Frames:\t2
Frame Time: .0333333
0 100 0 0 0 0 90 0 0
1.5 100 -0.0000 0 90 0 0 0 0
"""


def test_small_file_forward_kinematics():
    b = parse(SMALL, "small.bvh")
    assert b.names == ["Hips", "Leg"] and b.fps == pytest.approx(30.0, rel=1e-4)
    assert b.joints[0].rotation_order == "ZYX" and b.joints[1].rotation_order == "ZXY"
    wr, wp = b.world()
    assert np.allclose(wp[0, 1], [0, 90, 0]) and np.allclose(wp[1, 1], [1.5, 90, 0])
    assert np.allclose(wr[0, 1] @ [0, -5, 0], [5, 0, 0])  # Leg's Rz(90) takes -y to +x
    assert np.allclose(wr[1, 0] @ [1, 0, 0], [0, 0, -1])  # the root's Ry(90) takes +x to -z


def test_every_public_file_reads():
    files = sorted(MOCAP.glob("*.bvh"))
    assert len(files) == 6
    counts = {f.name: read(str(f)).frames.shape for f in files}
    assert counts["cmu_02_01_walk.bvh"] == (344, 96)
    assert counts["bandai2_walk-turn-left_normal_001.bvh"] == (102, 132)


def test_bandai_position_channels_replace_the_offset():
    b = read(str(MOCAP / "bandai2_walk-turn-left_normal_001.bvh"))
    _, wp = b.world(b.frames[:1])
    thigh = np.linalg.norm(wp[0, b.index("LowerLeg_L")] - wp[0, b.index("UpperLeg_L")])
    assert 35 < thigh < 50  # cm: one thigh, not two


@pytest.mark.parametrize("text,where,msg", [
    (SMALL.replace("OFFSET 0 -10 0", "OFFSET 0 x 0"), (8, 12), "expected a number"),
    (SMALL.replace("Zrotation Xrotation Yrotation", "Zrotation Xrotation Wrotation"), (9, 34), "unknown channel"),
    (SMALL.replace("Frames:\t2", "Frames:\t3"), (20, 1), "expected 3 frames"),
    (SMALL.replace("1.5 100 -0.0000 0 90 0 0 0 0", "1.5 100 -0.0000 0 90 0 0 0"), (20, 1), "expected 9 numbers"),
    (SMALL.replace("0 100 0 0 0 0 90 0 0", "0 100 0 0 0 0 nine 0 0"), (19, 15), "expected a number"),
    (SMALL.replace("MOTION\n", ""), None, "expected"),
])
def test_errors_name_line_and_column(text, where, msg):
    with pytest.raises(ParseError, match=msg) as exc:
        parse(text, "bad.bvh")
    if where is not None:
        assert str(exc.value).startswith(f"bad.bvh:{where[0]}:{where[1]}:")


def test_write_then_read_is_exact():
    joints = [BVHJoint("root", -1, np.zeros(3), ["Xposition", "Yposition", "Zposition", "Zrotation", "Xrotation",
                                                  "Yrotation"]),
              BVHJoint("child", 0, np.array([0.1, 12.5, 1e-5]), ["Zrotation", "Xrotation", "Yrotation"],
                       np.array([0, 3.0, 0]), 6)]
    frames = np.random.default_rng(0).uniform(-90, 90, (3, 9))
    b = parse(format_bvh(joints, frames, 1 / 30))
    assert np.array_equal(b.frames, frames) and np.array_equal(b.joints[1].offset, joints[1].offset)
    assert b.frame_time == 1 / 30


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet=st.sampled_from(list("{}ROOTJOINTOFFSETCHANNELSMOTIONFrames:Time 0123456789.-\n\tXYZrotation")),
               max_size=300))
def test_fuzzed_text_gives_only_parse_errors(text):
    try:
        parse(text, "fuzz.bvh")
    except ParseError as exc:
        assert str(exc).startswith("fuzz.bvh:")


@settings(max_examples=100, deadline=None)
@given(st.integers(0, len(SMALL) - 1), st.text(max_size=3))
def test_mutated_small_file_gives_only_parse_errors(pos, insert):
    try:
        parse(SMALL[:pos] + insert + SMALL[pos + 1:], "m.bvh")
    except ParseError as exc:
        assert str(exc).startswith("m.bvh:")
