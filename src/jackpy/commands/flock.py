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
    p.add_argument("--birds", type=int, default=1, help="sensor birds on this one port")
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

    r = sub.add_parser("flock-replay", help="replay a Flock recording: print its samples")
    r.add_argument("file")
    r.add_argument("--speed", type=float, default=1.0, help="real-time factor (0 = as fast as possible)")
    r.add_argument("--step", action="store_true", help="frame by frame: press Enter for the next frame")
    r.add_argument("--json", action="store_true", help="one JSON object per frame")
    r.set_defaults(func=run_replay)


def run_sim(args: argparse.Namespace) -> int:
    import random

    from jackpy.devices.flock.simulator import FlockSimulator
    from jackpy.devices.recording import read_recording

    motion = None
    if args.motion:
        motion = read_recording(args.motion).pose_at
    sim = FlockSimulator(args.birds, multi_port=args.multi_port, rate=args.rate, motion=motion,
                         link=args.link, tcp_port=args.tcp)
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
              f"birds {driver.birds}, {args.mode} mode", flush=True)
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
    print(f"{st.records} records, {st.dropped} dropped, {st.skipped_bytes} bytes skipped, "
          f"{st.disconnects} disconnects", flush=True)
    return 0


def run_replay(args: argparse.Namespace) -> int:
    from jackpy.devices.recording import read_recording, replay

    if args.speed < 0:
        raise DeviceError("--speed must be >= 0")
    rec = read_recording(args.file)
    if not rec.samples:
        raise DeviceError(f"{args.file}: the recording holds no samples")
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
