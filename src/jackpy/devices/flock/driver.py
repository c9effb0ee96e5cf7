"""pyserial driver for the Flock of Birds: configuration, a reader thread, a latest-sample store.

Topologies: one port with a standalone bird; one port with a flock of N sensor birds (FBB
prefixes, AUTO-CONFIG, group mode), with or without an Extended Range Controller; or one port
per bird (``ports=[...]``, the first on the master).

A flock is mapped from its FLOCK SYSTEM STATUS (spec §5.4): the sensor birds are the accessible
units with a sensor, in address order (an ERC has none and is skipped: no format, hemisphere or
scaling command is ever sent to it); AUTO-CONFIG names the highest address needed; positions are
at the ERT's fixed 144 in full scale when an ERC is present, else at each bird's POSITION SCALING.
Ports are pyserial URLs, so ``/dev/ttyUSB0``, a pty path and ``socket://host:port`` all work.

The reader thread owns all reads while running; the workbench only calls :meth:`FlockDriver.latest`
/ :meth:`FlockDriver.snapshot`, which never block on I/O. Faults never escape the thread: a broken
record is dropped and counted, silence longer than ``data_timeout`` or a vanished port closes
everything, reports it in :attr:`FlockDriver.events`, and reconnects every
``reconnect_interval`` seconds.
"""

from __future__ import annotations

import collections
import contextlib
import logging
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import serial

from jackpy.devices.flock import protocol as p
from jackpy.devices.flock.protocol import BirdLayout, Format, Record, StreamDecoder
from jackpy.errors import DeviceError

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Sample:
    """One decoded record of one bird, stamped on the host.

    ``time`` is ``time.perf_counter()`` (seconds) when the record was complete; ``seq`` counts
    this bird's samples from 0 since the driver started.
    """

    bird: int
    record: Record
    time: float
    seq: int


class LatestSamples:
    """Thread-safe latest sample per bird (no queue: a reader overwrites, consumers peek)."""

    def __init__(self) -> None:
        self._latest: dict[int, Sample] = {}
        self._cond = threading.Condition()

    def put(self, sample: Sample) -> None:
        with self._cond:
            self._latest[sample.bird] = sample
            self._cond.notify_all()

    def latest(self, bird: int) -> Sample | None:
        """The newest sample of ``bird``, or None; never blocks."""
        with self._cond:
            return self._latest.get(bird)

    def snapshot(self) -> dict[int, Sample]:
        """The newest sample of every bird seen so far."""
        with self._cond:
            return dict(self._latest)

    def wait(self, bird: int, after_seq: int = -1, timeout: float = 1.0) -> Sample | None:
        """Block up to ``timeout`` s for a sample of ``bird`` newer than ``after_seq``."""
        with self._cond:
            self._cond.wait_for(lambda: (s := self._latest.get(bird)) is not None and s.seq > after_seq,
                                timeout)
            s = self._latest.get(bird)
            return s if s is not None and s.seq > after_seq else None


@dataclass
class DriverStats:
    """Counters of a running driver (cumulative over reconnects)."""

    records: int = 0
    dropped: int = 0  # records lost (broken or missing in the cycle), see StreamDecoder
    skipped_bytes: int = 0  # stray bytes that belong to no lost record
    disconnects: int = 0
    connects: int = 0
    max_pending_bytes: int = 0


class _Link:
    """One open port and what travels on it."""

    def __init__(self, url: str, ser: serial.SerialBase) -> None:
        self.url = url
        self.ser = ser
        self.birds: list[int] = []
        self.decoder: StreamDecoder | None = None
        self.group = False
        self.lock = threading.Lock()  # held by whoever talks on the port


