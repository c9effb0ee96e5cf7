"""Record raw Flock samples to a file as they arrive, and read and replay them.

File format (text, one JSON value per line, UTF-8): the first line is a header object
``{"jackpy": "flock-recording", "version": 1, ...}``; every other line is one sample
``[t, bird, seq, format, scale, [words...], button, metal]`` with ``t`` in seconds since the
recording started, ``format`` the record format's command letter, ``scale`` the position full
scale in inches and ``words`` the record's signed 16-bit words (device units, transmitter frame).

Safety: the header is written to a temporary file and renamed into place, so a recording file
always starts with a valid header; samples are appended and handed to the operating system at
least every ``flush_interval`` seconds (default 0.25 s: by the first sample that comes later, or
by a flusher thread when samples stop), and a flusher thread forces them to disk. So a killed process loses at most
the last quarter second (the promise is one second, with margin; a power cut may lose what the
disk had not yet written). A torn last line is ignored on read; a recording with a header and no
samples reads as an empty recording.
"""

from __future__ import annotations

import contextlib
import json
import os
import threading
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from jackpy import jsonfile
from jackpy.devices.flock.driver import Sample
from jackpy.devices.flock.protocol import Format, Record, angles_from_rotation
from jackpy.errors import DeviceError, ParseError

MAGIC = "flock-recording"


class Recorder:
    """Append samples to ``path`` (thread-safe; use :meth:`add` as a driver listener)."""

    def __init__(self, path: str | os.PathLike, meta: Mapping[str, Any] | None = None,
                 flush_interval: float = 0.25) -> None:
        if not 0.0 < flush_interval <= 1.0:
            raise DeviceError(f"flush interval must be within (0, 1] s, not {flush_interval:g}")
        self.path = Path(path)
        header = {"jackpy": MAGIC, "version": 1, "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
                  "units": "inches, 16-bit record words, transmitter frame", **(meta or {})}
        tmp = self.path.with_name(self.path.name + ".tmp")
        try:
            with open(tmp, "w", encoding="utf-8") as f:
                f.write(json.dumps(header) + "\n")
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, self.path)
            self._file = open(self.path, "a", encoding="utf-8")
        except OSError as exc:
            raise DeviceError(f"cannot write recording {self.path}: {exc.strerror}") from None
        self._lock = threading.Lock()
        self._sync_lock = threading.Lock()
        self._interval = flush_interval
        self._flushed = time.monotonic()
        self._t0: float | None = None
        self.count = 0
        self._closed = threading.Event()
        self._flusher = threading.Thread(target=self._flush_loop, args=(flush_interval,),
                                         name="flock-recorder", daemon=True)
        self._flusher.start()

    def add(self, sample: Sample) -> None:
        """Append one sample; its time is taken relative to the first sample recorded."""
        rec = sample.record
        with self._lock:
            if self._closed.is_set():
                return
            if self._t0 is None:
                self._t0 = sample.time
            row = [round(sample.time - self._t0, 6), sample.bird, sample.seq, chr(rec.format),
                   rec.scale, list(rec.words), rec.button, rec.metal]
            self._file.write(json.dumps(row, separators=(",", ":")) + "\n")
            self.count += 1
            if time.monotonic() - self._flushed >= self._interval:
                self._hand_over()  # a write call; the flusher thread does the slow fsync

    def _hand_over(self) -> None:
        """Give the buffered lines to the operating system (lock held): they survive a kill."""
        if not self._file.closed:
            self._file.flush()
        self._flushed = time.monotonic()

    def _sync(self) -> None:
        """Force what the OS holds to disk, outside the writers' lock (an fsync may be slow)."""
        with self._sync_lock, contextlib.suppress(OSError, ValueError):  # ValueError: closed
            os.fsync(self._file.fileno())

    def flush(self) -> None:
        """Push everything written so far to disk."""
        with self._lock:
            self._hand_over()
        self._sync()

    def _flush_loop(self, interval: float) -> None:
        synced = 0
        while not self._closed.wait(interval / 2):
            with self._lock:
                if time.monotonic() - self._flushed >= interval:
                    self._hand_over()
                count = self.count
            if count != synced:
                self._sync()
                synced = count

    def close(self) -> None:
        self.flush()
        with self._lock, self._sync_lock:
            self._closed.set()
            self._file.close()

    def __enter__(self) -> Recorder:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


