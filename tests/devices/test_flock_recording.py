"""Recording: incremental, crash-tolerant writes; reading, frames, replay; as simulator motion."""

from __future__ import annotations

import os
import time

import numpy as np
import pytest

from jackpy.devices.flock.driver import Sample
from jackpy.devices.flock.protocol import Format, make_record
from jackpy.devices.recording import Recorder, read_recording, replay
from jackpy.errors import DeviceError, ParseError


def samples(n_frames: int = 20, birds=(1, 2)):
    out = []
    for i in range(n_frames):
        for b in birds:
            rec = make_record(Format.POSITION_ANGLES, (i, b, -i), (i, 0, b), address=b)
            out.append(Sample(b, rec, 100.0 + i / 100, i))
    return out


def test_round_trip_frames_and_replay(tmp_path):
    path = tmp_path / "rec.jsonl"
    with Recorder(path, meta={"birds": 2}) as r:
        for s in samples():
            r.add(s)
    rec = read_recording(path)
    assert rec.header["birds"] == 2 and rec.birds == [1, 2] and len(rec.samples) == 40
    assert rec.samples[3].record.words == samples()[3].record.words
    assert rec.samples[0].time == 0.0 and rec.duration == pytest.approx(0.19)
    frames = rec.frames()
    assert len(frames) == 20 and set(frames[5]) == {1, 2}
    assert len(list(replay(rec, speed=0))) == 20
    t0 = time.perf_counter()
    assert len(list(replay(rec, speed=2.0))) == 20
    assert time.perf_counter() - t0 >= 0.09
    pos, ang = rec.pose_at(0.05, 2)
    assert np.allclose(pos, (5, 2, -5), atol=0.01) and np.allclose(ang, (5, 0, 2), atol=0.05)


def test_flushed_while_open_and_torn_last_line(tmp_path):
    path = tmp_path / "rec.jsonl"
    r = Recorder(path, flush_interval=0.1)
    for s in samples(5):
        r.add(s)
    time.sleep(0.4)  # no close: as if the process died now
    assert len(read_recording(path).samples) == 10
    with open(path, "a") as f:
        f.write('[0.5,1,9,"Y",36.0,[1,2')  # a crash in mid-line
    assert len(read_recording(path).samples) == 10
    r.close()


def test_malformed_recordings(tmp_path):
    path = tmp_path / "bad.jsonl"
    path.write_text("hello\n")
    with pytest.raises(ParseError, match=":1:1"):
        read_recording(path)
    path.write_text('{"jackpy": "flock-recording", "version": 1}\n[0,1,0,"Y",36,[1,2],null,null]\n[0,1,1,"Y",36,[0,0,0,0,0,0],null,null]\n')
    with pytest.raises(ParseError, match=":2:"):
        read_recording(path)
    assert not os.path.exists(tmp_path / "bad.jsonl.tmp")


def test_default_recorder_hands_samples_over_within_a_quarter_second(tmp_path):
    path = tmp_path / "rec.jsonl"
    r = Recorder(path)
    for s in samples(3):
        r.add(s)
    time.sleep(0.45)  # the flusher thread: no sample came after these, and no close
    assert len(read_recording(path).samples) == 6
    r.close()
    with pytest.raises(DeviceError, match="flush interval"):
        Recorder(tmp_path / "x.jsonl", flush_interval=2.0)


def test_header_only_recording_is_empty(tmp_path):
    path = tmp_path / "empty.jsonl"
    Recorder(path, meta={"birds": 1}).close()
    rec = read_recording(path)
    assert rec.samples == [] and rec.frames() == [] and rec.duration == 0.0
    assert list(replay(rec, speed=0)) == []