class FlockDriver:
    """Drive a Flock of Birds on one or several ports.

    ``birds``: number of sensor birds (single port; ignored with several ports: one each).
    ``mode``: ``"stream"`` or ``"point"`` (polled at ``point_rate`` Hz). Other settings are
    applied to every bird at each (re)connection. Timing knobs default to the manual's values
    (``autoconfig_wait`` 0.65 s: the manual's 600 ms before and after AUTO-CONFIG, with margin).
    """

    def __init__(self, ports: str | Sequence[str], birds: int = 1, *,
                 format: Format = Format.POSITION_ANGLES, mode: str = "stream",
                 hemisphere: str = "forward", measurement_rate: float | None = None,
                 report_rate: int = 1, point_rate: float = 50.0, baudrate: int = 115200,
                 rts_reset: tuple[float, float] | None = (1.0, 2.0), autoconfig_wait: float = 0.65,
                 reply_timeout: float = 0.5, data_timeout: float = 2.0,
                 reconnect_interval: float = 1.0) -> None:
        self.urls = [ports] if isinstance(ports, str) else list(ports)
        if not self.urls:
            raise DeviceError("no port given")
        if mode not in ("stream", "point"):
            raise DeviceError(f"mode must be 'stream' or 'point', not {mode!r}")
        if len(self.urls) == 1 and not 1 <= birds <= 14:
            raise DeviceError(f"1..14 birds on one port, not {birds}")
        if not 1 <= report_rate <= 127:
            raise DeviceError(f"report rate must be 1..127 measurement cycles, not {report_rate}")
        p.hemisphere_command(hemisphere)  # validates the name
        if measurement_rate is not None:
            p.measurement_rate_value(measurement_rate)
        self.nbirds = birds if len(self.urls) == 1 else len(self.urls)
        self.format = format
        self.mode = mode
        self.hemisphere = hemisphere
        self.measurement_rate = measurement_rate
        self.report_rate = report_rate
        self.point_rate = point_rate
        self.baudrate = baudrate
        self.rts_reset = rts_reset
        self.autoconfig_wait = autoconfig_wait
        self.reply_timeout = reply_timeout
        self.data_timeout = data_timeout
        self.reconnect_interval = reconnect_interval
        self.store = LatestSamples()
        self.stats = DriverStats()
        self.events: collections.deque[str] = collections.deque(maxlen=100)
        self.device_errors: list[tuple[int, str]] = []
        self.layouts: dict[int, BirdLayout] = {}
        self.info: dict[str, str] = {}
        self.state = "stopped"
        self.last_error: str | None = None
        self._listeners: list[Callable[[Sample], None]] = []
        self._links: list[_Link] = []
        self._seq: dict[int, int] = {}
        self._stop = threading.Event()
        self._connected = threading.Event()
        self._lost = threading.Event()
        self._thread: threading.Thread | None = None

    # --- public API -----------------------------------------------------------------------------
    def start(self, wait: float | None = 10.0) -> FlockDriver:
        """Start the reader thread. With ``wait`` seconds, block until data flows, else raise
        :class:`DeviceError` saying what went wrong (and stop). ``wait=None`` never blocks."""
        self._stop.clear()
        self._thread = threading.Thread(target=self._supervise, name="flock-driver", daemon=True)
        self._thread.start()
        if wait is not None and not self._connected.wait(wait):
            err = self.last_error or "no answer"
            self.stop()
            raise DeviceError(f"could not start the Flock within {wait:g} s: {err}", self.urls[0])
        return self

    def stop(self) -> None:
        """Stop streaming, put the birds to sleep, close the ports and end the thread."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(5.0)
        self.state = "stopped"

    def __enter__(self) -> FlockDriver:
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()

    def add_listener(self, fn: Callable[[Sample], None]) -> None:
        """Call ``fn(sample)`` on the reader thread for every sample (recording, tests). Keep it quick."""
        self._listeners.append(fn)

    def latest(self, bird: int) -> Sample | None:
        """Newest sample of ``bird`` (FBB address; 0 for a standalone unit); never blocks."""
        return self.store.latest(bird)

    def snapshot(self) -> dict[int, Sample]:
        """Newest sample of every bird."""
        return self.store.snapshot()

    @property
    def birds(self) -> list[int]:
        """FBB addresses of the sensor birds (``[0]`` for a standalone unit)."""
        return sorted(self.layouts)

    def change(self, param: int, value: bytes, bird: int | None = None) -> None:
        """CHANGE VALUE ``param`` of ``bird`` (default: the master); pauses a running stream."""
        link, prefix = self._route(bird)
        with self._command_mode(link):
            link.ser.write(prefix + p.change_value(param, value))

    def check_errors(self) -> list[tuple[int, str]]:
        """Read (and so clear) the device error register of every port; returns new errors."""
        found: list[tuple[int, str]] = []
        for link in list(self._links):
            with self._command_mode(link):
                found += self._drain_errors(link)
        return found

    # --- supervisor -----------------------------------------------------------------------------
    def _event(self, msg: str) -> None:
        log.info("flock: %s", msg)
        self.events.append(f"{time.strftime('%H:%M:%S')} {msg}")

    def _supervise(self) -> None:
        while not self._stop.is_set():
            self.state = "connecting"
            try:
                self._connect()
            except Exception as exc:  # noqa: BLE001 - the thread must survive anything
                self._fail(f"connect failed: {exc}")
                self._stop.wait(self.reconnect_interval)
                continue
            self.stats.connects += 1
            self.state = self.mode
            self._connected.set()
            self._event(f"{self.mode}ing {len(self.layouts)} bird(s) on {', '.join(self.urls)}")
            readers = [threading.Thread(target=self._read_loop, args=(lk,), daemon=True,
                                        name=f"flock-read-{i}") for i, lk in enumerate(self._links)]
            self._lost.clear()
            for t in readers:
                t.start()
            while not self._stop.is_set() and not self._lost.is_set():
                self._stop.wait(0.05)
            for t in readers:
                t.join(2.0)
            if self._stop.is_set():
                self._shutdown()
                return
            self.stats.disconnects += 1
            self._connected.clear()
            self.state = "disconnected"
            self._close()
            self._stop.wait(self.reconnect_interval)

    def _fail(self, msg: str) -> None:
        self.last_error = msg
        self._event(msg)
        self._close()

    def _close(self) -> None:
        for link in self._links:
            with contextlib.suppress(Exception):
                link.ser.close()
        self._links = []

    def _shutdown(self) -> None:
        for link in self._links:
            with contextlib.suppress(Exception), link.lock:
                link.ser.write(bytes([p.STREAM_STOP]))
                time.sleep(0.02)
                link.ser.write(bytes([p.SLEEP]))
                link.ser.flush()
        self._close()
        self._connected.clear()

    # --- connection and configuration -----------------------------------------------------------
    def _open(self, url: str) -> _Link:
        try:
            ser = serial.serial_for_url(url, do_not_open=True, baudrate=self.baudrate,
                                        bytesize=serial.EIGHTBITS, parity=serial.PARITY_NONE,
                                        stopbits=serial.STOPBITS_ONE, xonxoff=False, rtscts=False,
                                        dsrdtr=False, timeout=self.reply_timeout)
            ser.rts = False  # RTS high would hold the bird in reset: never flow control
            ser.dtr = True
            ser.open()
        except (serial.SerialException, OSError, ValueError) as exc:
            raise DeviceError(f"cannot open: {exc}", url) from None
        link = _Link(url, ser)
        self._links.append(link)
        if self.rts_reset:
            try:
                ser.rts = True
                self._stop.wait(self.rts_reset[0])
                ser.rts = False
                self._stop.wait(self.rts_reset[1])
            except (OSError, serial.SerialException) as exc:  # a pty cannot carry RTS
                self._event(f"{url}: RTS reset not possible ({exc}); continuing without it")
        return link

    def _connect(self) -> None:
        self._links = []
        links = [self._open(url) for url in self.urls]
        for link in links:
            link.ser.write(bytes([p.STREAM_STOP]))
            self._drain(link)
        master = links[0]
        self.info["revision"] = p.decode_revision(self._ask(master, p.examine_value(p.P_REVISION), 2))
        self.info["model"] = self._ask(master, p.examine_value(p.P_MODEL_ID), 10).decode("ascii", "replace").strip()
        address = self._ask(master, p.examine_value(p.P_FBB_ADDRESS), 1)[0]
        flock = address != 0
        if len(links) > 1 and not flock:
            raise DeviceError("several ports, but the first unit is standalone (FBB address 0)", master.url)
        erc = False
        sensors: list[int] = []
        if flock:
            status = self._ask(master, p.examine_value(p.P_SYSTEM_STATUS), 14)
            sensors, units, erc = self._map_flock(status, master.url)
            self._stop.wait(self.autoconfig_wait)
            master.ser.write(p.change_value(p.P_AUTO_CONFIG, bytes([units])))
            self._stop.wait(self.autoconfig_wait)
        self.info["erc"] = "yes" if erc else "no"
        if self.measurement_rate is not None:
            master.ser.write(p.change_value(p.P_MEASUREMENT_RATE, p.measurement_rate_value(self.measurement_rate)))
        self.layouts = {}
        if len(links) == 1:
            master.birds = sensors if flock else [0]
            # group mode whenever the master is not the one bird streamed (several birds, an ERC)
            master.group = flock and master.birds != [address]
        else:
            for link in links:
                link.birds = [self._ask(link, p.examine_value(p.P_FBB_ADDRESS), 1)[0]]
        for link in links:
            for bird in link.birds:
                # per-sensor commands: prefixed on a shared flock port, never to an ERC (spec §2.2)
                prefix = p.fbb_prefix(bird) if flock and len(links) == 1 else b""
                link.ser.write(prefix + bytes([self.format]))
                link.ser.write(prefix + p.hemisphere_command(self.hemisphere))
                if erc:
                    scale = p.ERT_SCALE
                else:
                    code = self._ask(link, prefix + p.examine_value(p.P_POSITION_SCALING), 2)[0]
                    scale = p.POSITION_SCALES[code & 1]
                self.layouts[bird] = BirdLayout(self.format, scale)
            link.decoder = StreamDecoder({b: self.layouts[b] for b in link.birds}, group=link.group)
        if master.group:
            master.ser.write(p.change_value(p.P_GROUP_MODE, b"\x01"))
        for link in links:
            self.device_errors += self._drain_errors(link)
            if self.report_rate in p.REPORT_RATE:
                link.ser.write(bytes([p.REPORT_RATE[self.report_rate]]))
            else:
                link.ser.write(p.change_value(p.P_REPORT_RATE, bytes([self.report_rate])))
            if self.mode == "stream":
                link.ser.write(bytes([p.STREAM]))

    def _map_flock(self, status: bytes, url: str) -> tuple[list[int], int, bool]:
        """From FLOCK SYSTEM STATUS: the sensor birds to stream (the first ``nbirds`` units with
        a sensor, ERCs skipped), the AUTO-CONFIG unit count (the highest address they need; all
        units up to it must answer) and whether an ERC is present."""
        accessible = [a for a, b in enumerate(status, start=1) if b & p.UNIT_ACCESSIBLE]
        have = [a for a in accessible if status[a - 1] & p.UNIT_HAS_SENSOR]
        if len(have) < self.nbirds:
            raise DeviceError(f"{self.nbirds} sensor birds wanted but {len(have)} answer on the bus "
                              f"(system status {status.hex(' ')})", url)
        sensors = have[:self.nbirds]
        units = sensors[-1]
        silent = [a for a in range(1, units + 1) if a not in accessible]
        if silent:
            raise DeviceError(f"FBB address(es) {silent} do not answer; AUTO-CONFIG needs every unit "
                              f"from 1 to {units} (system status {status.hex(' ')})", url)
        erc = any(status[a - 1] & p.UNIT_IS_ERC for a in range(1, units + 1))
        if erc:
            self._event(f"Extended Range Controller present: sensor birds {sensors}, 144 in full scale")
        return sensors, units, erc

    def _ask(self, link: _Link, frame: bytes, n: int) -> bytes:
        """Send a request and read exactly ``n`` reply bytes, or raise a clear timeout."""
        link.ser.write(frame)
        reply = link.ser.read(n)
        if len(reply) != n:
            raise DeviceError(f"no reply to {frame.hex(' ')} (wanted {n} bytes, got "
                              f"{len(reply)} in {self.reply_timeout:g} s)", link.url)
        return reply

    def _drain(self, link: _Link, quiet: float = 0.1) -> None:
        """Discard input until the line has been quiet for ``quiet`` s (after a stream stop)."""
        end = time.monotonic() + 2.0
        link.ser.timeout = quiet
        try:
            while time.monotonic() < end and link.ser.read(4096):
                pass
            link.ser.reset_input_buffer()
        finally:
            link.ser.timeout = self.reply_timeout

    def _drain_errors(self, link: _Link) -> list[tuple[int, str]]:
        found = []
        for _ in range(16):
            code, info = self._ask(link, p.examine_value(p.P_EXPANDED_ERROR), 2)
            if code == 0:
                break
            text = p.error_text(code) + (f" (FBB address {info & 0x0F})" if code == 13 else "")
            found.append((code, text))
            self.last_error = f"device {text}"
            self._event(f"{link.url}: device {text}")
        return found

    def _route(self, bird: int | None) -> tuple[_Link, bytes]:
        if not self._links:
            raise DeviceError("not connected", self.urls[0])
        for link in self._links:
            if bird is None or bird in link.birds:
                return link, (p.fbb_prefix(bird) if link.group and bird else b"")
        raise DeviceError(f"no bird at FBB address {bird}", self.urls[0])

    @contextlib.contextmanager
    def _command_mode(self, link: _Link):
        """Hold the port: stop a stream, drain, run the exchange, restart the stream."""
        with link.lock:
            if self.mode == "stream":
                link.ser.write(bytes([p.STREAM_STOP]))
                self._drain(link)
            try:
                yield
            finally:
                if link.decoder is not None:
                    link.decoder.reset()
                if self.mode == "stream":
                    link.ser.write(bytes([p.STREAM]))

    # --- reading --------------------------------------------------------------------------------
    def _read_loop(self, link: _Link) -> None:
        last_data = time.monotonic()
        next_poll = time.monotonic()
        dec = link.decoder
        counted = (0, 0, 0)
        want = sum(self.layouts[b].length(link.group) for b in link.birds)  # one POINT reply
        try:
            while not self._stop.is_set() and not self._lost.is_set():
                with link.lock:
                    if self.mode == "point":
                        now = time.monotonic()
                        if now < next_poll:
                            data = b""
                        else:
                            next_poll = max(next_poll + 1.0 / self.point_rate, now)
                            link.ser.write(bytes([p.POINT]))
                            data = link.ser.read(want)
                    else:
                        if link.ser.timeout != 0.05:  # the setter reconfigures the port: only on change
                            link.ser.timeout = 0.05
                        data = link.ser.read(max(1, link.ser.in_waiting))
                    now = time.perf_counter()
                    if data:
                        last_data = time.monotonic()
                        self._deliver(dec.feed(data), now)
                        pending = link.ser.in_waiting + dec.pending
                        self.stats.max_pending_bytes = max(self.stats.max_pending_bytes, pending)
                    cur = (dec.records, dec.dropped, dec.skipped_bytes)
                    self.stats.dropped += cur[1] - counted[1]
                    self.stats.skipped_bytes += cur[2] - counted[2]
                    counted = cur
                if self.mode == "point" and not data:
                    time.sleep(min(0.005, max(0.0, next_poll - time.monotonic())))
                if time.monotonic() - last_data > self.data_timeout:
                    raise DeviceError(f"no data for {self.data_timeout:g} s", link.url)
        except Exception as exc:  # noqa: BLE001 - report, never crash the workbench
            self.last_error = f"{link.url}: {exc}" if not isinstance(exc, DeviceError) else str(exc)
            self._event(f"lost the device: {self.last_error}")
            self._lost.set()

    def _deliver(self, records: list[Record], now: float) -> None:
        for rec in records:
            bird = rec.address if rec.address is not None else 0
            seq = self._seq.get(bird, -1) + 1
            self._seq[bird] = seq
            sample = Sample(bird, rec, now, seq)
            self.stats.records += 1
            self.store.put(sample)
            for fn in self._listeners:
                fn(sample)
