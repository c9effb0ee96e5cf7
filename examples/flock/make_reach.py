"""Make ``reach.jsonl``: four Flock birds recording the standard human reaching forward.

The motion is known exactly: the standard male 50th percentile stands in the neutral pose for
0.5 s (the calibration pose), then over 2 s bends the spine 10° forward and twists it 8°, raises
the right arm forward to a reach in front of the chest and lifts the left forearm a little, then
holds for 0.5 s. Each frame (100 Hz) the world poses of the pelvis centre, the base of the neck
(``t1.base``) and both palm centres are computed by forward kinematics, carried to where the
sensors sit on the body (``MOUNTS``), expressed in the transmitter's frame (the inverse of the
transmitter placement and of jackpy's axis change), quantised into POSITION/ANGLES records and
written with :class:`jackpy.devices.recording.Recorder`.

The transmitter stands level at ``TRANSMITTER`` (yaw only), behind the operator, so every sensor
lies in its forward hemisphere and within ±36 inches on each axis. The waist sensor's mount is the
sensor configuration's offset (``reach-sensors.json``), so calibration places the transmitter
exactly; the other mounts are unknown to jackpy and are captured by calibration.

Run:  python examples/flock/make_reach.py   (writes reach.jsonl and reach-sensors.json here)
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from jackpy.behaviors.anatomy import human_anatomy
from jackpy.behaviors.torso import bend_spine
from jackpy.body.human import make_human
from jackpy.devices.flock.driver import Sample
from jackpy.devices.flock.protocol import Format, angles_from_rotation, make_record
from jackpy.devices.recording import Recorder
from jackpy.devices.sensors import (
    INCH,
    TRANSMITTER_TO_WORLD,
    sensor_config_from_dict,
    sensor_pose,
)

HERE = Path(__file__).resolve().parent
RATE = 100.0
SECONDS = 3.0
PARTS = {1: ("pelvis", ("pelvis", "centre")), 2: ("neck", ("t1", "base")),
         3: ("left_palm", ("left_palm", "palm_centre")), 4: ("right_palm", ("right_palm", "palm_centre"))}
TRANSMITTER = {"position_m": [0.05, 1.05, -0.35], "yaw_deg": 20.0}
#: the sensor configuration shipped with the recording: the waist sensor's offset (sensor -> site)
CONFIG = {
    "transmitter": TRANSMITTER,
    "sensors": [
        {"bird": 1, "part": "pelvis", "offset": {"position_m": [0.0, -0.03, -0.11], "rotation_deg": [8, 180, 0]}},
        {"bird": 2, "part": "neck"},
        {"bird": 3, "part": "left_palm"},
        {"bird": 4, "part": "right_palm"},
    ],
    "conjugate_quaternion": True,
}


def _rot(rx: float, ry: float, rz: float) -> np.ndarray:
    """Rz·Ry·Rx (degrees) as a 4x4."""
    def r(axis: int, a: float) -> np.ndarray:
        c, s = np.cos(np.radians(a)), np.sin(np.radians(a))
        i, j = [(1, 2), (2, 0), (0, 1)][axis]
        m = np.eye(4)
        m[i, i] = m[j, j] = c
        m[i, j], m[j, i] = -s, s
        return m
    return r(2, rz) @ r(1, ry) @ r(0, rx)


def _at(x: float, y: float, z: float) -> np.ndarray:
    t = np.eye(4)
    t[:3, 3] = (x, y, z)
    return t


def mounts() -> dict[str, np.ndarray]:
    """Where each sensor sits on its site (site frame -> sensor frame), the body's truth."""
    cfg = sensor_config_from_dict(CONFIG)
    return {"pelvis": np.linalg.inv(cfg.mount("pelvis").offset),
            "neck": _at(0.0, 0.02, -0.07) @ _rot(-15, 170, 5),
            "left_palm": _at(0.01, 0.02, -0.015) @ _rot(30, -40, 80),
            "right_palm": _at(-0.01, 0.02, 0.015) @ _rot(-20, 35, -70)}


