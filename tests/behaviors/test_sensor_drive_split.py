"""Split frames of a live sensor drive (issue 20, flock-latency-ik): a sample's frame solves the
spine and the arms only (the body frozen), the loop's full step runs in SensorDrive.idle or every
``body_every``-th frame. Nothing here asserts wall time: frames and steps are counted, and an idle
step is given either no time (a deadline already past) or a minute."""

from __future__ import annotations

import time

import numpy as np
import pytest
from flock_support import (  # noqa: F401
    DRIVER_OPTIONS,
    PALMS,
    final_fixture,
    reach_fixture,
    reach_simulator,
)

from jackpy.behaviors import BehaviorLoop
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.behaviors.sensor_drive import DriveConfig, SensorDrive, replay_into
from jackpy.body.human import make_human
from jackpy.devices.flock.driver import FlockDriver
from jackpy.devices.sensors import sensor_config_from_dict
from jackpy.errors import DeviceError


def split_drive(reach, source=None, **kw) -> SensorDrive:
    fig = make_human("male", 50)
    cfg = DriveConfig(sensors=sensor_config_from_dict(reach.header["sensors"]), split=True, **kw)
    return SensorDrive(BehaviorLoop(fig, human_anatomy(fig)), source, cfg)


def test_split_frames_freeze_the_body_and_every_fourth_frame_steps_the_loop(reach, final):
    drive = split_drive(reach, body_every=4)
    fig = drive.loop.figure
    kinds, worst = [], 0.0
    before = fig.site_world("pelvis", "centre")
    for k, r in replay_into(drive, reach, speed=0, every=3):
        pelvis = fig.site_world("pelvis", "centre")
        if r.loop is None:  # a split frame: spine and arms; the legs, hence the pelvis, stay put
            assert r.notes == ["split frame"]
            assert np.allclose(pelvis, before)
        kinds.append(r.loop is None)
        worst = max(worst, *(r.errors[p] for p in PALMS))
        before = pelvis
    assert kinds[:8] == [True, True, True, False] * 2  # no idle step came: every 4th frame is full
    assert drive.split_frames == sum(kinds) and drive.idle_steps == 0
    assert worst < 0.02, f"worst palm error {worst * 100:.2f} cm"
    for p in PALMS:  # the hands ended on the recorded reach, the pelvis on the waist's
        assert np.linalg.norm(fig.site_world(*drive.sites[p])[:3, 3] - final[p][:3, 3]) < 0.005
    assert np.linalg.norm(fig.site_world("pelvis", "centre")[:3, 3] - final["pelvis"][:3, 3]) < 0.02


def test_split_drive_tracks_the_palms_as_closely_as_the_full_loop(reach):
    ends = {}
    for split in (False, True):
        fig = make_human("male", 50)
        drive = SensorDrive(BehaviorLoop(fig, human_anatomy(fig)), None,
                            DriveConfig(sensors=sensor_config_from_dict(reach.header["sensors"]),
                                        split=split, frame_budget_ms=1e-3))  # the 3-iteration floor
        errs = [max(r.errors[p] for p in PALMS) for _, r in replay_into(drive, reach, speed=0, every=2)]
        ends[split] = (float(np.median(errs)), float(np.percentile(errs, 90)))
    assert ends[True][0] <= ends[False][0] + 0.001 and ends[True][1] <= ends[False][1] + 0.002, ends


def test_idle_runs_the_owed_loop_step_only_with_time_left(reach):
    drive = split_drive(reach)
    frames = list(reach.frames())
    drive.calibrate(frames[0])
    assert drive.idle(time.perf_counter() + 60.0) is None  # nothing owed yet
    r = drive.step(frames[60], live=False)
    assert r.loop is None and drive.split_frames == 1
    assert drive.idle(time.perf_counter() + 60.0) is None  # one split frame: idle_every=2 not reached
    drive.step(frames[61], live=False)
    assert drive.idle(time.perf_counter() - 1.0) is None and drive.idle_steps == 0  # no time left
    report = drive.idle(time.perf_counter() + 60.0)
    assert report is not None and not report.timed_out and drive.idle_steps == 1
    assert drive.idle(time.perf_counter() + 60.0) is None  # owed nothing again
    for k in (62, 63, 64):  # the idle step counts as the loop's: three split frames again, then a full one
        assert drive.step(frames[k], live=False).loop is None
    assert drive.step(frames[65], live=False).loop is not None and drive.split_frames == 5
    for k in (66, 67, 68):  # body_every - 1 split frames owed: the idle step runs without time left
        drive.step(frames[k], live=False)
    assert drive.idle(time.perf_counter() - 1.0) is not None and drive.idle_steps == 2
    assert drive.step(frames[69], live=False).loop is None
    for knob in ("body_every", "idle_every"):
        with pytest.raises(DeviceError, match=knob):
            split_drive(reach, **{knob: 0})


def test_live_split_reach_through_simulator_and_driver(reach, final):
    """The bench's drive on the real stack: split frames at each cycle, idle steps before the next
    cycle is due (whether one fits depends on the machine; the pose must not)."""
    motion, sim = reach_simulator(reach)
    with sim:
        drv = FlockDriver(sim.paths[0], 4, **DRIVER_OPTIONS)
        drv.start()
        try:
            for b in range(1, 5):
                assert drv.store.wait(b, timeout=5.0) is not None
            drive = split_drive(reach, drv, frame_budget_ms=7.0)
            drive.calibrate()
            motion.play()
            worst, after_end = 0.0, 0
            for _ in range(20000):  # a cap, not a clock: the test ends on frames counted
                if drv.store.wait(4, after_seq=drive.consumed[4], timeout=1.0) is None:
                    continue
                r = drive.step()
                worst = max(worst, *(r.errors[p] for p in PALMS))
                drive.idle(r.arrival + 0.009)
                if motion.done:
                    after_end += 1
                    if after_end >= 20:
                        break
        finally:
            drv.stop()
    assert motion.done and drive.split_frames > 0
    assert worst < 0.02, f"worst palm error {worst * 100:.2f} cm"
    fig = drive.loop.figure
    for p in PALMS:
        assert np.linalg.norm(fig.site_world(*drive.sites[p])[:3, 3] - final[p][:3, 3]) < 0.005
    assert np.linalg.norm(fig.site_world("pelvis", "centre")[:3, 3] - final["pelvis"][:3, 3]) < 0.02
