"""Live driving benchmark: a Flock sample's arrival on the port -> goals set -> IK solved.

The simulator plays the shipped reaching recording (``examples/flock/reach.jsonl``, looped) with 4
birds at 100 Hz on a pty; the real driver decodes it; a :class:`SensorDrive` on the standard human
runs a frame as soon as a new measurement cycle is complete (the last bird's sample), always on
the newest samples (older ones are coalesced away, never queued), and the behavior loop solves.
Latency per frame = end of the solve - host arrival time of the newest sample used.

A 60 Hz display shows the newest solved pose at each refresh: a display frame is *skipped* when
no solve finished during its 16.7 ms. The row is the drive with bounded work per frame
(``frame_budget_ms``, :class:`~jackpy.behaviors.sensor_drive.FrameBudget`); the baseline is the
same drive with the loop's full settings, run in the same process on the same simulator and
driver, in alternating segments (so both see the same machine load).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from jackpy.bench.runner import Case, Result

REACH = Path(__file__).resolve().parents[3] / "examples" / "flock" / "reach.jsonl"
BUDGET_MS = 7.0
DISPLAY_HZ = 60.0
WARMUP_S = 0.25  # of each segment: the first frames catch up with the reach after a switch


def _reach_recording():
    from jackpy.devices.recording import read_recording

    if REACH.exists():
        return read_recording(REACH)
    raise FileNotFoundError(f"{REACH} is missing (run examples/flock/make_reach.py)")


class _Tally:
    """Per-frame figures of one drive over its segments."""

    def __init__(self) -> None:
        self.latency: list[float] = []
        self.step: list[float] = []
        self.palm: list[float] = []
        self.coalesced = 0
        self.display_frames = 0
        self.display_skipped = 0
        self.seconds = 0.0
        self.frames = 0

    def segment(self, solved: list[float], start: float, end: float) -> None:
        """Count 60 Hz display frames in [start, end) with no solve finishing in them."""
        ticks = np.arange(start, end, 1.0 / DISPLAY_HZ)
        done = np.searchsorted(np.sort(solved), ticks)
        got = np.diff(done) > 0
        self.display_frames += len(got)
        self.display_skipped += int(np.count_nonzero(~got))
        self.seconds += end - start


def _drive_segment(drive, drv, motion, seconds: float, tally: _Tally) -> None:
    start = time.perf_counter()
    measure_from = start + WARMUP_S
    end = start + seconds
    solved: list[float] = []
    last_bird = max(mt.bird for mt in drive.config.sensors.mounts)
    while time.perf_counter() < end:
        if motion.done:
            motion.play()  # loop the reach
        if drv.store.wait(last_bird, after_seq=drive.consumed.get(last_bird, -1), timeout=0.2) is None:
            continue
        r = drive.step()
        if r.solved < measure_from or r.latency_ms is None:
            continue
        solved.append(r.solved)
        tally.latency.append(r.latency_ms)
        tally.step.append(r.step_ms)
        tally.coalesced += r.skipped
        tally.frames += 1
        palms = [e for p, e in r.errors.items() if p.endswith("palm")]
        if palms:
            tally.palm.append(max(palms) * 1e3)
    tally.segment(solved, measure_from, end)


def _run(seconds: float) -> tuple[_Tally, _Tally, dict]:
    from jackpy.behaviors import BehaviorLoop
    from jackpy.behaviors.anatomy import human_anatomy
    from jackpy.behaviors.sensor_drive import DriveConfig, SensorDrive
    from jackpy.body.human import make_human
    from jackpy.devices.flock.driver import FlockDriver
    from jackpy.devices.flock.simulator import FlockSimulator
    from jackpy.devices.recording import FrameMotion
    from jackpy.devices.sensors import sensor_config_from_dict

    rec = _reach_recording()
    sensors = sensor_config_from_dict(rec.header["sensors"])
    motion = FrameMotion(rec)
    tallies = {"bounded": _Tally(), "full": _Tally()}
    with FlockSimulator(4, motion=motion, rate=100.0, autoconfig_delay=0.05) as sim:
        drv = FlockDriver(sim.paths[0], 4, measurement_rate=100.0, rts_reset=None, autoconfig_wait=0.08)
        drv.start()
        try:
            for b in range(1, 5):
                drv.store.wait(b, timeout=5.0)
            drives = {}
            for name, budget in (("bounded", BUDGET_MS), ("full", None)):
                fig = make_human("male", 50)
                drives[name] = SensorDrive(BehaviorLoop(fig, human_anatomy(fig)), drv,
                                           DriveConfig(sensors=sensors, frame_budget_ms=budget))
                drives[name].calibrate()
            motion.play()
            for _ in range(2):  # alternating segments: both drives see the same load
                for name in ("full", "bounded"):
                    _drive_segment(drives[name], drv, motion, seconds / 2, tallies[name])
            dropped = drv.stats.dropped
            over = drives["bounded"].budget.over
            cap = drives["bounded"].budget.cap
        finally:
            drv.stop()
    return tallies["bounded"], tallies["full"], {"dropped": dropped, "over_budget": over, "cap": cap}


def _latency_ik_case(quick: bool) -> Result:
    seconds = 3.0 if quick else 8.0
    ours, full, info = _run(seconds)

    def figures(t: _Tally, tag: str) -> dict:
        lat = np.array(t.latency) if t.latency else np.array([np.nan])
        return {f"{tag}p90_ms": float(np.percentile(lat, 90)),
                f"{tag}step_ms": float(np.median(t.step)) if t.step else float("nan"),
                f"{tag}solves_per_s": t.frames / t.seconds if t.seconds else 0.0,
                f"{tag}skipped_display_frames": t.display_skipped,
                f"{tag}display_frames": t.display_frames,
                f"{tag}coalesced_samples": t.coalesced,
                f"{tag}palm_error_mm": float(np.median(t.palm)) if t.palm else float("nan")}

    lat = np.array(ours.latency)
    base = float(np.median(full.latency)) if full.latency else None
    return Result("flock-latency-ik", float(np.median(lat)), float(np.percentile(lat, 90)), base,
                  {"birds": 4, "rate_hz": 100, "budget_ms": BUDGET_MS, **figures(ours, ""),
                   **figures(full, "full_"), **info})


CASES = [
    Case("flock-latency-ik", _latency_ik_case,
         "sample arrival on the port -> goals set -> IK solved (standard human, 4 birds at 100 Hz, "
         f"{BUDGET_MS:g} ms frame budget; baseline: full loop settings)"),
]
