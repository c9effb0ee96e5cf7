"""A byte-level Flock of Birds simulator on pseudo-terminals (or a TCP socket).

It parses host commands exactly as the hardware does (command byte + data bytes, FBB prefixes,
CHANGE/EXAMINE VALUE), keeps per-bird and master state (format, hemisphere, scaling, button,
group mode, report rate, measurement rate, error register with read-to-clear), and emits records
paced by its own clock (a pty ignores the baud rate). Topologies:

* one bird, one port: a standalone unit (FBB address 0, running at once);
* N birds, one port: a flock at addresses 1..N on the master's port; nothing runs until
  FBB AUTO-CONFIG, group mode returns every bird's record with its address byte;
* N birds, ``multi_port=True``: one port per bird (records carry no address byte);
* ``erc=True``: an Extended Range Controller at address 1 (the master, with its Extended Range
  Transmitter) and N sensor birds at addresses 2..N+1 behind its port. The ERC has no sensor: its
  system status byte says so (``D1`` running), AUTO-CONFIG counts it, group mode returns only the
  sensor birds' records, and every position is at the ERT's fixed 144 in full scale whatever
  POSITION SCALING says (spec §2.3, §3.3). A per-sensor command that reaches the ERC is kept in
  :attr:`FlockSimulator.erc_commands` (the manual says never to send one; what the hardware does
  then is not documented).

AUTO-CONFIG with n units configures addresses 1..n (contiguous, as on the hardware); units above
n stay idle, n above the flock latches error 13 with the first missing address.

Timing rules honoured: bytes arriving within ``autoconfig_delay`` seconds after AUTO-CONFIG are
ignored (the unit is busy configuring). Faults: dropped bytes, inserted garbage, error codes
(fatal ones stop the output) and hangs. A pty cannot carry RTS, so :meth:`reset` is explicit.

Poses come from ``motion(t, address) -> (position_in, angles_deg)`` in the transmitter frame.
"""

from __future__ import annotations

import contextlib
import math
import os
import random
import select
import socket
import threading
import time
import tty
from collections.abc import Callable
from dataclasses import dataclass, field

from jackpy.devices.flock import protocol as p
from jackpy.devices.flock.protocol import Format, Record
from jackpy.errors import DeviceError

Pose = tuple[tuple[float, float, float], tuple[float, float, float]]
Motion = Callable[[float, int], Pose]


def builtin_motion(t: float, address: int) -> Pose:
    """A smooth, distinct motion per bird: slow sway within ±20 in and ±60°, ahead of the
    transmitter (x > 0, so the forward hemisphere never folds it)."""
    ph = 0.7 * address
    pos = (12.0 + 6.0 * math.sin(0.9 * t + ph), 8.0 * math.sin(0.6 * t + 2 * ph),
           -5.0 + 10.0 * math.cos(0.5 * t + ph))
    ang = (60.0 * math.sin(0.4 * t + ph), 30.0 * math.sin(0.7 * t + ph), 45.0 * math.cos(0.3 * t + ph))
    return pos, ang


@dataclass
class SimBird:
    """Per-bird state of the simulated unit."""

    address: int
    format: Format = Format.POSITION_ANGLES
    scale: float = 36.0
    hemisphere: bytes = b"\x00\x00"
    button_mode: bool = False
    button: int = 0
    metal: bool = False
    erc: bool = False  # an Extended Range Controller: no sensor, drives the ERT
    values: dict[int, bytes] = field(default_factory=dict)  # other CHANGE VALUE params


@dataclass
class SentRecord:
    """What the simulator put on the wire (for tests): the record and whether it was intact."""

    record: Record
    intact: bool
    time: float  # time.perf_counter() just before the write


