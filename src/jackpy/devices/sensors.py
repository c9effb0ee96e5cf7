"""From Flock samples to world-space targets for body parts (no IK, no figure here).

Frames. The transmitter frame is x forward, y right, z down (inches). jackpy's world is y up,
metres, and a figure faces +z, so its right is −x. The fixed change of axes is

    C = [[0, -1,  0],      world = C @ transmitter:  x_t (forward) -> +z_w
         [0,  0, -1],                                y_t (right)   -> −x_w
         [1,  0,  0]]                                z_t (down)    -> −y_w

(det C = +1). A sensor's pose is expressed the same way on both sides, so a sensor at zero
angles has the identity orientation in the world: ``pose = [[C R Cᵀ, 0.0254 C p], [0, 1]]``
where R is the sensor-to-transmitter rotation and p the position in inches.

Targets. ``target(part) = world_from_transmitter @ pose(sensor) @ offset(part)``: the offset is
the sensor-to-segment-site transform, captured by :func:`calibrate` with the operator standing
in a known pose. The default configuration is Jack's four sensors (book §4.5): waist -> pelvis,
base of the neck -> neck, palms -> left/right palm sites.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from jackpy import jsonfile
from jackpy.devices.filters import OneEuroPoseFilter
from jackpy.devices.flock.driver import Sample
from jackpy.devices.flock.protocol import Record
from jackpy.errors import DeviceError, ParseError

INCH = 0.0254  # metres

#: Transmitter axes (x forward, y right, z down) -> world axes (y up, figure faces +z).
TRANSMITTER_TO_WORLD = np.array([[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]])

PARTS = ("pelvis", "neck", "left_palm", "right_palm")


@dataclass(frozen=True)
class SensorMount:
    """Bird ``bird`` (FBB address; 0 standalone) worn on ``part``; ``offset`` (4×4, metres)
    takes the sensor frame (y-up convention) to the body part's site."""

    bird: int
    part: str
    offset: np.ndarray = field(default_factory=lambda: np.eye(4))


@dataclass
class SensorConfig:
    """Which bird is on which body part, and where the transmitter sits in the world (4×4)."""

    mounts: list[SensorMount]
    world_from_transmitter: np.ndarray = field(default_factory=lambda: np.eye(4))
    conjugate_quaternion: bool = True  # quaternion sign convention, spec §3.4

    def mount(self, part: str) -> SensorMount | None:
        return next((m for m in self.mounts if m.part == part), None)


def default_config() -> SensorConfig:
    """Jack's four sensors: bird 1 waist, 2 base of neck, 3 left palm, 4 right palm."""
    return SensorConfig([SensorMount(i + 1, part) for i, part in enumerate(PARTS)])


def load_sensor_config(path: str | os.PathLike) -> SensorConfig:
    """Read a JSON sensor configuration::

        {"transmitter": {"position_m": [0, 1, 0], "yaw_deg": 0},
         "sensors": [{"bird": 1, "part": "pelvis",
                      "offset": {"position_m": [0, 0, 0.1], "rotation_deg": [0, 0, 0]}}, ...],
         "conjugate_quaternion": true}

    ``rotation_deg`` is (x, y, z) applied as Rz·Ry·Rx in the y-up sensor frame; ``yaw_deg`` turns
    the transmitter about world y. Errors name the file and what is wrong.
    """
    name = str(path)
    try:
        data = jsonfile.load(path, ParseError)
    except OSError as exc:
        raise DeviceError(f"cannot read sensor configuration {name}: {exc.strerror or exc}") from None
    except ValueError:  # a name with a NUL byte
        raise DeviceError(f"cannot read sensor configuration {name!r}: not a valid file name") from None
    return sensor_config_from_dict(data, name)


