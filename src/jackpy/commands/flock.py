"""``jackpy flock-sim``, ``flock-probe`` and ``flock-replay``: the Flock of Birds on the command line."""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

from jackpy.errors import DeviceError


def register(sub: argparse._SubParsersAction) -> None:
    s = sub.add_parser("flock-sim", help="run a simulated Flock of Birds on a pseudo-terminal")
    s.add_argument("--birds", type=int, default=4, help="number of sensor birds (1 = standalone unit)")
    s.add_argument("--erc", action="store_true",
                   help="an Extended Range Controller at address 1, the sensor birds at 2..N+1 (144 in scale)")
    s.add_argument("--multi-port", action="store_true", help="one pty per bird instead of one shared port")
    s.add_argument("--rate", type=float, default=103.3, help="measurement rate in Hz (default 103.3)")
    s.add_argument("--link", metavar="PATH", help="also make PATH a stable symlink to the pty (PATH0.. with --multi-port)")
    s.add_argument("--tcp", metavar="PORT", type=int, help="serve on 127.0.0.1:PORT (socket://) instead of a pty")
    s.add_argument("--motion", metavar="FILE", help="poses from a recording instead of the built-in motion")
    s.add_argument("--duration", type=float, help="stop after this many seconds")
    s.add_argument("--drop", type=int, default=0, metavar="N", help="fault: lose a byte in N records each second")
    s.add_argument("--garbage", type=int, default=0, metavar="N", help="fault: N random bytes each second")
    s.add_argument("--error", type=int, metavar="CODE", help="fault: latch device error CODE at start")
    s.add_argument("--hang", type=float, nargs=2, metavar=("AT", "FOR"), help="fault: go silent at AT s for FOR s")
    s.set_defaults(func=run_sim)

    p = sub.add_parser("flock-probe", help="connect to a Flock of Birds, print its identity and samples")
    p.add_argument("port", help="serial port, pty path or pyserial URL (socket://host:port)")
    p.add_argument("--birds", type=int, default=1, help="sensor birds on this one port (an ERC is not counted)")
    p.add_argument("--ports", nargs="+", metavar="PORT", help="more ports: one port per bird")
    p.add_argument("--format", default="position_angles", help="record format (position_angles, pos_quat ...)")
    p.add_argument("--mode", choices=("stream", "point"), default="stream")
    p.add_argument("--hemisphere", default="forward")
    p.add_argument("--rate", type=float, help="measurement rate in Hz")
    p.add_argument("--baud", type=int, default=115200)
    p.add_argument("--no-reset", action="store_true", help="skip the 3 s RTS reset on open")
    p.add_argument("--seconds", type=float, default=5.0, help="how long to read (0 = until Ctrl-C)")
    p.add_argument("--record", metavar="FILE", help="record every raw sample to FILE")
    p.set_defaults(func=run_probe)

    r = sub.add_parser("flock-replay", help="replay a Flock recording: print its samples, or drive a figure")
    r.add_argument("file")
    r.add_argument("--speed", type=float, default=1.0, help="real-time factor (0 = as fast as possible)")
    r.add_argument("--step", action="store_true", help="frame by frame: press Enter for the next frame")
    r.add_argument("--json", action="store_true", help="one JSON object per frame")
    g = r.add_argument_group("driving a figure (--figure)")
    g.add_argument("--figure", action="store_true",
                   help="drive the standard human from the recording (pelvis, spine, hands, stepping)")
    g.add_argument("--sex", choices=("male", "female"), help="standard human's sex (default: the recording's, else male)")
    g.add_argument("--percentile", type=float, help="standard human's stature percentile (default: the recording's, else 50)")
    g.add_argument("--sensors", metavar="JSON", help="sensor configuration (default: the recording's, else Jack's four)")
    g.add_argument("--calibrate-frame", type=int, metavar="K",
                   help="frame where the operator stands in the neutral pose (default: the recording's, else 0)")
    g.add_argument("--every", type=int, default=1, metavar="N", help="with --speed 0 or --step: drive every N-th frame")
    g.add_argument("--smooth", action="store_true", help="one-euro smoothing of the sensor targets")
    g.add_argument("--out", metavar="FIG", help="write the final posture: Peabody .fig (psurfs beside it) or .glb")
    g.add_argument("--png", metavar="PNG", help="write a strip of snapshots of the figure (offscreen rendering)")
    g.add_argument("--strip", type=int, default=6, metavar="K", help="snapshots in the --png strip (default 6)")
    g.add_argument("--quiet", action="store_true", help="print only the summary")
    r.set_defaults(func=run_replay)


