"""The real driver against the simulator over real pseudo-terminals (and a TCP socket)."""

from __future__ import annotations

import os
import time

import pytest

from jackpy.devices.flock import protocol as p
from jackpy.devices.flock.driver import FlockDriver, Sample
from jackpy.devices.flock.simulator import FlockSimulator
from jackpy.errors import DeviceError

FAST = dict(rts_reset=None, autoconfig_wait=0.08, data_timeout=1.0, reconnect_interval=0.2)


def collect(driver: FlockDriver) -> dict[int, list[Sample]]:
    got: dict[int, list[Sample]] = {}
    driver.add_listener(lambda s: got.setdefault(s.bird, []).append(s))
    return got


def wait_until(cond, timeout: float = 10.0) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if cond():
            return True
        time.sleep(0.02)
    return cond()


def finish(sim: FlockSimulator, drv: FlockDriver) -> None:
    """Silence the simulator, let the driver read what is on the wire, then stop it."""
    sim.hang(30.0)
    time.sleep(0.3)
    drv.stop()


def assert_same_as_sent(sim: FlockSimulator, got: dict[int, list[Sample]]) -> int:
    """Every intact record the simulator sent came out, in order and word for word."""
    total = 0
    for bird, sent in sim.sent.items():
        want = [s.record.words for s in sent if s.intact]
        have = [s.record.words for s in got.get(bird, [])]
        assert have == want, (bird, len(have), len(want))
        assert [s.seq for s in got[bird]] == list(range(len(have)))
        total += len(have)
    return total


def test_group_mode_stream_4_birds_100hz_3s():
    with FlockSimulator(4, autoconfig_delay=0.05, log=True) as sim:
        drv = FlockDriver(sim.paths[0], 4, measurement_rate=100.0, **FAST)
        got = collect(drv)
        drv.start()
        time.sleep(3.0)
        finish(sim, drv)
        n = assert_same_as_sent(sim, got)
    assert n >= 4 * 100 * 2.7  # ~100 Hz per bird for 3 s (generous: a busy CI box may lag)
    assert drv.stats.dropped == 0 and drv.stats.skipped_bytes == 0
    assert drv.birds == [1, 2, 3, 4] and drv.info["revision"] == "3.67"


def test_one_port_per_bird_stream():
    with FlockSimulator(3, multi_port=True, autoconfig_delay=0.05, log=True) as sim:
        assert len(sim.paths) == 3
        drv = FlockDriver(sim.paths, format=p.Format.POSITION_QUATERNION, measurement_rate=100.0, **FAST)
        got = collect(drv)
        drv.start()
        time.sleep(1.5)
        finish(sim, drv)
        assert_same_as_sent(sim, got)
    assert set(got) == {1, 2, 3} and all(len(v) > 50 for v in got.values())
    assert got[2][-1].record.format is p.Format.POSITION_QUATERNION


def test_point_mode_group_4_birds_100hz_3s():
    with FlockSimulator(4, autoconfig_delay=0.05, log=True) as sim:
        drv = FlockDriver(sim.paths[0], 4, mode="point", point_rate=100.0, **FAST)
        got = collect(drv)
        drv.start()
        time.sleep(3.0)
        finish(sim, drv)
        n = assert_same_as_sent(sim, got)
    assert n >= 4 * 100 * 2.1  # one POINT request per 10 ms answered by all 4 birds (a busy box may lag)
    assert all(len(got[b]) >= 210 for b in (1, 2, 3, 4))
    assert drv.stats.dropped == 0 and drv.stats.skipped_bytes == 0


def test_standalone_over_socket_url():
    with FlockSimulator(1, tcp_port=0, log=True) as sim:
        assert sim.paths[0].startswith("socket://")
        drv = FlockDriver(sim.paths[0], format=p.Format.MATRIX, **FAST)
        with drv:
            s = drv.store.wait(0, after_seq=5, timeout=5.0)
        assert s is not None and s.record.format is p.Format.MATRIX and s.record.address == 0


def test_device_error_is_read_and_reported():
    with FlockSimulator(2, autoconfig_delay=0.05) as sim:
        with FlockDriver(sim.paths[0], 2, **FAST) as drv:
            first = drv.store.wait(1, timeout=3.0)
            assert first is not None
            sim.set_error(13, 3)
            errors = drv.check_errors()
            assert [c for c, _ in errors] == [13]
            assert "no FBB command response" in errors[0][1] and "address 3" in errors[0][1]
            assert drv.check_errors() == []  # reading cleared it
            assert drv.store.wait(1, after_seq=first.seq + 1, timeout=3.0) is not None  # streaming again


def test_kill_and_reconnect(tmp_path):
    link = str(tmp_path / "flock0")
    sim = FlockSimulator(2, link=link, autoconfig_delay=0.05).start()
    drv = FlockDriver(link, 2, **FAST).start()
    try:
        assert drv.store.wait(1, timeout=3.0) is not None
        sim.stop()
        assert wait_until(lambda: drv.state in ("disconnected", "connecting"), 5.0)
        assert drv.stats.disconnects == 1 and drv.last_error
        assert not os.path.exists(link)
        sim = FlockSimulator(2, link=link, autoconfig_delay=0.05).start()
        assert wait_until(lambda: drv.stats.connects == 2 and drv.state == "stream", 10.0)
        seq = drv.latest(2).seq
        assert drv.store.wait(2, after_seq=seq, timeout=3.0) is not None
    finally:
        drv.stop()
        sim.stop()


def test_hang_times_out_and_recovers():
    with FlockSimulator(1, log=True) as sim:
        with FlockDriver(sim.paths[0], **FAST) as drv:
            assert drv.store.wait(0, timeout=3.0) is not None
            sim.hang(1.5)
            assert wait_until(lambda: drv.stats.disconnects == 1, 5.0)
            assert "no data" in drv.last_error
            assert wait_until(lambda: drv.stats.connects == 2, 10.0)


def test_nothing_answers_times_out_cleanly():
    master, slave = os.openpty()
    try:
        drv = FlockDriver(os.ttyname(slave), reply_timeout=0.2, rts_reset=None)
        with pytest.raises(DeviceError, match="no reply"):
            drv.start(wait=1.5)
        assert drv.state == "stopped"
    finally:
        os.close(master)
        os.close(slave)


def test_bad_settings_are_clear_errors():
    with pytest.raises(DeviceError, match="hemisphere"):
        FlockDriver("/dev/null", hemisphere="down")
    with pytest.raises(DeviceError, match="mode"):
        FlockDriver("/dev/null", mode="burst")
    with pytest.raises(DeviceError, match="cannot open"):
        FlockDriver("/nonexistent/tty", rts_reset=None, reply_timeout=0.1).start(wait=1.0)


def test_8_birds_144hz_backlog_stays_bounded():
    with FlockSimulator(8, autoconfig_delay=0.05, log=True) as sim:
        drv = FlockDriver(sim.paths[0], 8, measurement_rate=144.0, **FAST)
        got = collect(drv)
        drv.start()
        time.sleep(3.0)
        finish(sim, drv)
        n = assert_same_as_sent(sim, got)
    assert sim.overrun_bytes == 0  # the pty never filled up: the reader kept pace
    assert drv.stats.max_pending_bytes < 4096
    assert n >= 8 * 144 * 2
