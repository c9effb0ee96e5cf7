"""Live driving benchmark: a Flock sample's arrival on the port -> goals set -> IK solved.

The simulator plays the shipped reaching recording (``examples/flock/reach.jsonl``, looped) with 4
birds at 100 Hz on a pty; the real driver decodes it; a :class:`SensorDrive` on the standard human
takes the newest samples each frame (waiting only when nothing new has come) and runs the
behavior loop. Latency per frame = end of the solve - host arrival time of the newest sample used.
``targets_only_ms`` is the same pipeline without the behavior loop and IK (samples -> targets),
for comparison; no ratio is printed, since the two do different work.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from jackpy.bench.runner import Case, Result

REACH = Path(__file__).resolve().parents[3] / "examples" / "flock" / "reach.jsonl"


def _reach_recording():
    from jackpy.devices.recording import read_recording

    if REACH.exists():
        return read_recording(REACH)
    raise FileNotFoundError(f"{REACH} is missing (run examples/flock/make_reach.py)")


def _run(seconds: float, solve: bool) -> tuple[np.ndarray, dict]:
    from jackpy.behaviors import BehaviorLoop
    from jackpy.behaviors.anatomy import human_anatomy
    from jackpy.behaviors.sensor_drive import SensorDrive
    from jackpy.body.human import make_human
    from jackpy.devices.flock.driver import FlockDriver
    from jackpy.devices.flock.simulator import FlockSimulator
    from jackpy.devices.recording import FrameMotion
    from jackpy.devices.sensors import sensor_config_from_dict, sensor_targets

    rec = _reach_recording()
    motion = FrameMotion(rec)
    lat, steps, skipped = [], [], 0
    with FlockSimulator(4, motion=motion, rate=100.0, autoconfig_delay=0.05) as sim:
        drv = FlockDriver(sim.paths[0], 4, measurement_rate=100.0, rts_reset=None, autoconfig_wait=0.05)
        drv.start()
        try:
            for b in range(1, 5):
                drv.store.wait(b, timeout=5.0)
            fig = make_human("male", 50)
            drive = SensorDrive(BehaviorLoop(fig, human_anatomy(fig)), drv,
                                sensor_config_from_dict(rec.header["sensors"]))
            drive.calibrate()
            motion.play()
            end = time.perf_counter() + seconds
            while time.perf_counter() < end:
                if motion.done:
                    motion.play()  # loop the reach
                drv.store.wait(4, after_seq=drive.consumed.get(4, -1), timeout=0.2)
                if solve:
                    r = drive.step()
                    if r.latency_ms is not None:
                        lat.append(r.latency_ms)
                        steps.append(r.step_ms)
                        skipped += r.skipped
                else:  # baseline: read, account and compute targets only
                    snap = drv.snapshot()
                    fresh, sk = drive._account(snap)
                    sensor_targets(snap, drive.calibration)
                    if fresh:
                        lat.append((time.perf_counter() - max(snap[b].time for b in fresh)) * 1e3)
                        skipped += sk
            st = drive.status()
        finally:
            drv.stop()
    return np.array(lat), {"frames": len(lat), "skipped": skipped, "dropped": st.dropped,
                           "step_ms": float(np.median(steps)) if steps else 0.0}


def _latency_ik_case(quick: bool) -> Result:
    seconds = 3.0 if quick else 8.0
    lat, info = _run(seconds, solve=True)
    base, _ = _run(1.0 if quick else 2.0, solve=False)
    return Result("flock-latency-ik", float(np.median(lat)), float(np.percentile(lat, 90)), None,
                  {"targets_only_ms": float(np.median(base)), "birds": 4, "rate_hz": 100, "frames": info["frames"], "fps": info["frames"] / seconds,
                   "step_ms": info["step_ms"], "skipped": info["skipped"], "dropped": info["dropped"]})


CASES = [
    Case("flock-latency-ik", _latency_ik_case,
         "sample arrival on the port -> goals set -> IK solved (standard human, 4 birds at 100 Hz)"),
]