class _Port:
    """One serial endpoint: the master side of a pty, or an accepted TCP connection."""

    def __init__(self, bird: int, link: str | None = None, tcp_port: int | None = None) -> None:
        self.bird = bird  # default target of prefix-less commands
        self.streaming = False
        self.xoff = False
        self.inbuf = bytearray()
        self.listener: socket.socket | None = None
        self.conn: socket.socket | None = None
        self.link = link
        if tcp_port is not None:
            self.listener = socket.create_server(("127.0.0.1", tcp_port))
            self.path = f"socket://127.0.0.1:{self.listener.getsockname()[1]}"
            self.fd = self.slave_fd = -1
            return
        self.fd, self.slave_fd = os.openpty()
        tty.setraw(self.slave_fd)
        os.set_blocking(self.fd, False)
        self.path = self.tty = os.ttyname(self.slave_fd)
        if link:
            tmp = f"{link}.{os.getpid()}.tmp"
            with contextlib.suppress(FileNotFoundError):
                os.unlink(tmp)
            os.symlink(self.path, tmp)
            os.replace(tmp, link)
            self.path = link

    def selectables(self) -> list:
        if self.listener is not None:
            return [self.listener] + ([self.conn] if self.conn else [])
        return [self.fd]

    def read(self, obj) -> bytes:
        if obj is self.listener:
            if self.conn:
                self.conn.close()
            self.conn, _ = self.listener.accept()
            self.conn.setblocking(False)
            self.inbuf.clear()
            self.streaming = False
            return b""
        try:
            if self.conn is not None:
                data = self.conn.recv(4096)
                if not data:
                    self.conn.close()
                    self.conn = None
                    self.streaming = False
                return data
            return os.read(self.fd, 4096)
        except (BlockingIOError, ConnectionError, OSError):
            return b""

    def write(self, data: bytes) -> int:
        """Write what fits without blocking; returns bytes written (the rest is an overrun)."""
        try:
            if self.listener is not None:
                return self.conn.send(data) if self.conn else 0
            return os.write(self.fd, data)
        except (BlockingIOError, ConnectionError, OSError):
            return 0

    def close(self) -> None:
        for s in (self.conn, self.listener):
            if s is not None:
                s.close()
        for fd in (self.fd, self.slave_fd):
            if fd >= 0:
                with contextlib.suppress(OSError):
                    os.close(fd)
        if self.link and self.listener is None:
            with contextlib.suppress(OSError):
                if os.readlink(self.link) == self.tty:  # not yet taken over by a new simulator
                    os.unlink(self.link)