def sensor_config_from_dict(data: Mapping, name: str = "<sensor configuration>") -> SensorConfig:
    """A :class:`SensorConfig` from the JSON object of :func:`load_sensor_config` (e.g. one kept in
    a recording's header); errors raise :class:`ParseError` naming ``name`` and the key path
    (``sensors[1].bird: expected an integer in 0..126, found 200``)."""
    try:
        data = jsonfile.obj(data, "")
        tx = jsonfile.obj(data.get("transmitter", {}), "transmitter")
        world = _transform(jsonfile.vector(tx.get("position_m", [0, 0, 0]), "transmitter.position_m", 3),
                           [0, jsonfile.num(tx.get("yaw_deg", 0.0), "transmitter.yaw_deg"), 0])
        mounts = []
        for k, s in enumerate(jsonfile.arr(jsonfile.required(data, "sensors", ""), "sensors")):
            where = f"sensors[{k}]"
            s = jsonfile.obj(s, where)
            off = jsonfile.obj(s.get("offset", {}), f"{where}.offset")
            bird = jsonfile.integer(jsonfile.required(s, "bird", where), f"{where}.bird", 0, 126)
            part = jsonfile.string(jsonfile.required(s, "part", where), f"{where}.part")
            mounts.append(SensorMount(bird, part, _transform(
                jsonfile.vector(off.get("position_m", [0, 0, 0]), f"{where}.offset.position_m", 3),
                jsonfile.vector(off.get("rotation_deg", [0, 0, 0]), f"{where}.offset.rotation_deg", 3))))
        if len({m.bird for m in mounts}) != len(mounts) or len({m.part for m in mounts}) != len(mounts):
            raise jsonfile.Invalid("sensors", "each bird and each part may appear once")
        conjugate = jsonfile.boolean(data.get("conjugate_quaternion", True), "conjugate_quaternion")
        return SensorConfig(mounts, world, conjugate)
    except jsonfile.Invalid as exc:
        raise jsonfile.schema_error(ParseError, name, exc) from None


def _transform(position, rotation_deg) -> np.ndarray:
    pos = np.asarray(position, dtype=float)
    rx, ry, rz = np.radians(np.asarray(rotation_deg, dtype=float))
    if pos.shape != (3,):
        raise ValueError("a position needs three numbers")
    t = np.eye(4)
    t[:3, :3] = _rot(2, rz) @ _rot(1, ry) @ _rot(0, rx)
    t[:3, 3] = pos
    return t


