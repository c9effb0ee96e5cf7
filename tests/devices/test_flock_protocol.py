"""Protocol: the spec's worked examples (§6), round trips for every format, and decoder fuzzing."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from jackpy.devices.flock import protocol as p
from jackpy.devices.flock.protocol import BirdLayout, Format, StreamDecoder
from jackpy.errors import DeviceError, JackpyError

H = bytes.fromhex


def decode_one(data: bytes, fmt: Format, scale: float = 36.0, group: bool = False,
               address: int = 0, button: bool = False) -> p.Record:
    dec = StreamDecoder({address: BirdLayout(fmt, scale, button)}, group=group)
    recs = dec.feed(data)
    assert len(recs) == 1 and dec.dropped == 0 and dec.pending == 0
    return recs[0]


def test_e1_manual_packing_vector():
    data = p.pack_words([0x1122, 0x3344, 0x5566])
    assert data == H("C8 08 51 19 59 2A")
    assert [w & 0xFFFF for w in p.unpack_words(data)] == [0x1120, 0x3344, 0x5564]


def test_e2_position_angles():
    r = decode_one(H("E4 11 0E 77 39 04 00 20 00 70 55 0A"), Format.POSITION_ANGLES)
    assert np.allclose(r.position, (10.001953, -5.000977, 2.500488), atol=1e-6)
    assert np.allclose(r.angles, (90.0, -45.0, 29.992676), atol=1e-6)


def test_e3_position_extremes():
    r = decode_one(H("80 40 7F 3F 01 00"), Format.POSITION)
    assert np.allclose(r.position, (-36.0, 35.995605, 0.004395), atol=1e-6)


def test_e4_quaternion_identity_and_clamp():
    r = decode_one(H("FF 3F 00 00 00 00 00 00"), Format.QUATERNION)
    assert np.allclose(r.quaternion, (0.999878, 0, 0, 0), atol=1e-6)
    assert p.make_record(Format.QUATERNION).words == (0x7FFC, 0, 0, 0)
    assert p.unpack_words(H("80 40")) == (-0x8000,)


def test_e5_position_quaternion_group_72():
    data = H("D5 0A 55 7A 2B 15 21 2D 00 00 00 00 5F 52 02")
    r = decode_one(data, Format.POSITION_QUATERNION, 72.0, group=True, address=2)
    assert r.address == 2
    assert np.allclose(r.position, (11.997070, -6.002930, 24.002930), atol=1e-6)
    assert np.allclose(r.quaternion, (0.707153, 0, 0, -0.707153), atol=1e-6)
    # azimuth +90 deg: the sensor x axis turns to transmitter +y (turned right)
    assert np.allclose(r.rotation() @ [1, 0, 0], [0, 1, 0], atol=1e-3)
    made = p.make_record(Format.POSITION_QUATERNION, (12, -6, 24), (90, 0, 0), scale=72.0, address=2)
    assert p.encode_record(made, group=True) == data


def test_e6_matrix_and_quaternion_agree():
    data = H("80 00 00 40 00 00 7F 3F 00 00 00 00 00 00 00 00 7F 3F")
    r = decode_one(data, Format.MATRIX)
    m = r.matrix
    assert np.allclose(m, [[0, 0.999878, 0], [-1.0, 0, 0], [0, 0, 0.999878]], atol=1e-6)
    assert p.encode_record(p.make_record(Format.MATRIX, angles=(90, 0, 0))) == data
    q = p.encode_record(p.make_record(Format.QUATERNION, angles=(90, 0, 0)))
    assert q == H("A1 2D 00 00 00 00 5F 52")
    rq = decode_one(q, Format.QUATERNION)
    assert np.allclose(rq.rotation(), r.rotation(), atol=1e-3)
    assert np.allclose(r.rotation(), p.rotation_from_angles(np.pi / 2, 0, 0), atol=1e-3)


def test_e7_group_point_mixed_formats():
    dec = StreamDecoder({2: BirdLayout(Format.POSITION), 3: BirdLayout(Format.POSITION_ANGLES)},
                        group=True)
    recs = dec.feed(H("F2 08 00 00 0E 77 02 80 00 64 11 00 00 00 60 00 10 7F 3F 03"))
    assert [r.address for r in recs] == [2, 3]
    assert np.allclose(recs[0].position, (5.000977, 0, -5.000977), atol=1e-6)
    assert np.allclose(recs[1].position, (0, 10.001953, 0), atol=1e-6)
    assert np.allclose(recs[1].angles, (-90.0, 45.0, 179.978027), atol=1e-6)


def test_e8_resync_after_lost_byte():
    dec = StreamDecoder({0: BirdLayout(Format.POSITION)})
    assert dec.feed(H("E4 11 00 1C 6E D5 12 00 00 1C 6E")) == []  # B follows a fault: wait for C
    recs = dec.feed(H("80"))  # the next record starts: B is confirmed
    assert len(recs) == 1 and (dec.dropped, dec.skipped_bytes) == (1, 0)
    assert np.allclose(recs[0].position, (10.498535, 0, -10.001953), atol=1e-6)


def test_e8_byte_at_a_time_gives_the_same():
    dec = StreamDecoder({0: BirdLayout(Format.POSITION)})
    recs = [r for b in H("E4 11 00 1C 6E D5 12 00 00 1C 6E 80") for r in dec.feed(bytes([b]))]
    assert len(recs) == 1 and (dec.dropped, dec.skipped_bytes) == (1, 0)


def test_e9_button_and_group_trailers():
    r = decode_one(H("80 00 00 00 00 00 10 01"), Format.POSITION, group=True, address=1, button=True)
    assert r.button == 0x10 and r.address == 1 and r.position == (0, 0, 0)
    made = p.make_record(Format.POSITION, button=0x10, address=1)
    assert p.encode_record(made, group=True) == H("80 00 00 00 00 00 10 01")


def test_e10_command_frames():
    assert p.fbb_prefix(2) + p.hemisphere_command("lower") == H("F2 4C 0C 00")
    assert p.fbb_prefix(3) + bytes([Format.POSITION_QUATERNION]) == H("F3 5D")
    assert p.change_value(p.P_AUTO_CONFIG, b"\x03") == H("50 32 03")
    assert p.change_value(p.P_GROUP_MODE, b"\x01") == H("50 23 01")
    assert p.change_value(p.P_MEASUREMENT_RATE, p.measurement_rate_value(103.3)) == H("50 07 4D 67")
    assert p.fbb_prefix(2) + p.change_value(p.P_POSITION_SCALING, b"\x01\x00") == H("F2 50 03 01 00")
    assert p.fbb_prefix(2) + bytes([p.ANGLE_ALIGN2]) + p.angle_words(90, -30, 0) == H("F2 71 00 40 AB EA 00 00")
    assert p.fbb_prefix(16, "expanded") == H("E0") and p.fbb_prefix(30, "expanded") == H("EE")
    assert p.fbb_prefix(2, "super") == H("A0 02") and p.fbb_prefix(15) == H("FF")


def test_e11_examine_replies():
    st_ = p.BirdStatus(p.u16_le(H("09 D0")))
    assert st_.master and st_.initialized and st_.running and st_.stream
    assert st_.format is Format.POSITION_ANGLES
    assert p.decode_revision(H("03 43")) == "3.67"
    assert p.u16_le(H("4D 67")) / 256 == pytest.approx(103.30, abs=0.01)


def test_bad_commands_raise_project_errors():
    with pytest.raises(DeviceError):
        p.fbb_prefix(16)
    with pytest.raises(DeviceError):
        p.change_value(p.P_GROUP_MODE, b"\x01\x00")
    with pytest.raises(DeviceError):
        p.hemisphere_command("sideways")
    with pytest.raises(DeviceError):
        Format.parse("euler")
    with pytest.raises(DeviceError):
        p.measurement_rate_value(500)
    with pytest.raises(DeviceError):
        StreamDecoder({1: BirdLayout(), 2: BirdLayout()}, group=False)


def test_format_names():
    assert Format.parse("pos_quat") is Format.POSITION_QUATERNION
    assert Format.parse("position-angles") is Format.POSITION_ANGLES
    assert Format.parse("Y") is Format.POSITION_ANGLES
    for f in Format:
        assert Format(f.status_code + 0x55) is f


poses = st.tuples(
    st.tuples(*[st.floats(-35.9, 35.9)] * 3),
    st.tuples(st.floats(-179.9, 179.9), st.floats(-89.9, 89.9), st.floats(-179.9, 179.9)),
)


@settings(max_examples=60, deadline=None)
@given(pose=poses, fmt=st.sampled_from(list(Format)), scale=st.sampled_from(p.POSITION_SCALES),
       group=st.booleans(), button=st.booleans())
def test_round_trip_every_format(pose, fmt, scale, group, button):
    pos, ang = pose
    pos = tuple(x * scale / 36.0 for x in pos)
    rec = p.make_record(fmt, pos, ang, scale=scale, button=0x10 if button else None,
                        address=5 if group else None)
    data = p.encode_record(rec, group=group)
    assert len(data) == BirdLayout(fmt, scale, button).length(group)
    back = decode_one(data, fmt, scale, group=group, address=5 if group else 0, button=button)
    assert back.words == rec.words
    if fmt.has_position:
        assert np.allclose(back.position, pos, atol=scale / 8192)
    r_true = p.rotation_from_angles(*np.radians(ang))
    if fmt.orientation_words == 3:
        assert np.allclose(back.angles, ang, atol=180 / 8192)
    if fmt.orientation_words:
        assert np.allclose(back.rotation(), r_true, atol=2e-3)


@settings(max_examples=200, deadline=None)
@given(junk=st.binary(max_size=400), group=st.booleans(), chunk=st.integers(1, 64))
def test_fuzz_decoder_never_raises(junk, group, chunk):
    layouts = {1: BirdLayout(Format.POSITION), 2: BirdLayout(Format.POSITION_QUATERNION, 72.0, True)}
    dec = StreamDecoder(layouts if group else {1: layouts[1]}, group=group)
    good = p.encode_record(p.make_record(Format.POSITION, (1, 2, 3), address=1), group=group)
    # In group mode with mixed record lengths, the end of a record is only certain once the next
    # record's phasing byte arrives, so the clean record is followed by another one.
    stream = junk + good + good
    try:
        recs = [r for k in range(0, len(stream), chunk) for r in dec.feed(stream[k:k + chunk])]
    except JackpyError:
        return
    # garbage in -> only drops; a clean record after the garbage (and its successor's start) comes out
    assert recs and recs[-1].words == p.make_record(Format.POSITION, (1, 2, 3)).words
    for r in recs:
        assert r.address in (1, 2) and len(r.words) == r.format.words


LONG_FORMATS = [Format.POSITION_ANGLES, Format.MATRIX, Format.POSITION_MATRIX, Format.POSITION_QUATERNION]


def _faulty_stream(rng: np.random.Generator, layouts: dict[int, BirdLayout], group: bool, fault: str):
    """Cycles of records with isolated faults: one byte lost from a record (never two damaged
    records in a row), or a garbage burst between records (never two bursts around one record).
    Returns (bytes, intact records, lost records, garbage bytes)."""
    out, intact, lost, garbage = bytearray(), [], 0, 0
    last_damaged = last_garbage = False
    addrs = sorted(layouts)
    for cycle in range(40):
        for a in addrs:
            lay = layouts[a]
            rec = p.make_record(lay.format, rng.uniform(-30, 30, 3), rng.uniform(-80, 80, 3),
                                scale=lay.scale, address=a)
            data = p.encode_record(rec, group=group)
            tail = cycle >= 38  # two clean cycles at the end settle the last gap
            if fault == "drop" and not tail and not last_damaged and rng.random() < 0.15:
                k = int(rng.integers(len(data)))
                out += data[:k] + data[k + 1:]
                lost += 1
                last_damaged = True
                continue
            last_damaged = False
            burst_here = fault == "garbage" and not tail and cycle > 0 and not last_garbage \
                and rng.random() < 0.15
            if burst_here:
                burst = rng.integers(0, 256, int(rng.integers(1, 40)), dtype=np.uint8).tobytes()
                out += burst
                garbage += len(burst)
            last_garbage = burst_here
            out += data
            intact.append(rec.words)
    return bytes(out), intact, lost, garbage


@pytest.mark.parametrize("fault", ["drop", "garbage"])
def test_decoder_counts_lost_records_and_stray_bytes_exactly(fault):
    """150 random streams (1..5 birds, mixed formats, random read sizes): the records lost and
    the garbage bytes are counted exactly, and every record delivered is one that was sent."""
    rng = np.random.default_rng(2026)
    for trial in range(150):
        nbirds = int(rng.integers(1, 6))
        group = nbirds > 1 or bool(rng.integers(2))
        fmts = LONG_FORMATS if fault == "garbage" else list(Format)  # see the decoder's docstring
        layouts = {a: BirdLayout(fmts[int(rng.integers(len(fmts)))], 36.0)
                   for a in (range(1, nbirds + 1) if group else [0])}
        data, intact, lost, garbage = _faulty_stream(rng, layouts, group, fault)
        dec = StreamDecoder(layouts, group=group)
        got, k = [], 0
        while k < len(data):
            step = int(rng.integers(1, 80))
            got += dec.feed(data[k:k + step])
            k += step
        assert [r.words for r in got] == intact, trial
        assert (dec.dropped, dec.skipped_bytes) == (lost, garbage), trial


def test_record_that_lost_its_phasing_byte_is_one_lost_record():
    """Issue 22: a group record without its first byte was counted as 14 skipped bytes."""
    layouts = {2: BirdLayout(Format.POSITION_QUATERNION), 3: BirdLayout(Format.POSITION_QUATERNION)}
    recs = [p.encode_record(p.make_record(Format.POSITION_QUATERNION, (i, 2, 3), address=a), group=True)
            for i in range(3) for a in (2, 3)]
    dec = StreamDecoder(layouts, group=True)
    out = dec.feed(b"".join(recs[:3]) + recs[3][1:] + b"".join(recs[4:]))
    assert len(out) == 5 and (dec.dropped, dec.skipped_bytes) == (1, 0)
    dec = StreamDecoder({0: BirdLayout(Format.POSITION)})
    one = [p.encode_record(p.make_record(Format.POSITION, (i, 0, 0))) for i in range(4)]
    out = dec.feed(one[0] + one[1][1:] + one[2] + one[3])
    assert len(out) == 3 and (dec.dropped, dec.skipped_bytes) == (1, 0)


def test_false_record_starts_in_garbage_are_stray_bytes_not_lost_records():
    """Issue 22: garbage bursts were counted as lost records (245 reported, 0 lost)."""
    layouts = {1: BirdLayout(), 2: BirdLayout()}
    recs = [p.encode_record(p.make_record(Format.POSITION_ANGLES, (i, 1, 1), address=a), group=True)
            for i in range(3) for a in (1, 2)]
    junk = bytes([0x85, 0x01, 0x90, 0x91, 0x02, 0xFF])
    dec = StreamDecoder(layouts, group=True)
    out = dec.feed(recs[0] + junk + b"".join(recs[1:]))
    assert len(out) == 6 and (dec.dropped, dec.skipped_bytes) == (0, len(junk))