@dataclass
class Recording:
    """A recording read back: its header and samples (``Sample.time`` = seconds from start)."""

    header: dict[str, Any]
    samples: list[Sample]

    def __post_init__(self) -> None:
        self._per_bird: dict[int, list[Sample]] = {}
        for s in self.samples:
            self._per_bird.setdefault(s.bird, []).append(s)
        self._times = {b: np.array([s.time for s in v]) for b, v in self._per_bird.items()}

    @property
    def birds(self) -> list[int]:
        return sorted({s.bird for s in self.samples})

    @property
    def duration(self) -> float:
        return self.samples[-1].time if self.samples else 0.0

    def frames(self) -> list[dict[int, Sample]]:
        """Samples grouped by measurement cycle: a new frame starts when a bird repeats."""
        frames: list[dict[int, Sample]] = []
        cur: dict[int, Sample] = {}
        for s in self.samples:
            if s.bird in cur:
                frames.append(cur)
                cur = {}
            cur[s.bird] = s
        if cur:
            frames.append(cur)
        return frames

    def pose_at(self, t: float, bird: int) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """(position in inches, angles in degrees) of ``bird`` at ``t`` s, looping the recording;
        usable as a simulator motion."""
        mine = self._per_bird.get(bird)
        if not mine:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        times = self._times[bird]
        t = t % (self.duration or 1.0)
        rec = mine[max(0, int(np.searchsorted(times, t, side="right")) - 1)].record
        pos = rec.position or (0.0, 0.0, 0.0)
        r = rec.rotation()
        ang = tuple(np.degrees(angles_from_rotation(r))) if r is not None else (0.0, 0.0, 0.0)
        return pos, ang  # type: ignore[return-value]


def read_recording(path: str | os.PathLike) -> Recording:
    """Read a recording; a malformed line raises :class:`ParseError` at its line (a torn last
    line is skipped); an unreadable file raises :class:`DeviceError`.

    Each sample is checked: finite time >= 0, bird 0..126, a known record format with its number
    of 16-bit words, a finite positive scale, button and metal bytes 0..255 or null. The header's
    fields the replay commands use (``figure``, ``calibrate_frame``, ``sensors``) are checked too.
    """
    name = str(path)
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise DeviceError(f"cannot read recording {name}: {exc.strerror or exc}") from None
    except ValueError:  # a name with a NUL byte
        raise DeviceError(f"cannot read recording {name!r}: not a valid file name") from None
    text = jsonfile.decode(data, name)
    lines = text.split("\n")
    torn = lines[-1] != ""  # no final newline: the last line may have been cut by a crash
    lines = lines[:-1] if not torn else lines
    try:
        header = jsonfile.loads(lines[0], name) if lines else None
    except ParseError:
        header = None
    if not isinstance(header, dict) or header.get("jackpy") != MAGIC:
        raise ParseError("not a jackpy Flock recording (bad header line)", name, 1, 1)
    try:
        _check_header(header)
    except jsonfile.Invalid as exc:
        raise ParseError(f"bad header: {exc}", name, 1, 1) from None
    samples = []
    for k, line in enumerate(lines[1:], start=2):
        try:
            samples.append(_sample(jsonfile.loads(line, name, line=k)))
        except (ParseError, jsonfile.Invalid) as exc:
            if torn and k == len(lines):
                break
            if isinstance(exc, ParseError):
                raise ParseError(f"bad sample line: {exc.message}", name, k, exc.column) from None
            raise ParseError(f"bad sample line: {exc}", name, k, 1) from None
    return Recording(header, samples)


def _check_header(header: dict[str, Any]) -> None:
    if "figure" in header:
        fig = jsonfile.obj(header["figure"], "figure")
        if "sex" in fig:
            jsonfile.string(fig["sex"], "figure.sex", ("male", "female"))
        if "percentile" in fig:
            jsonfile.num(fig["percentile"], "figure.percentile", 1.0, 99.0)
    if "calibrate_frame" in header:
        jsonfile.integer(header["calibrate_frame"], "calibrate_frame", 0, 2**31 - 1)
    if "sensors" in header:
        jsonfile.obj(header["sensors"], "sensors")


