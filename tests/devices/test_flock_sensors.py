"""Sensor frames, calibration, targets, spine angles, one-euro filters."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from jackpy.devices import sensors as sn
from jackpy.devices.filters import OneEuroFilter, OneEuroPoseFilter
from jackpy.devices.flock.protocol import Format, make_record
from jackpy.errors import DeviceError, ParseError


def test_transmitter_axes_to_world():
    c = sn.TRANSMITTER_TO_WORLD
    assert np.allclose(c @ [1, 0, 0], [0, 0, 1])   # forward -> +z
    assert np.allclose(c @ [0, 1, 0], [-1, 0, 0])  # right -> -x (figure facing +z, y up)
    assert np.allclose(c @ [0, 0, 1], [0, -1, 0])  # down -> -y
    assert np.isclose(np.linalg.det(c), 1.0)


def test_sensor_pose_units_and_frames():
    rec = make_record(Format.POSITION_ANGLES, (10, 0, -20), (90, 0, 0))  # 10 in ahead, 20 in up
    pose = sn.sensor_pose(rec)
    assert np.allclose(pose[:3, 3], [0, 20 * 0.0254, 10 * 0.0254], atol=1e-4)
    # azimuth +90 (turned right about down): the sensor's forward (+z) now points to world -x
    assert np.allclose(pose[:3, :3] @ [0, 0, 1], [-1, 0, 0], atol=1e-3)
    assert np.allclose(pose[:3, :3] @ [0, 1, 0], [0, 1, 0], atol=1e-3)
    for fmt in (Format.POSITION_MATRIX, Format.POSITION_QUATERNION):
        other = sn.sensor_pose(make_record(fmt, (10, 0, -20), (90, 0, 0)))
        assert np.allclose(other, pose, atol=2e-3)
    assert sn.sensor_pose(make_record(Format.POSITION)) is None
    assert sn.sensor_pose(make_record(Format.POSITION_MATRIX, (0, 0, 0))) is not None


def test_calibrate_then_targets_hit_the_reference():
    rng = np.random.default_rng(1)
    recs = {b: make_record(Format.POSITION_ANGLES, rng.uniform(-20, 20, 3), rng.uniform(-60, 60, 3))
            for b in (1, 2, 3, 4)}
    ref = {}
    for i, part in enumerate(sn.PARTS):
        t = np.eye(4)
        t[:3, :3] = sn._rot(1, 0.3 * i) @ sn._rot(0, 0.1)
        t[:3, 3] = [0.2 * i, 1.0 + 0.1 * i, 0.5]
        ref[part] = t
    cal = sn.calibrate(recs, ref)
    targets = sn.sensor_targets(recs, cal)
    for part in sn.PARTS:
        assert np.allclose(targets[part], ref[part], atol=1e-9)
    # transmitter placement is yaw + translation only: y stays up
    assert np.allclose(cal.world_from_transmitter[:3, 1], [0, 1, 0])
    # moving the waist sensor 10 in forward moves the pelvis target 0.254 m along its heading
    moved = dict(recs)
    p = recs[1].position
    moved[1] = make_record(Format.POSITION_ANGLES, (p[0] + 10, p[1], p[2]), recs[1].angles)
    d = sn.sensor_targets(moved, cal)["pelvis"][:3, 3] - targets["pelvis"][:3, 3]
    assert math.isclose(np.linalg.norm(d), 0.254, abs_tol=1e-3) and abs(d[1]) < 1e-3


def test_missing_and_bad_samples():
    cal = sn.uncalibrated()
    assert set(sn.sensor_targets({2: make_record(Format.POSITION_ANGLES)}, cal)) == {"neck"}
    with pytest.raises(DeviceError):
        sn.calibrate({}, {"pelvis": np.eye(4)})
    with pytest.raises(DeviceError):
        sn.calibrate({1: make_record(Format.ANGLES)}, {"pelvis": np.eye(4)})


def test_spine_angles_round_trip():
    flex, twist, bend = 0.3, -0.2, 0.15
    neck = np.eye(4)
    neck[:3, :3] = sn._rot(1, twist) @ sn._rot(0, flex) @ sn._rot(2, bend)
    pelvis = np.eye(4)
    pelvis[:3, :3] = sn._rot(1, 0.7)
    neck[:3, :3] = pelvis[:3, :3] @ neck[:3, :3]
    assert np.allclose(sn.spine_angles(pelvis, neck), (flex, twist, bend))


def test_load_sensor_config(tmp_path):
    f = tmp_path / "s.json"
    f.write_text(json.dumps({"transmitter": {"position_m": [0, 1, 0], "yaw_deg": 90},
                             "sensors": [{"bird": 2, "part": "pelvis",
                                          "offset": {"position_m": [0, 0, 0.1]}}]}))
    cfg = sn.load_sensor_config(f)
    assert cfg.mount("pelvis").bird == 2 and np.allclose(cfg.mount("pelvis").offset[:3, 3], [0, 0, 0.1])
    assert np.allclose(cfg.world_from_transmitter[:3, 2], [1, 0, 0])
    f.write_text('{"sensors": [{"bird": 1}]}')
    with pytest.raises(ParseError, match="part"):
        sn.load_sensor_config(f)
    f.write_text('{"sensors": [')
    with pytest.raises(ParseError):
        sn.load_sensor_config(f)


def test_one_euro_smooths_rest_and_follows_motion():
    rng = np.random.default_rng(0)
    f = OneEuroFilter(min_cutoff=1.0, beta=0.0)
    out = [f(1.0 + 0.01 * rng.standard_normal(), i / 100) for i in range(200)]
    assert np.std(out[100:]) < 0.003
    g = OneEuroFilter(min_cutoff=1.0, beta=5.0)
    ramp = [g(i / 100, i / 100) for i in range(200)]
    assert abs(ramp[-1] - 1.99) < 0.05  # little lag while moving
    pf = OneEuroPoseFilter()
    for i in range(50):
        t = np.eye(4)
        t[:3, :3] = sn._rot(1, 0.5)
        res = pf(t, i / 100)
    assert np.allclose(res, t, atol=1e-6)
    with pytest.raises(DeviceError):
        OneEuroFilter(min_cutoff=0)


def test_smoother_keeps_parts():
    sm = sn.TargetSmoother()
    out = sm({"pelvis": np.eye(4)}, 0.0)
    assert set(out) == {"pelvis"} and np.allclose(out["pelvis"], np.eye(4))
