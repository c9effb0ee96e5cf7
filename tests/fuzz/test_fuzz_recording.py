"""Fuzzing Flock recordings (``read_recording``) and sensor configurations (``load_sensor_config``):
mutated files raise only the project's errors, and a recording that reads also replays."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from fuzz_helpers import (
    FUZZ,
    byte_mutations,
    check_error,
    expect_only_project_errors,
    mutate,
    mutate_bytes,
    mutations,
)
from hypothesis import given

from jackpy.devices.recording import FrameMotion, read_recording, replay
from jackpy.devices.sensors import load_sensor_config, sensor_config_from_dict
from jackpy.errors import DeviceError, JackpyError, ParseError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "flock"
REC_TEXT = "".join((EXAMPLES / "reach.jsonl").read_text().splitlines(keepends=True)[:13])
SENSORS_TEXT = (EXAMPLES / "reach-sensors.json").read_text()
REC_WORDS = ['"Y"', '"Z"', '"W"', '"V"', '"X"', '"A"', '"q"', '"flock-recording"', '"jackpy"', "[1,2,3]",
             '{"a":1}', "127", "-32769", "32767", "1e400", '"figure"', '"calibrate_frame"', '"sensors"']
SENSOR_WORDS = ['"bird"', '"part"', '"sensors"', '"offset"', '"position_m"', '"rotation_deg"', '"transmitter"',
                '"yaw_deg"', '"pelvis"', '"neck"', "127", "-1", "[1,2]", "[[1]]", '{"x": 1}', "1e400"]


def _consume(rec) -> None:
    """Everything the replay commands do with a recording that read."""
    for _ in replay(rec, speed=0):
        pass
    for bird in rec.birds:
        rec.pose_at(0.5, bird)
    if rec.samples:
        motion = FrameMotion(rec)
        motion.play()
        for bird in rec.birds:
            motion(0.0, bird)
    header = rec.header
    if isinstance(header.get("sensors"), dict):
        expect_only_project_errors(lambda: sensor_config_from_dict(header["sensors"], "hdr"), "hdr")


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("recfuzz")


def test_seeds_read(folder: Path) -> None:
    (folder / "seed.jsonl").write_text(REC_TEXT)
    rec = read_recording(folder / "seed.jsonl")
    assert len(rec.samples) == 12
    _consume(rec)
    assert len(load_sensor_config(EXAMPLES / "reach-sensors.json").mounts) == 4


@pytest.mark.timeout(60)
@FUZZ
@given(mutations(REC_TEXT, REC_WORDS))
def test_mutated_recording(folder: Path, ops) -> None:
    path = folder / "fuzz.jsonl"
    path.write_text(mutate(REC_TEXT, ops), encoding="utf-8", newline="")
    rec = expect_only_project_errors(lambda: read_recording(path), str(path), position=True)
    if rec is not None:
        _consume(rec)


@pytest.mark.timeout(60)
@FUZZ
@given(byte_mutations(REC_TEXT.encode()))
def test_byte_mutated_recording(folder: Path, ops) -> None:
    path = folder / "bytes.jsonl"
    path.write_bytes(mutate_bytes(REC_TEXT.encode(), ops))
    rec = expect_only_project_errors(lambda: read_recording(path), str(path), position=True)
    if rec is not None:
        _consume(rec)


HEADER = json.loads(REC_TEXT.splitlines()[0])


@pytest.mark.parametrize("line", [
    '[Infinity,1,0,"Y",36,[1,2,3,4,5,6],null,null]', '[NaN,1,0,"Y",36,[1,2,3,4,5,6],null,null]',
    '[-1,1,0,"Y",36,[1,2,3,4,5,6],null,null]', '[0,Infinity,0,"Y",36,[1,2,3,4,5,6],null,null]',
    '[0,1,1e300,"Y",36,[1,2,3,4,5,6],null,null]', '[0,1,0,"Y",NaN,[1,2,3,4,5,6],null,null]',
    '[0,1,0,"Y",36,[1,2,3,4,5,6],"x",null]', '[0,1,0,"Y",36,[1,2,3,4,5,6],1e9,null]',
    '[0,1,0,"Y",36,[1.5,2,3,4,5,6],null,null]', '[0,1,0,"Y",36,[true,2,3,4,5,6],null,null]',
    '[0,1.5,0,"Y",36,[1,2,3,4,5,6],null,null]', '[0,-1,0,"Y",36,[1,2,3,4,5,6],null,null]',
    '{"t":0,"b":1,"s":0,"f":"Y","x":36,"w":0,"u":0,"m":0}', '"abcdefgh"', "[" * 100000 + "]" * 100000,
    "1" * 5000])
def test_bad_sample_lines(folder: Path, line: str) -> None:
    path = folder / "lines.jsonl"
    path.write_text(json.dumps(HEADER) + "\n" + line + "\n[0,1,0,\"Y\",36,[1,2,3,4,5,6],null,null]\n")
    with pytest.raises(ParseError) as info:
        read_recording(path)
    check_error(info.value, str(path), position=True)
    assert info.value.line == 2


@pytest.mark.parametrize("header", [
    {"figure": [1]}, {"figure": {"percentile": [1]}}, {"figure": {"percentile": "x"}}, {"figure": {"sex": 3}},
    {"figure": {"sex": "robot"}}, {"figure": {"percentile": 1e400}}, {"calibrate_frame": [1]},
    {"calibrate_frame": "x"}, {"calibrate_frame": 1e300}, {"calibrate_frame": -1}, {"sensors": [1]}])
def test_bad_header_fields(folder: Path, header: dict) -> None:
    """Header fields the replay commands use are checked when reading, not deep in a command."""
    path = folder / "header.jsonl"
    path.write_text(json.dumps({**HEADER, **header}) + "\n" + "\n".join(REC_TEXT.splitlines()[1:]) + "\n")
    with pytest.raises(ParseError) as info:
        read_recording(path)
    check_error(info.value, str(path), position=True)
    assert info.value.line == 1


def test_unreadable_recordings(folder: Path) -> None:
    for name in ("nosuch.jsonl", "."):
        with pytest.raises(JackpyError):
            read_recording(folder / name)
    with pytest.raises(DeviceError):
        read_recording(str(folder / "a\x00b"))


# ------------------------------------------------------------------------------ sensors
@pytest.mark.timeout(60)
@FUZZ
@given(mutations(SENSORS_TEXT, SENSOR_WORDS))
def test_mutated_sensor_config(folder: Path, ops) -> None:
    path = folder / "sensors.json"
    path.write_text(mutate(SENSORS_TEXT, ops), encoding="utf-8", newline="")
    expect_only_project_errors(lambda: load_sensor_config(path), str(path))


@pytest.mark.timeout(60)
@FUZZ
@given(byte_mutations(SENSORS_TEXT.encode()))
def test_byte_mutated_sensor_config(folder: Path, ops) -> None:
    path = folder / "sensors_b.json"
    path.write_bytes(mutate_bytes(SENSORS_TEXT.encode(), ops))
    expect_only_project_errors(lambda: load_sensor_config(path), str(path))


@pytest.mark.parametrize("text, where", [
    ('{"sensors": [{"bird": 1, "part": "pelvis"}, {"bird": 200, "part": "neck"}]}', "sensors[1].bird"),
    ('{"sensors": [{"bird": 1}]}', "sensors[0].part"),
    ('{"sensors": [{"bird": 1, "part": "pelvis", "offset": {"position_m": [1, 2]}}]}',
     "sensors[0].offset.position_m"),
    ('{"sensors": [{"bird": 1, "part": "pelvis", "offset": {"rotation_deg": [1, 2, "x"]}}]}',
     "sensors[0].offset.rotation_deg"),
    ('{"transmitter": {"yaw_deg": [1]}, "sensors": []}', "transmitter.yaw_deg"),
    ('{"transmitter": 3, "sensors": []}', "transmitter"),
    ('{"sensors": {"bird": 1}}', "sensors"),
    ('[1, 2]', "the top level"),
])
def test_sensor_config_errors_name_the_key(folder: Path, text: str, where: str) -> None:
    path = folder / "keys.json"
    path.write_text(text)
    with pytest.raises(ParseError) as info:
        load_sensor_config(path)
    check_error(info.value, str(path))
    assert where in str(info.value)


def test_sensor_config_json_errors_have_line_and_column(folder: Path) -> None:
    path = folder / "syntax.json"
    path.write_text('{\n "sensors": [\n  {"bird": 1,, "part": "pelvis"}]}\n')
    with pytest.raises(ParseError) as info:
        load_sensor_config(path)
    assert (info.value.line, info.value.column) == (3, 14)
    for data in (b'{"sensors": [\xff]}', b"[" * 100000, b"1" * 5000):
        path.write_bytes(data)
        with pytest.raises(ParseError) as info:
            load_sensor_config(path)
        check_error(info.value, str(path), position=True)