def run_sim(args: argparse.Namespace) -> int:
    import random

    from jackpy.devices.flock.simulator import FlockSimulator
    from jackpy.devices.recording import read_recording

    motion = None
    if args.motion:
        motion = read_recording(args.motion).pose_at
    sim = FlockSimulator(args.birds, multi_port=args.multi_port, rate=args.rate, motion=motion,
                         link=args.link, tcp_port=args.tcp, erc=args.erc)
    if args.error:
        sim.set_error(args.error)
    sim.start()
    for i, path in enumerate(sim.paths):
        print(f"flock-sim port {i}: {path}", flush=True)
    t0 = time.monotonic()
    rng = random.Random()
    try:
        while args.duration is None or time.monotonic() - t0 < args.duration:
            time.sleep(1.0)
            if args.drop:
                sim.drop_bytes(args.drop)
            if args.garbage:
                sim.inject_garbage(bytes(rng.randrange(256) for _ in range(args.garbage)))
            if args.hang and args.hang[0] <= time.monotonic() - t0 < args.hang[0] + 1.0:
                sim.hang(args.hang[1])
    finally:
        sim.stop()
    print(f"flock-sim: {sim.records_sent} records sent", flush=True)
    return 0


def _describe(sample) -> str:
    rec = sample.record
    parts = [f"bird {sample.bird}"]
    if rec.position is not None:
        parts.append("pos (%+8.3f %+8.3f %+8.3f) in" % rec.position)
    if rec.angles is not None:
        parts.append("ang (%+8.2f %+7.2f %+8.2f) deg" % rec.angles)
    elif rec.quaternion is not None:
        parts.append("quat (%+.4f %+.4f %+.4f %+.4f)" % rec.quaternion)
    elif rec.matrix is not None:
        parts.append("matrix " + " ".join(f"{v:+.3f}" for v in rec.matrix.ravel()))
    if rec.button is not None:
        parts.append(f"button {rec.button:#04x}")
    return "  ".join(parts)


def run_probe(args: argparse.Namespace) -> int:
    from jackpy.devices.flock.driver import FlockDriver
    from jackpy.devices.flock.protocol import Format
    from jackpy.devices.recording import Recorder

    ports = [args.port] + (args.ports or [])
    driver = FlockDriver(ports if len(ports) > 1 else args.port, args.birds, format=Format.parse(args.format),
                         mode=args.mode, hemisphere=args.hemisphere, measurement_rate=args.rate,
                         baudrate=args.baud, rts_reset=None if args.no_reset else (1.0, 2.0))
    recorder = Recorder(args.record, meta={"ports": ports}) if args.record else None
    if recorder:
        driver.add_listener(recorder.add)
    driver.start()
    try:
        print(f"{driver.info.get('model', '?')} revision {driver.info.get('revision', '?')}, "
              f"birds {driver.birds}{', with an Extended Range Controller' if driver.info.get('erc') == 'yes' else ''}, "
              f"{args.mode} mode", flush=True)
        for code, text in driver.device_errors:
            print(f"device {text}", flush=True)
        t0 = time.monotonic()
        while args.seconds <= 0 or time.monotonic() - t0 < args.seconds:
            time.sleep(0.1)
            for s in driver.snapshot().values():
                print(f"{s.time - t0:9.3f}  {_describe(s)}")
            if driver.state != args.mode:
                print(f"[{driver.state}] {driver.last_error or ''}", flush=True)
    finally:
        driver.stop()
        if recorder:
            recorder.close()
    st = driver.stats
    print(f"{st.records} records, {st.dropped} records lost, {st.skipped_bytes} stray bytes skipped, "
          f"{st.disconnects} disconnects", flush=True)
    return 0


def run_replay(args: argparse.Namespace) -> int:
    from jackpy.devices.recording import read_recording, replay

    if args.speed < 0:
        raise DeviceError("--speed must be >= 0")
    rec = read_recording(args.file)
    if not rec.samples:  # e.g. stopped before the first sample: an empty recording, not an error
        skipped = [opt for opt, v in (("--out", getattr(args, "out", None)), ("--png", getattr(args, "png", None)))
                   if v]
        print(f"note: {args.file} holds a header and no samples: nothing to replay"
              + (f" ({' and '.join(skipped)} not written)" if skipped else ""), file=sys.stderr, flush=True)
        return 0
    if args.figure:
        return run_replay_figure(args, rec)
    interactive = args.step and os.isatty(sys.stdin.fileno())
    for i, frame in enumerate(replay(rec, 0.0 if args.step else args.speed)):
        t = min(s.time for s in frame.values())
        if args.json:
            print(json.dumps({"frame": i, "t": t, "samples": {
                str(b): {"position_in": s.record.position, "angles_deg": s.record.angles,
                         "quaternion": s.record.quaternion,
                         "matrix": None if s.record.matrix is None else s.record.matrix.tolist()}
                for b, s in frame.items()}}), flush=True)
        else:
            print(f"frame {i:6d}  t={t:9.3f} s", flush=True)
            for s in frame.values():
                print(f"    {_describe(s)}", flush=True)
        if interactive:
            input()
    return 0


