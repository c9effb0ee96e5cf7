"""Extended Range Controller flocks: the real driver against the simulator's ERC over a real pty.

The ERC sits at FBB address 1 with no sensor; sensor birds follow it. The driver must skip it
when mapping sensors, take the ERT's fixed 144 in full scale, and never send it a per-sensor
command (spec §5.4).
"""

from __future__ import annotations

import math
import time

import pytest

from jackpy.devices.flock import protocol as p
from jackpy.devices.flock.driver import FlockDriver, Sample
from jackpy.devices.flock.simulator import FlockSimulator

FAST = dict(rts_reset=None, autoconfig_wait=0.08, data_timeout=1.0, reconnect_interval=0.2)


def far_motion(t: float, address: int):
    """Positions 40..70 in ahead of the transmitter: beyond a 36 in bird's range, in an ERT's."""
    pos = (55.0 + 12.0 * math.sin(3.0 * t + address), -30.0 + 10.0 * math.cos(2.0 * t), 20.0 + address)
    ang = (50.0 * math.sin(2.0 * t + address), 20.0 * math.cos(t), -40.0 + 10.0 * address)
    return pos, ang


def run_erc(sensor_birds: int, fmt: p.Format, wanted: int | None = None, seconds: float = 0.35):
    with FlockSimulator(sensor_birds, erc=True, motion=far_motion, autoconfig_delay=0.05, log=True) as sim:
        drv = FlockDriver(sim.paths[0], wanted or sensor_birds, format=fmt, **FAST)
        got: dict[int, list[Sample]] = {}
        drv.add_listener(lambda s: got.setdefault(s.bird, []).append(s))
        drv.start()
        time.sleep(seconds)
        sim.hang(30.0)
        time.sleep(0.15)
        drv.stop()
    return sim, drv, got


@pytest.mark.parametrize("fmt", list(p.Format), ids=lambda f: f.name.lower())
@pytest.mark.parametrize("birds", [2, 3])
def test_erc_flock_every_format(birds, fmt):
    sim, drv, got = run_erc(birds, fmt)
    sensors = list(range(2, birds + 2))
    assert drv.birds == sensors and drv.info["model"] == "6DERC" and drv.info["erc"] == "yes"
    assert sim.erc_commands == []  # no format, hemisphere or scaling command reached the ERC
    assert set(got) == set(sensors)  # no bird dropped, nothing from the ERC
    for b in sensors:
        sent = [s.record.words for s in sim.sent[b]]
        have = [s.record.words for s in got[b]]
        assert have == sent and len(have) >= 15  # every record equals what was sent, in order
        assert all(s.record.format is fmt and s.record.scale == p.ERT_SCALE for s in got[b])
    assert drv.stats.dropped == 0 and drv.stats.skipped_bytes == 0
    if fmt.has_position:  # positions at the ERT's 144 in scale: far beyond 36 in, as sent
        for b in sensors:
            xs = [s.record.position[0] for s in got[b]]
            assert 40.0 <= min(xs) and max(xs) <= 70.0
            assert got[b][-1].record.position[2] == pytest.approx(20.0 + b, abs=p.ERT_SCALE / 8192)


def test_erc_flock_with_idle_birds_configures_only_those_wanted():
    sim, drv, got = run_erc(3, p.Format.POSITION_ANGLES, wanted=2)
    assert drv.birds == [2, 3] and set(got) == {2, 3} and sim.units == 3  # AUTO-CONFIG 3: ERC + 2
    assert sim.sent[4] == [] and sim.erc_commands == []
    assert drv.stats.dropped == 0 and drv.stats.skipped_bytes == 0


def test_erc_point_mode_one_sensor_uses_group_mode():
    """One sensor bird behind an ERC still needs group mode: the master (ERC) has no sensor."""
    with FlockSimulator(1, erc=True, motion=far_motion, autoconfig_delay=0.05, log=True) as sim:
        drv = FlockDriver(sim.paths[0], 1, mode="point", point_rate=50.0, **FAST)
        with drv:
            s = drv.store.wait(2, after_seq=5, timeout=5.0)
            assert s is not None and s.record.address == 2 and 40.0 <= s.record.position[0] <= 70.0
        assert sim.group_mode and sim.erc_commands == []


def test_simulated_erc_reports_itself_as_the_manual_says():
    """FLOCK SYSTEM STATUS (spec §6 E11): ERC with one ERT running = D1, sensor birds E0."""
    import serial

    with FlockSimulator(2, erc=True, autoconfig_delay=0.05) as sim:
        ser = serial.serial_for_url(sim.paths[0], timeout=1.0)
        try:
            ser.write(p.change_value(p.P_AUTO_CONFIG, b"\x03"))
            time.sleep(0.1)
            ser.write(p.examine_value(p.P_SYSTEM_STATUS))
            assert ser.read(14) == bytes.fromhex("D1 E0 E0 00 00 00 00 00 00 00 00 00 00 00")
            ser.write(p.examine_value(p.P_MODEL_ID))
            assert ser.read(10) == b"6DERC     "
            ser.write(p.fbb_prefix(1) + bytes([p.Format.POSITION]))  # what a driver must never do
            time.sleep(0.1)
            assert sim.erc_commands == [bytes([0xF1, p.Format.POSITION])]
        finally:
            ser.close()
