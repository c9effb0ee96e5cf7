"""Exact loss accounting: the real driver against the simulator's faults over a real pty.

Records lost = records the simulator sent that the driver did not deliver; stray bytes = the
garbage the simulator put on the wire. Both must be counted exactly, separately, and every
delivered record must equal what was sent.
"""

from __future__ import annotations

import random
import time

import pytest

from jackpy.devices.flock import protocol as p
from jackpy.devices.flock.driver import FlockDriver, Sample
from jackpy.devices.flock.simulator import FlockSimulator

FAST = dict(rts_reset=None, autoconfig_wait=0.08, data_timeout=1.0, reconnect_interval=0.2)
TOPOLOGIES = {
    "standalone": dict(birds=1),
    "flock4": dict(birds=4),
    "erc2": dict(birds=2, erc=True),
}


def run_faults(topology: str, fmt: p.Format, inject, rounds: int = 30):
    """Stream, call ``inject(sim, rng)`` ``rounds`` times 50 ms apart (about 5 records apart
    per bird), let clean records follow, then stop. Returns (sim, driver, delivered)."""
    kw = TOPOLOGIES[topology]
    with FlockSimulator(kw["birds"], erc=kw.get("erc", False), autoconfig_delay=0.05, log=True,
                        seed=7) as sim:
        drv = FlockDriver(sim.paths[0], kw["birds"], format=fmt, **FAST)
        got: dict[int, list[Sample]] = {}
        drv.add_listener(lambda s: got.setdefault(s.bird, []).append(s))
        rng = random.Random(11)
        with drv:
            end = time.monotonic() + 5.0
            while drv.stats.records < 20 and time.monotonic() < end:
                time.sleep(0.01)
            for _ in range(rounds):
                inject(sim, rng)
                time.sleep(0.05)
            time.sleep(0.15)  # clean records after the last fault settle its gap
            sim.hang(30.0)
            time.sleep(0.2)
        return sim, drv, got


def delivered_equal_sent(sim: FlockSimulator, got: dict[int, list[Sample]]) -> tuple[int, int]:
    """Every delivered record is an intact sent one, in order; returns (sent, delivered)."""
    sent_n = have_n = 0
    for bird, sent in sim.sent.items():
        have = [s.record.words for s in got.get(bird, [])]
        intact = [s.record.words for s in sent if s.intact]
        assert have == intact, (bird, len(have), len(intact))
        sent_n += len(sent)
        have_n += len(have)
    return sent_n, have_n


@pytest.mark.parametrize("topology,fmt", [("standalone", p.Format.POSITION_ANGLES),
                                          ("flock4", p.Format.POSITION_QUATERNION),
                                          ("erc2", p.Format.POSITION_MATRIX)])
def test_drop_only_counts_exactly_the_records_lost(topology, fmt):
    sim, drv, got = run_faults(topology, fmt, lambda sim, rng: sim.drop_bytes(1))
    sent, have = delivered_equal_sent(sim, got)
    damaged = sum(not s.intact for v in sim.sent.values() for s in v)
    assert damaged == 30 and sim.overrun_bytes == 0
    assert drv.stats.dropped == sent - have == damaged  # one lost record per damaged one
    assert drv.stats.skipped_bytes == 0


@pytest.mark.parametrize("topology,fmt", [("standalone", p.Format.POSITION_ANGLES),
                                          ("flock4", p.Format.POSITION_ANGLES),
                                          ("erc2", p.Format.QUATERNION)])
def test_garbage_only_counts_exactly_the_bytes_skipped(topology, fmt):
    garbage = []

    def inject(sim, rng):
        burst = bytes(rng.randrange(256) for _ in range(rng.randint(1, 40)))
        garbage.append(burst)
        sim.inject_garbage(burst)

    sim, drv, got = run_faults(topology, fmt, inject)
    sent, have = delivered_equal_sent(sim, got)
    assert have == sent and sim.overrun_bytes == 0  # garbage between records loses nothing
    assert drv.stats.dropped == 0
    assert drv.stats.skipped_bytes == sum(map(len, garbage))
