"""Bounded work per frame for a live sensor drive (issue 20, flock-latency-ik): FrameBudget cuts and
restores the loop's solver iterations; a drive held to its minimum (3 iterations a solve) still
tracks the shipped reach as closely as the full loop (the solves warm-start from the last frame)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from jackpy.behaviors import BehaviorLoop
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.behaviors.sensor_drive import DriveConfig, FrameBudget, SensorDrive, replay_into
from jackpy.body.human import make_human
from jackpy.devices.recording import read_recording
from jackpy.devices.sensors import sensor_config_from_dict
from jackpy.errors import DeviceError

REACH = Path(__file__).resolve().parents[2] / "examples" / "flock" / "reach.jsonl"


def human_loop() -> BehaviorLoop:
    fig = make_human("male", 50)
    return BehaviorLoop(fig, human_anatomy(fig))


def test_frame_budget_cuts_in_proportion_and_gives_back_slowly():
    loop = human_loop()
    full_it, full_passes = loop.max_iterations, loop.max_passes
    b = FrameBudget(loop, 5.0)
    b.update(20.0)  # four times over: the cap falls to a quarter
    assert loop.max_iterations == full_it * 5 // 20 and b.over == 1
    for _ in range(200):
        b.update(40.0)
    assert loop.max_iterations == b.min_iterations == 3  # never below the floor
    b.update(4.0)  # within the budget but not well under it: unchanged
    assert loop.max_iterations == 3
    for _ in range(full_it):
        b.update(1.0)
    assert loop.max_iterations == full_it and loop.max_passes == full_passes  # passes never cut
    with pytest.raises(DeviceError, match="budget"):
        FrameBudget(loop, 0.0)


def test_one_iteration_a_frame_still_tracks_the_reach():
    rec = read_recording(REACH)
    sensors = sensor_config_from_dict(rec.header["sensors"])
    finals = {}
    for budget in (None, 1e-3):  # 1 us: every frame is over it, so the floor of 3 iterations
        drive = SensorDrive(human_loop(), None, DriveConfig(sensors=sensors, frame_budget_ms=budget))
        for _, r in replay_into(drive, rec, speed=0, every=2):
            pass
        if budget is not None:
            assert drive.loop.max_iterations == 3
            assert drive.budget.over == drive.frames
        finals[budget] = r.errors
    for part, e in finals[1e-3].items():
        assert e <= finals[None][part] + 0.002, (part, e, finals[None][part])  # within 2 mm of the full loop
    assert max(finals[1e-3][p] for p in ("left_palm", "right_palm")) < 0.005


def test_spine_correction_warm_starts_from_the_last_frame():
    rec = read_recording(REACH)
    drive = SensorDrive(human_loop(), None, DriveConfig(sensors=sensor_config_from_dict(rec.header["sensors"])))
    reports = [r for _, r in replay_into(drive, rec, speed=0, every=30)]
    assert np.any(drive._spine_offset != 0.0)  # the command differs from the target by a correction
    last = reports[-1]
    fig = drive.loop.figure
    got = drive._relative(fig.site_world(*drive.sites["pelvis"]), fig.site_world(*drive.sites["neck"]))
    assert np.allclose(got, last.spine_target, atol=2e-3)  # the neck turned by the target