def _figure_drive(args: argparse.Namespace, rec):
    """The standard human, its behavior loop and a sensor drive configured for ``rec``."""
    from jackpy.behaviors import BehaviorLoop
    from jackpy.behaviors.anatomy import human_anatomy
    from jackpy.behaviors.sensor_drive import DriveConfig, SensorDrive
    from jackpy.body.human import make_human
    from jackpy.devices.sensors import (
        default_config,
        load_sensor_config,
        sensor_config_from_dict,
    )

    meta = rec.header.get("figure") if isinstance(rec.header.get("figure"), dict) else {}
    sex = args.sex or meta.get("sex", "male")
    percentile = args.percentile if args.percentile is not None else float(meta.get("percentile", 50))
    if not 1.0 <= percentile <= 99.0:
        raise DeviceError(f"--percentile must be within 1..99, not {percentile:g}")
    if args.sensors:
        sensors = load_sensor_config(args.sensors)
    elif isinstance(rec.header.get("sensors"), dict):
        sensors = sensor_config_from_dict(rec.header["sensors"], f"{args.file} (header)")
    else:
        sensors = default_config()
    fig = make_human(sex, percentile)
    loop = BehaviorLoop(fig, human_anatomy(fig))
    return fig, SensorDrive(loop, None, DriveConfig(sensors=sensors, smoothing=args.smooth))


def run_replay_figure(args: argparse.Namespace, rec) -> int:
    """``flock-replay FILE --figure``: drive the standard human from a recording, headless."""
    import numpy as np

    from jackpy.behaviors.sensor_drive import replay_into

    if args.every < 1:
        raise DeviceError("--every must be >= 1")
    if args.strip < 1:
        raise DeviceError("--strip must be >= 1")
    fig, drive = _figure_drive(args, rec)
    frames = rec.frames()
    cal = args.calibrate_frame if args.calibrate_frame is not None else int(rec.header.get("calibrate_frame", 0))
    if not 0 <= cal < len(frames):
        raise DeviceError(f"--calibrate-frame {cal} is outside the recording's {len(frames)} frames")
    interactive = args.step and os.isatty(sys.stdin.fileno())
    speed = 0.0 if args.step else args.speed
    shots, next_shot = [], 0
    marks = [round(i * (len(frames) - 1) / max(1, args.strip - 1)) for i in range(args.strip)]
    worst: dict[str, float] = {}
    driven = 0
    t0 = time.perf_counter()
    for k, r in replay_into(drive, rec, speed=speed, every=args.every, calibrate_frame=cal):
        driven += 1
        for part, e in r.errors.items():
            worst[part] = max(worst.get(part, 0.0), e)
        t = min(s.time for s in frames[k].values())
        if args.json:
            print(json.dumps({"frame": k, "t": t, "errors_m": r.errors,
                              "spine_deg": None if r.spine is None else [float(np.degrees(a)) for a in r.spine],
                              "steps": drive.loop.state.steps_taken, "notes": r.notes,
                              "step_ms": r.step_ms}), flush=True)
        elif not args.quiet:
            errs = "  ".join(f"{p} {e * 100:5.2f}" for p, e in r.errors.items())
            spine = "" if r.spine is None else "  spine {:+.1f} {:+.1f} {:+.1f} deg".format(*np.degrees(r.spine))
            notes = f"  [{'; '.join(r.notes)}]" if r.notes else ""
            print(f"frame {k:6d}  t={t:7.3f} s  error cm: {errs}{spine}{notes}", flush=True)
        if args.png:
            while next_shot < len(marks) and k >= marks[next_shot]:
                shots.append(_snapshot(fig))
                next_shot += 1
        if interactive:
            input()
    elapsed = time.perf_counter() - t0
    summary = (f"drove {driven} of {len(frames)} frames in {elapsed:.2f} s; worst error cm: "
               + ", ".join(f"{p} {e * 100:.2f}" for p, e in worst.items())
               + f"; steps taken {drive.loop.state.steps_taken}")
    print(summary, file=sys.stderr if args.json else sys.stdout, flush=True)
    if args.out:
        from jackpy.commands.human import write_human

        write_human(args.out, fig)  # .fig with psurfs beside it (or .glb, .obj ...)
        print(f"wrote {args.out}", file=sys.stderr if args.json else sys.stdout, flush=True)
    if args.png:
        from jackpy.render import write_png

        write_png(args.png, np.concatenate(shots, axis=1))
        print(f"wrote {args.png} ({len(shots)} snapshots)", file=sys.stderr if args.json else sys.stdout,
              flush=True)
    return 0


def _snapshot(fig):
    """RGBA image of ``fig`` alone, from the side-front (offscreen)."""
    from jackpy.peabody import Environment
    from jackpy.ui.screenshot import render_scene

    env = Environment()
    env.add(fig)
    return render_scene(env, (320, 480), "iso")
