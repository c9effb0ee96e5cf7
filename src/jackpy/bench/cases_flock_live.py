"""Live driving benchmark: a Flock sample's arrival on the port -> goals set -> IK solved.

The simulator plays the shipped reaching recording (``examples/flock/reach.jsonl``, looped) with 4
birds at 100 Hz on a pty; the real driver decodes it; a :class:`SensorDrive` on the standard human
runs a frame as soon as a new measurement cycle is complete (the last bird's sample), always on
the newest samples (older ones are coalesced away, never queued), and the behavior loop solves.
Latency per frame = end of the solve - host arrival time of the newest sample used.

A 60 Hz display shows the newest solved pose at each refresh: a display frame is *skipped* when
no solve finished during its 16.7 ms. The row is the drive with bounded work per frame
(``frame_budget_ms``, :class:`~jackpy.behaviors.sensor_drive.FrameBudget`) and split frames (a
sample's frame solves the spine and arms; the pelvis, balance, stepping and legs run in
:meth:`~jackpy.behaviors.sensor_drive.SensorDrive.idle` before the next sample is due); the
baseline is the same drive with the loop's full settings, every frame a full loop step, run in the
same process on the same simulator and driver, in alternating segments (so both see the same machine
load). Each segment plays the whole reach from its start, so both drives solve the same motion. The
set-up's objects are frozen out of the cyclic garbage collector (``gc.freeze``) while the drives
run, as a live session would after loading. Palm error: the farther palm's distance from its sensor
target after each frame's solve (median and p90); pelvis error: the pelvis site's (median).
``cpu_ms_per_frame``: the driving thread's CPU time per sample frame, idle steps included (the work,
whatever the load).
"""

from __future__ import annotations

import gc
import time
from pathlib import Path

import numpy as np

from jackpy.bench.runner import Case, Result

REACH = Path(__file__).resolve().parents[3] / "examples" / "flock" / "reach.jsonl"
BUDGET_MS = 7.0
RATE_HZ = 100.0
DISPLAY_HZ = 60.0
WARMUP_S = 0.25  # of each segment: the first frames catch up with the reach's start after a switch
IDLE_MARGIN_S = 0.001  # an idle step ends this long before the next sample is due
SPLIT = True  # the bounded drive's split frames (DriveConfig.split)


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
        self.pelvis: list[float] = []
        self.coalesced = 0
        self.display_frames = 0
        self.display_skipped = 0
        self.seconds = 0.0
        self.frames = 0
        self.cpu_s = 0.0  # the driving thread's CPU time over whole segments (frames and idle steps)
        self.all_frames = 0

    def segment(self, solved: list[float], start: float, end: float) -> None:
        """Count 60 Hz display frames in [start, end) with no solve finishing in them."""
        ticks = np.arange(start, end, 1.0 / DISPLAY_HZ)
        done = np.searchsorted(np.sort(solved), ticks)
        got = np.diff(done) > 0
        self.display_frames += len(got)
        self.display_skipped += int(np.count_nonzero(~got))
        self.seconds += end - start


def _drive_segment(drive, drv, motion, tally: _Tally) -> None:
    """Drive the whole reach once, from its start."""
    motion.play()
    cpu0 = time.thread_time()
    frames0 = drive.frames
    start = time.perf_counter()
    measure_from = start + WARMUP_S
    solved: list[float] = []
    last_bird = max(mt.bird for mt in drive.config.sensors.mounts)
    while not motion.done:
        if drv.store.wait(last_bird, after_seq=drive.consumed.get(last_bird, -1), timeout=0.2) is None:
            continue
        r = drive.step()
        if drive.config.split and r.arrival is not None:
            drive.idle(r.arrival + 1.0 / RATE_HZ - IDLE_MARGIN_S)
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
        if "pelvis" in r.errors:
            tally.pelvis.append(r.errors["pelvis"] * 1e3)
    tally.segment(solved, measure_from, time.perf_counter())
    tally.cpu_s += time.thread_time() - cpu0
    tally.all_frames += drive.frames - frames0


def _run(rounds: int) -> tuple[_Tally, _Tally, dict]:
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
    with FlockSimulator(4, motion=motion, rate=RATE_HZ, autoconfig_delay=0.05) as sim:
        drv = FlockDriver(sim.paths[0], 4, measurement_rate=RATE_HZ, rts_reset=None, autoconfig_wait=0.08)
        drv.start()
        try:
            for b in range(1, 5):
                drv.store.wait(b, timeout=5.0)
            drives = {}
            for name, budget in (("bounded", BUDGET_MS), ("full", None)):
                fig = make_human("male", 50)
                drives[name] = SensorDrive(BehaviorLoop(fig, human_anatomy(fig)), drv,
                                           DriveConfig(sensors=sensors, frame_budget_ms=budget,
                                                       split=SPLIT and budget is not None))
                drives[name].calibrate()
            # what a live session holds after loading (figures, compiled problems) stays out of the
            # cyclic collector's scans: a full collection of this process inside a frame took
            # 120 ms (seven display frames); the frames' own garbage is still collected
            gc.collect()
            gc.freeze()
            try:
                for _ in range(rounds):  # alternating segments: both drives see the same load
                    for name in ("full", "bounded"):
                        _drive_segment(drives[name], drv, motion, tallies[name])
            finally:
                gc.unfreeze()
            dropped = drv.stats.dropped
            ours = drives["bounded"]
            info = {"dropped": dropped, "over_budget": ours.budget.over, "cap": ours.budget.cap,
                    "split_frames": ours.split_frames, "idle_steps": ours.idle_steps}
        finally:
            drv.stop()
    return tallies["bounded"], tallies["full"], info


def _latency_ik_case(quick: bool) -> Result:
    ours, full, info = _run(2 if quick else 4)

    def figures(t: _Tally, tag: str) -> dict:
        lat = np.array(t.latency) if t.latency else np.array([np.nan])
        return {f"{tag}p90_ms": float(np.percentile(lat, 90)),
                f"{tag}step_ms": float(np.median(t.step)) if t.step else float("nan"),
                f"{tag}solves_per_s": t.frames / t.seconds if t.seconds else 0.0,
                f"{tag}cpu_ms_per_frame": t.cpu_s * 1e3 / t.all_frames if t.all_frames else float("nan"),
                f"{tag}skipped_display_frames": t.display_skipped,
                f"{tag}display_frames": t.display_frames,
                f"{tag}coalesced_samples": t.coalesced,
                f"{tag}palm_error_mm": float(np.median(t.palm)) if t.palm else float("nan"),
                f"{tag}palm_error_p90_mm": float(np.percentile(t.palm, 90)) if t.palm else float("nan"),
                f"{tag}pelvis_error_mm": float(np.median(t.pelvis)) if t.pelvis else float("nan")}

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
