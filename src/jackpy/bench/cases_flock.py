"""Flock of Birds benchmarks: stream decoding throughput and pty-to-store latency."""

from __future__ import annotations

import time

import numpy as np

from jackpy.bench.runner import Case, Result, time_calls


def _stream(n_cycles: int = 250, birds: int = 4) -> bytes:
    from jackpy.devices.flock.protocol import Format, encode_record, make_record

    rng = np.random.default_rng(0)
    out = bytearray()
    for _ in range(n_cycles):
        for b in range(1, birds + 1):
            rec = make_record(Format.POSITION_ANGLES, rng.uniform(-30, 30, 3), rng.uniform(-80, 80, 3),
                              address=b)
            out += encode_record(rec, group=True)
    return bytes(out)


def _naive_decode(data: bytes, length: int, nwords: int) -> list:
    """Baseline: a byte-at-a-time hunt/collect state machine (what most C drivers do), building
    the same :class:`Record` objects but checking only the first byte's phasing bit."""
    from jackpy.devices.flock.protocol import Format, Record

    out, rec = [], []
    for b in data:
        if b & 0x80:
            rec = [b]
        elif rec:
            rec.append(b)
        if len(rec) == length:
            words = []
            for k in range(nwords):
                u = ((rec[2 * k + 1] & 0x7F) << 9) | ((rec[2 * k] & 0x7F) << 2)
                words.append(u - 0x10000 if u & 0x8000 else u)
            out.append(Record(Format.POSITION_ANGLES, tuple(words), 36.0, None, None, rec[-1]))
            rec = []
    return out


def _decode_case(quick: bool) -> Result:
    from jackpy.devices.flock.protocol import BirdLayout, StreamDecoder

    data = _stream()
    chunks = [data[k:k + 64] for k in range(0, len(data), 64)]  # what a serial read returns
    layouts = {b: BirdLayout() for b in range(1, 5)}
    n_records = len(data) // 13

    def ours():
        dec = StreamDecoder(layouts, group=True)
        for c in chunks:
            dec.feed(c)
        assert dec.records == n_records

    def naive():
        assert len(_naive_decode(data, 13, 6)) == n_records

    repeat = 10 if quick else 40
    t = time_calls(ours, repeat=repeat, warmup=2)
    base = time_calls(naive, repeat=repeat, warmup=2)
    return Result("flock-decode", t.median_ms, t.p90_ms, base.median_ms,
                  {"records": n_records, "records_per_s": n_records / (t.median_ms / 1e3)})


def _latency_case(quick: bool) -> Result:
    from jackpy.devices.flock.driver import FlockDriver
    from jackpy.devices.flock.simulator import FlockSimulator

    got: dict[int, list[float]] = {}
    with FlockSimulator(4, autoconfig_delay=0.05, log=True) as sim:
        drv = FlockDriver(sim.paths[0], 4, measurement_rate=100.0, rts_reset=None, autoconfig_wait=0.05)
        drv.add_listener(lambda s: got.setdefault(s.bird, []).append(s.time))
        drv.start()
        time.sleep(2.0 if quick else 6.0)
        sim.hang(30.0)
        time.sleep(0.2)
        drv.stop()
    lat = [got_t - sent.time for b, sent_list in sim.sent.items()
           for sent, got_t in zip(sent_list, got.get(b, []))]
    ms = np.array(lat) * 1e3
    return Result("flock-latency", float(np.median(ms)), float(np.percentile(ms, 90)), None,
                  {"samples": len(ms), "birds": 4, "rate_hz": 100, "dropped": drv.stats.dropped,
                   "max_ms": float(ms.max())})


CASES = [
    Case("flock-decode", _decode_case, "decode 1000 group-mode POS/ANG records fed in 64-byte reads"),
    Case("flock-latency", _latency_case, "simulator write -> decoded sample in the store (4 birds, 100 Hz)"),
]