def _sample(row: Any) -> Sample:
    """One sample line ``[t, bird, seq, format, scale, [words...], button, metal]`` (module doc)."""
    row = jsonfile.arr(row, "sample")
    if len(row) != 8:
        raise jsonfile.Invalid("sample", f"expected 8 values [t, bird, seq, format, scale, words, button, "
                                         f"metal], found {len(row)}")
    t = jsonfile.num(row[0], "t", 0.0)
    bird = jsonfile.integer(row[1], "bird", 0, 126)
    seq = jsonfile.integer(row[2], "seq", -2**63, 2**63 - 1)
    letter = jsonfile.string(row[3], "format")
    try:
        fm = Format(ord(letter)) if len(letter) == 1 else None
    except ValueError:
        fm = None
    if fm is None:
        raise jsonfile.Invalid("format", "expected a record format letter ("
                               + ", ".join(chr(f.value) for f in Format) + f"), found {letter[:10]!r}")
    scale = jsonfile.num(row[4], "scale")
    if scale <= 0:
        raise jsonfile.Invalid("scale", f"expected a positive number, found {scale:g}")
    words = jsonfile.arr(row[5], "words")
    if len(words) != fm.words:
        raise jsonfile.Invalid("words", f"{fm.name.lower()} needs {fm.words} words, found {len(words)}")
    words = [jsonfile.integer(w, f"words[{i}]", -32768, 32767) for i, w in enumerate(words)]
    button, metal = (None if v is None else jsonfile.integer(v, what, 0, 255)
                     for v, what in ((row[6], "button"), (row[7], "metal")))
    return Sample(bird, Record(fm, tuple(words), scale, button, metal, bird), t, seq)


def replay(recording: Recording, speed: float = 1.0) -> Iterator[dict[int, Sample]]:
    """Yield the recording's frames; with ``speed`` > 0 paced in real time (×speed), with
    ``speed`` = 0 as fast as the caller takes them (frame by frame)."""
    start = time.perf_counter()
    for frame in recording.frames():
        if speed > 0:
            t = min(s.time for s in frame.values()) / speed
            delay = start + t - time.perf_counter()
            if delay > 0:
                time.sleep(delay)
        yield frame


class FrameMotion:
    """A :class:`~jackpy.devices.flock.simulator.FlockSimulator` motion that plays a recording
    frame by frame: the k-th record the simulator emits for a bird carries that bird's pose in
    frame k, so the recording runs at the simulator's rate, counted in records, not in seconds.

    Until :meth:`play` it holds frame ``start`` (an operator standing still for calibration);
    after the last frame it holds the last one. ``frame`` is the lowest frame index emitted so
    far across birds, ``done`` tells when every bird has passed the last frame.
    """

    def __init__(self, recording: Recording, start: int = 0) -> None:
        frames = recording.frames()
        if not frames:
            raise DeviceError("the recording holds no frames")
        self.birds = recording.birds
        self.start = start
        self.n = len(frames)
        self._poses: dict[int, list[tuple[tuple[float, float, float], tuple[float, float, float]]]] = {}
        last: dict[int, tuple] = {}
        for frame in frames:
            for b in self.birds:
                if b in frame:
                    last[b] = _pose_of(frame[b].record)
                self._poses.setdefault(b, []).append(last.get(b, ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))))
        self._count: dict[int, int] = {}
        self._playing = False
        self._lock = threading.Lock()

    def play(self) -> None:
        """Start advancing one frame per emitted record (per bird)."""
        with self._lock:
            self._count = {b: self.start for b in self.birds}
            self._playing = True

    @property
    def frame(self) -> int:
        with self._lock:
            if not self._playing:
                return self.start
            return min(self._count.get(b, self.start) for b in self.birds)

    @property
    def done(self) -> bool:
        return self.frame >= self.n

    def __call__(self, t: float, address: int):
        poses = self._poses.get(address)
        if poses is None:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
        with self._lock:
            if not self._playing:
                k = self.start
            else:
                k = self._count.get(address, self.start)
                self._count[address] = k + 1
        return poses[min(k, self.n - 1)]


def _pose_of(rec: Record) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
    pos = rec.position or (0.0, 0.0, 0.0)
    r = rec.rotation()
    ang = tuple(float(a) for a in np.degrees(angles_from_rotation(r))) if r is not None else (0.0, 0.0, 0.0)
    return tuple(float(v) for v in pos), ang  # type: ignore[return-value]
