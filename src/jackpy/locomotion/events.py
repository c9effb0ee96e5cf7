"""The footstep/contact event log (Sims Ch. 13): ``(frame, cause, location)`` per collision or
motion event, exported as CSV (``frame,time_s,cause,who,x,y,z``; metres, seconds)."""

from __future__ import annotations

import csv
import io
import os
from dataclasses import dataclass, field

import numpy as np

from jackpy.atomic import atomic_write_text


@dataclass
class Event:
    frame: int
    time: float
    cause: str  # "footstep", "liftoff", "landing", "takeoff", "bounce"
    who: str  # the foot, figure or object
    location: np.ndarray


@dataclass
class EventLog:
    fps: float
    events: list[Event] = field(default_factory=list)

    def add(self, frame: int, cause: str, who: str, location: np.ndarray, time: float | None = None) -> None:
        self.events.append(Event(int(frame), frame / self.fps if time is None else float(time), cause, who,
                                 np.asarray(location, dtype=float).copy()))

    def of(self, cause: str) -> list[Event]:
        return [e for e in self.events if e.cause == cause]

    def to_csv(self) -> str:
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["frame", "time_s", "cause", "who", "x", "y", "z"])
        for e in sorted(self.events, key=lambda e: (e.frame, e.time)):
            w.writerow([e.frame, repr(e.time), e.cause, e.who] + [repr(float(v)) for v in e.location])
        return buf.getvalue()

    def save_csv(self, path: str | os.PathLike[str]) -> None:
        atomic_write_text(path, self.to_csv())