def _rot(axis: int, a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[i, i] = r[j, j] = c
    r[i, j], r[j, i] = -s, s
    return r


def sensor_pose(record: Record, conjugate_quaternion: bool = True) -> np.ndarray | None:
    """4×4 pose of a sensor relative to the transmitter, in world axes and metres (module doc);
    None when the record lacks position or orientation or the sensor is saturated."""
    r = record.rotation(conjugate_quaternion)
    if r is None or record.position is None or record.saturated:
        return None
    t = np.eye(4)
    t[:3, :3] = TRANSMITTER_TO_WORLD @ r @ TRANSMITTER_TO_WORLD.T
    t[:3, 3] = TRANSMITTER_TO_WORLD @ np.asarray(record.position) * INCH
    return t


@dataclass
class Calibration:
    """Captured transmitter placement and per-part sensor-to-site offsets."""

    config: SensorConfig
    world_from_transmitter: np.ndarray
    offsets: dict[str, np.ndarray]


def _record(s: Sample | Record) -> Record:
    return s.record if isinstance(s, Sample) else s


def calibrate(samples: Mapping[int, Sample | Record], reference: Mapping[str, np.ndarray],
              config: SensorConfig | None = None, anchor: str = "pelvis",
              place_transmitter: bool = True) -> Calibration:
    """Calibrate from samples taken while the operator stands in a known pose.

    ``reference`` gives the world 4×4 pose each part's site has in that pose (e.g. from the
    figure's neutral stance). The transmitter is placed by yaw about world y plus a translation so
    the ``anchor`` sensor, carried by its configured mount offset, lands on its reference (keeping
    the configured transmitter placement if the anchor is missing or ``place_transmitter`` is
    False); each part's offset then absorbs the rest.

    The transmitter placement is exact when the transmitter stands level (yaw only) and the
    anchor's mount offset is known; an unknown anchor offset misplaces the transmitter by that
    offset, which shows as errors proportional to how far each part turns from the calibration
    pose.
    """
    config = config or default_config()
    poses = {}
    for m in config.mounts:
        if m.bird in samples and m.part in reference:
            pose = sensor_pose(_record(samples[m.bird]), config.conjugate_quaternion)
            if pose is None:
                raise DeviceError(f"calibration: bird {m.bird} ({m.part}) gives no valid pose")
            poses[m.part] = pose
    if not poses:
        raise DeviceError("calibration: no sample for any configured body part")
    world = config.world_from_transmitter.copy()
    if anchor in poses and place_transmitter:
        # the anchor's configured mount offset (where the waist sensor sits on the body) is
        # honoured, so a known offset places the transmitter exactly; identity by default
        mount = config.mount(anchor)
        s = poses[anchor] @ (mount.offset if mount is not None else np.eye(4))
        ref = np.asarray(reference[anchor], dtype=float)
        yaw = _heading(ref) - _heading(s)
        rot = np.eye(4)
        rot[:3, :3] = _rot(1, yaw)
        world = rot
        world[:3, 3] = ref[:3, 3] - rot[:3, :3] @ s[:3, 3]
    offsets = {part: np.linalg.inv(world @ pose) @ np.asarray(reference[part], dtype=float)
               for part, pose in poses.items()}
    return Calibration(config, world, offsets)


def _heading(t: np.ndarray) -> float:
    """Yaw about world y of a pose's forward (+z) axis."""
    f = t[:3, 2]
    return math.atan2(f[0], f[2])


def sensor_targets(samples: Mapping[int, Sample | Record], calibration: Calibration) -> dict[str, np.ndarray]:
    """World 4×4 target per body part from the latest sample of each configured bird.

    Parts without a sample (or with an invalid one) are left out.
    """
    out = {}
    cfg = calibration.config
    for m in cfg.mounts:
        s = samples.get(m.bird)
        if s is None:
            continue
        pose = sensor_pose(_record(s), cfg.conjugate_quaternion)
        if pose is not None:
            offset = calibration.offsets.get(m.part, m.offset)
            out[m.part] = calibration.world_from_transmitter @ pose @ offset
    return out


def spine_angles(pelvis: np.ndarray, neck: np.ndarray) -> tuple[float, float, float]:
    """Torso target from neck against waist (book §4.5): (flexion about x, axial twist about y,
    lateral bend about z) in radians, from the relative rotation Rpᵀ·Rn = Ry(twist)·Rx(flex)·Rz(bend)."""
    r = pelvis[:3, :3].T @ neck[:3, :3]
    flexion = math.asin(max(-1.0, min(1.0, -r[1, 2])))
    return flexion, math.atan2(r[0, 2], r[2, 2]), math.atan2(r[1, 0], r[1, 1])


class TargetSmoother:
    """Optional one-euro smoothing of targets per part (off unless you use it)."""

    def __init__(self, min_cutoff: float = 1.0, beta: float = 0.5, beta_rot: float = 0.1) -> None:
        self._args = (min_cutoff, beta, beta_rot)
        self._filters: dict[str, OneEuroPoseFilter] = {}

    def __call__(self, targets: Mapping[str, np.ndarray], t: float) -> dict[str, np.ndarray]:
        """Smoothed copy of ``targets`` sampled at ``t`` seconds."""
        return {part: self._filters.setdefault(part, OneEuroPoseFilter(*self._args))(pose, t)
                for part, pose in targets.items()}


def uncalibrated(config: SensorConfig | None = None) -> Calibration:
    """A calibration straight from a configuration: its transmitter placement and mount offsets."""
    config = config or default_config()
    return Calibration(config, config.world_from_transmitter.copy(),
                       {m.part: m.offset.copy() for m in config.mounts})