def progress(t: float) -> float:
    """Smoothstep from 0 at 0.5 s to 1 at 2.5 s."""
    u = min(1.0, max(0.0, (t - 0.5) / 2.0))
    return u * u * (3.0 - 2.0 * u)


def pose_figure(fig, anatomy, q0: np.ndarray, u: float) -> None:
    """The known motion at progress ``u`` (joint angles, forward kinematics)."""
    fig.q = q0
    bend_spine(fig, anatomy, np.radians(10.0) * u, 0.0, np.radians(8.0) * u)
    d = np.radians
    sh = fig.joint("right_shoulder").displacement
    sh[1] = sh[1] + (d(65.0) - sh[1]) * u
    sh[2] = d(80.0) * u
    fig.joint("right_elbow").displacement[0] = d(35.0) * u
    fig.joint("right_forearm_twist_1").displacement[0] = d(-20.0) * u
    fig.joint("right_wrist").displacement[1] = d(10.0) * u
    lsh = fig.joint("left_shoulder").displacement
    lsh[1] = lsh[1] + (d(20.0) - lsh[1]) * u
    fig.joint("left_elbow").displacement[0] = d(30.0) * u


def site_poses(fig) -> dict[str, np.ndarray]:
    return {part: fig.site_world(*site) for part, site in PARTS.values()}


def record_for(bird: int, sensor_world: np.ndarray, world_from_transmitter: np.ndarray):
    """The POSITION/ANGLES record bird ``bird`` sends at world pose ``sensor_world``."""
    p = np.linalg.inv(world_from_transmitter) @ sensor_world  # sensor in the transmitter (y-up axes)
    r_t = TRANSMITTER_TO_WORLD.T @ p[:3, :3] @ TRANSMITTER_TO_WORLD
    pos_in = TRANSMITTER_TO_WORLD.T @ p[:3, 3] / INCH
    if pos_in[0] <= 0 or np.max(np.abs(pos_in)) >= 36.0:
        raise SystemExit(f"bird {bird} at {pos_in} in leaves the transmitter's forward hemisphere or range")
    rec = make_record(Format.POSITION_ANGLES, pos_in, np.degrees(angles_from_rotation(r_t)), address=bird)
    back = sensor_pose(rec)
    err = np.linalg.norm(back[:3, 3] - p[:3, 3])
    if err > 1e-4 or np.linalg.norm(back[:3, :3] - p[:3, :3]) > 1e-3:
        raise SystemExit(f"bird {bird}: the record does not round-trip ({err * 1e3:.3f} mm)")
    return rec


def main(out: Path = HERE / "reach.jsonl") -> None:
    fig = make_human("male", 50)
    anatomy = human_anatomy(fig)
    q0 = fig.q.copy()
    world = sensor_config_from_dict(CONFIG).world_from_transmitter
    mount = mounts()
    n = round(SECONDS * RATE)
    final = {}
    with Recorder(out, meta={"description": "standard human (male, 50th) reaching forward with the right hand",
                             "figure": {"sex": "male", "percentile": 50}, "rate_hz": RATE,
                             "calibrate_frame": 0, "sensors": CONFIG}) as rec:
        for k in range(n):
            t = k / RATE
            pose_figure(fig, anatomy, q0, progress(t))
            sites = site_poses(fig)
            for bird, (part, _) in PARTS.items():
                record = record_for(bird, sites[part] @ mount[part], world)
                rec.add(Sample(bird, record, t + 2e-4 * (bird - 1), k))
            final = sites
    # the true final poses travel in a side file so a test can check the figure's end posture
    (out.with_name(out.stem + "-final.json")).write_text("{\n" + ",\n".join(
        f' "{part}": {json.dumps(np.round(pose, 6).tolist())}' for part, pose in final.items()) + "\n}\n")
    (out.with_name("reach-sensors.json")).write_text(json.dumps(CONFIG, indent=1) + "\n")
    print(f"wrote {out} ({n} frames, {len(PARTS)} birds)")


if __name__ == "__main__":
    main()