class FlockSimulator:
    """A simulated Flock of Birds; :meth:`start` runs it on a background thread.

    ``paths`` lists the tty paths (or ``socket://`` URL) to open, one per port.
    ``log=True`` keeps every sent record per bird in ``sent`` (for tests).
    """

    def __init__(self, birds: int = 1, *, multi_port: bool = False, rate: float = 103.3,
                 motion: Motion | None = None, link: str | None = None, tcp_port: int | None = None,
                 autoconfig_delay: float = 0.6, log: bool = False, seed: int = 0,
                 erc: bool = False) -> None:
        if not 1 <= birds + erc <= 14:
            raise DeviceError(f"the simulator supports 1..14 units (normal addressing), not {birds + erc}")
        if erc and multi_port:
            raise DeviceError("the simulator runs an ERC flock on one port only")
        self.erc = erc
        self.standalone = birds == 1 and not multi_port and not erc
        addresses = [0] if self.standalone else list(range(1, birds + erc + 1))
        self.birds = {a: SimBird(a, erc=erc and a == 1, scale=p.ERT_SCALE if erc else 36.0)
                      for a in addresses}
        self.master = addresses[0]
        self.multi_port = multi_port
        if multi_port and tcp_port is not None:
            raise DeviceError("a TCP simulator serves one port; use multi_port with ptys")
        links = [link] if not multi_port else [f"{link}{i}" if link else None for i in range(birds)]
        self.ports = ([_Port(a, links[i]) for i, a in enumerate(addresses)] if multi_port
                      else [_Port(self.master, link, tcp_port)])
        self.paths = [port.path for port in self.ports]
        self.motion = motion or builtin_motion
        self.rate = rate
        self.autoconfig_delay = autoconfig_delay
        self.report_rate = 1
        self.group_mode = False
        self.configured = self.standalone
        self.units = len(addresses)  # addresses 1..units run after AUTO-CONFIG
        self.erc_commands: list[bytes] = []
        self.sleeping = False
        self.error = 0
        self.error_info = 0
        self.error_flag = False
        self.stopped_by_fatal = False
        self.busy_until = 0.0
        self.hang_until = 0.0
        self.log = log
        self.sent: dict[int, list[SentRecord]] = {a: [] for a in addresses if not self.birds[a].erc}
        self.records_sent = 0
        self.overrun_bytes = 0
        self.ignored_bytes = 0
        self._drop_next = 0
        self._garbage: bytes = b""
        self._rng = random.Random(seed)
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._t0 = time.perf_counter()
        self._frozen_t = 0.0
        self._cycle = 0

    # --- lifecycle ------------------------------------------------------------------------------
    def start(self) -> FlockSimulator:
        self._thread = threading.Thread(target=self._run, name="flock-sim", daemon=True)
        self._thread.start()
        return self

    def stop(self) -> None:
        """Kill the simulator: stop the thread and close its ports (the driver sees them go)."""
        self._stop.set()
        if self._thread:
            self._thread.join(5)
        for port in self.ports:
            port.close()

    def __enter__(self) -> FlockSimulator:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()

    def reset(self) -> None:
        """What an RTS reset does: power-up defaults (spec §1.1)."""
        with self._lock:
            for a, old in self.birds.items():
                self.birds[a] = SimBird(a, erc=old.erc, scale=p.ERT_SCALE if self.erc else 36.0)
            for port in self.ports:
                port.streaming = False
                port.inbuf.clear()
            self.report_rate, self.group_mode = 1, False
            self.configured, self.sleeping = self.standalone, False
            self.units = len(self.birds)
            self.error = self.error_info = 0
            self.error_flag = self.stopped_by_fatal = False

    # --- faults ---------------------------------------------------------------------------------
    def drop_bytes(self, records: int) -> None:
        """Lose one byte (any, the phasing byte included) from each of the next ``records`` records."""
        with self._lock:
            self._drop_next += records

    def inject_garbage(self, data: bytes) -> None:
        """Put ``data`` on the wire before the next record."""
        with self._lock:
            self._garbage += data

    def set_error(self, code: int, info: int = 0) -> None:
        """Latch device error ``code``; a FATAL one stops all output, as on the hardware."""
        with self._lock:
            self._latch(code, info)

    def hang(self, seconds: float) -> None:
        """Go silent (no replies, no records, input ignored) for ``seconds``."""
        self.hang_until = time.perf_counter() + seconds

    # --- main loop ------------------------------------------------------------------------------
    def _run(self) -> None:
        next_tick = time.perf_counter()
        while not self._stop.is_set():
            period = self.report_rate / self.rate
            streaming = any(port.streaming for port in self.ports)
            now = time.perf_counter()
            timeout = max(0.0, next_tick - now) if streaming else 0.02
            objs = {o: port for port in self.ports for o in port.selectables()}
            try:
                ready, _, _ = select.select(list(objs), [], [], timeout)
            except (OSError, ValueError):
                return
            for obj in ready:
                port = objs[obj]
                data = port.read(obj)
                if data:
                    self._receive(port, data)
            now = time.perf_counter()
            if not streaming:
                next_tick = now
            elif now >= next_tick:
                next_tick += period
                if next_tick < now - 5 * period:  # fell far behind: skip, do not burst
                    next_tick = now + period
                self._cycle += 1
                if now >= self.hang_until:
                    with self._lock:
                        for port in self.ports:
                            if port.streaming and not port.xoff and not self.stopped_by_fatal:
                                self._emit(port, point=False)

    def _receive(self, port: _Port, data: bytes) -> None:
        now = time.perf_counter()
        if now < self.hang_until or now < self.busy_until:
            self.ignored_bytes += len(data)
            return
        with self._lock:
            port.inbuf += data
            while port.inbuf:
                used = self._command(port, port.inbuf)
                if used == 0:
                    break  # incomplete command: wait for its data bytes
                del port.inbuf[:used]
                if time.perf_counter() < self.busy_until:
                    self.ignored_bytes += len(port.inbuf)
                    port.inbuf.clear()

    # --- command interpreter --------------------------------------------------------------------
    def _command(self, port: _Port, buf: bytearray) -> int:
        """Execute the command at the start of ``buf``; return bytes used (0 = incomplete)."""
        target = port.bird
        start = 0
        if 0xF1 <= buf[0] <= 0xFF:
            if len(buf) < 2:
                return 0
            target, start = buf[0] - 0xF0, 1
        cmd = buf[start]
        if cmd == p.CHANGE_VALUE:
            if len(buf) < start + 2:
                return 0
            param = buf[start + 1]
            n = p.CHANGE_LENGTH.get(param)
            if n is None:
                self._latch(6)
                return start + 2
            if len(buf) < start + n:
                return 0
            self._to_erc(target, param in p.SENSOR_PARAMS, buf[:start + n])
            self._change(port, target, param, bytes(buf[start + 2:start + n]))
            return start + n
        n = p.COMMAND_DATA_LENGTH.get(cmd)
        if n is None:
            self._latch(6)
            return start + 1
        if len(buf) < start + 1 + n:
            return 0
        sensor = cmd in p.SENSOR_COMMANDS or (cmd == p.EXAMINE_VALUE and buf[start + 1] in p.SENSOR_PARAMS) \
            or (cmd == p.POINT and start == 1)
        self._to_erc(target, sensor, buf[:start + 1 + n])
        self._execute(port, target, cmd, bytes(buf[start + 1:start + 1 + n]))
        return start + 1 + n

    def _to_erc(self, target: int, sensor_command: bool, frame: bytearray) -> None:
        """Keep a per-sensor command addressed to an ERC (for tests)."""
        bird = self.birds.get(target)
        if sensor_command and bird is not None and bird.erc:
            self.erc_commands.append(bytes(frame))

    def _bird(self, target: int) -> SimBird | None:
        if target not in self.birds:
            self._latch(13, target)
            return None
        return self.birds[target]

    def _execute(self, port: _Port, target: int, cmd: int, data: bytes) -> None:
        if cmd in Format._value2member_map_:
            bird = self._bird(target)
            if bird:
                bird.format = Format(cmd)
            port.streaming = False
        elif cmd == p.POINT:
            port.streaming = False
            if self._can_run():
                self._emit(port, point=True, target=target)
        elif cmd == p.STREAM:
            if self._can_run():
                port.streaming = True
        elif cmd == p.STREAM_STOP:
            port.streaming = False
        elif cmd in p.REPORT_RATE.values():
            self.report_rate = {v: k for k, v in p.REPORT_RATE.items()}[cmd]
        elif cmd == p.RUN:
            if self.sleeping:
                self._t0 = time.perf_counter() - self._frozen_t
            self.sleeping = False
        elif cmd == p.SLEEP:
            if not self.sleeping:
                self._frozen_t = time.perf_counter() - self._t0
            self.sleeping = True
        elif cmd == p.NEXT_TRANSMITTER:
            if (data[0] >> 4) not in self.birds:
                self._latch(29)
        elif cmd == p.HEMISPHERE:
            bird = self._bird(target)
            if bird:
                bird.hemisphere = data
        elif cmd == p.BUTTON_MODE:
            bird = self._bird(target)
            if bird:
                bird.button_mode = bool(data[0])
        elif cmd == p.BUTTON_READ:
            bird = self._bird(target)
            if bird:
                port.write(bytes([bird.button]))
        elif cmd == p.METAL:
            bird = self._bird(target)
            if bird:
                bird.metal = data[0] != 0
        elif cmd == p.METAL_ERROR:
            port.write(b"\x00")
        elif cmd == p.XOFF:
            port.xoff = True
        elif cmd == p.XON:
            port.xoff = False
        elif cmd == p.EXAMINE_VALUE:
            self._examine(port, target, data[0])
        # ALIGN, REFERENCE FRAME, BORESIGHT, OFFSET, SYNC, FBB RESET: accepted, no visible effect

    def _can_run(self) -> bool:
        if not self.configured:
            self._latch(9)
            return False
        return not self.stopped_by_fatal

    def _change(self, port: _Port, target: int, param: int, value: bytes) -> None:
        bird = self.birds.get(target)
        if param == p.P_POSITION_SCALING and bird:
            bird.values[param] = value
            if not self.erc:  # with an ERT the full scale is fixed at 144 in
                bird.scale = p.POSITION_SCALES[value[0] & 1]
        elif param == p.P_MEASUREMENT_RATE:
            self.rate = min(144.0, max(10.0, p.u16_le(value) / 256.0))
        elif param == p.P_REPORT_RATE:
            self.report_rate = max(1, min(127, value[0]))
        elif param == p.P_GROUP_MODE:
            self.group_mode = bool(value[0])
        elif param == p.P_HEMISPHERE and bird:
            bird.hemisphere = value
        elif param == p.P_AUTO_CONFIG:
            if self.standalone or not 1 <= value[0] <= len(self.birds):
                self._latch(13, len(self.birds) + 1)
            else:
                self.configured, self.units = True, value[0]
            self.busy_until = time.perf_counter() + self.autoconfig_delay
        elif bird:
            bird.values[param] = value

    def _examine(self, port: _Port, target: int, param: int) -> None:
        n = p.EXAMINE_LENGTH.get(param)
        if n is None:
            self._latch(6)
            return
        bird = self._bird(target)
        if bird is None:
            return
        reply: bytes
        if param == p.P_STATUS:
            streaming = any(pt.streaming for pt in self.ports)
            word = ((0x8000 if bird.address == self.master else 0) | (0x4000 if self.configured else 0)
                    | (0x2000 if self.error_flag else 0) | (0x1000 if self.configured else 0)
                    | (0x20 if self.sleeping else 0) | (bird.format.status_code << 1) | streaming)
            self.error_flag = False
            reply = p.s16(word)
        elif param == p.P_REVISION:
            reply = b"\x03\x43"
        elif param == p.P_CRYSTAL:
            reply = b"\x19\x00"
        elif param == p.P_POSITION_SCALING:
            reply = bird.values.get(param, b"\x00\x00")
        elif param == p.P_MEASUREMENT_RATE:
            reply = p.s16(int(round(self.rate * 256)))
        elif param in (p.P_ERROR_CODE, p.P_EXPANDED_ERROR):
            reply = bytes([self.error, self.error_info])[:n]
            self.error = self.error_info = 0
        elif param == p.P_MODEL_ID:
            reply = b"6DERC     " if bird.erc else b"6DFOB     "
        elif param == p.P_ADDRESSING_MODE:
            reply = b"\x00"
        elif param == p.P_FBB_ADDRESS:
            reply = bytes([bird.address])
        elif param == p.P_HEMISPHERE:
            reply = bird.hemisphere
        elif param == p.P_REPORT_RATE:
            reply = bytes([self.report_rate])
        elif param == p.P_GROUP_MODE:
            reply = bytes([self.group_mode])
        elif param == p.P_SYSTEM_STATUS:
            status = []
            for a in sorted(self.birds):
                b = self.birds[a]
                run = p.UNIT_RUNNING if self.configured and a <= self.units else 0
                kind = (p.UNIT_IS_ERC | 0x01 if b.erc else p.UNIT_HAS_SENSOR
                        | (0x01 if a == self.master else 0))
                status.append(p.UNIT_ACCESSIBLE | run | kind)
            reply = bytes(status + [0] * (14 - len(status)))
        elif param == p.P_AUTO_CONFIG:
            mask = sum(1 << a for a in self.birds if a <= self.units) if self.configured else 0
            reply = bytes([0 if self.standalone else 1]) + p.s16(mask) + b"\x00\x00"
        else:
            reply = bird.values.get(param, b"\x00" * n)
        port.write(reply[:n].ljust(n, b"\x00"))

    def _latch(self, code: int, info: int = 0) -> None:
        if self.error == 0:
            self.error, self.error_info = code, info & 0x0F
        self.error_flag = True
        if p.ERROR_CODES.get(code, ("", ""))[1] == "FATAL":
            self.stopped_by_fatal = True
            for port in self.ports:
                port.streaming = False

    # --- records --------------------------------------------------------------------------------
    def _emit(self, port: _Port, point: bool, target: int | None = None) -> None:
        """Send one cycle's records on ``port`` (called with the lock held)."""
        group = self.group_mode and not self.multi_port and not self.standalone
        if group:  # every running sensor bird, smallest address first; an ERC sends nothing
            addrs = [a for a in sorted(self.birds) if a <= self.units and not self.birds[a].erc]
        else:
            addrs = [target if point and target in self.birds else port.bird]
        t = self._frozen_t if self.sleeping else time.perf_counter() - self._t0
        for a in addrs:
            if self.birds[a].erc:  # asked for data outside group mode: a fixed pose (spec §3.4)
                rec = p.make_record(self.birds[a].format, scale=p.ERT_SCALE, address=a)
                port.write(p.encode_record(rec))
                continue
            rec = self._record(self.birds[a], t)
            data = p.encode_record(rec, group=group)
            intact = True
            if self._drop_next:
                self._drop_next -= 1
                k = self._rng.randrange(len(data))
                data = data[:k] + data[k + 1:]
                intact = False
            if self._garbage:
                data, self._garbage = self._garbage + data, b""
            if self.log:
                self.sent[a].append(SentRecord(rec, intact, time.perf_counter()))
            written = port.write(data)
            self.overrun_bytes += len(data) - written
            self.records_sent += 1

    def _record(self, bird: SimBird, t: float) -> Record:
        pos, ang = self.motion(t, bird.address)
        axis = {0x00: 0, 0x06: 1, 0x0C: 2}.get(bird.hemisphere[0], 0)
        sign = -1.0 if bird.hemisphere[1] else 1.0
        if pos[axis] * sign < 0:  # the field is symmetric: report the folded position
            pos = (-pos[0], -pos[1], -pos[2])
        return p.make_record(bird.format, pos, ang, scale=bird.scale,
                             button=bird.button if bird.button_mode else None,
                             metal=0 if bird.metal else None, address=bird.address)

