"""Record: a live drag or a Flock-driven session turned into key tracks on the timeline (issue 12).

A :class:`Recorder` watches one figure of a document while something else drives it (the operator
dragging a hand, :class:`~jackpy.behaviors.sensor_drive.SensorDrive` streaming sensors, a script)
and samples the **targets of its parts** at a chosen rate: each sample stores what "set key"
stores (:func:`jackpy.motion.keyframes.capture`: the palm and ball poses, the pelvis rotation, the
balance parameters, the gaze point, joint displacements for ``joint:NAME``), read from the posture
the behaviors and IK produced that frame, so the keys are always reachable and replaying them
drives the same goals to the posture that was seen. Keys are goal targets, not joint angles
(except joint keys, which say so), as everywhere on the timeline.

Timing: the recording starts at the timeline's current time ``t0``; :meth:`Recorder.tick` is
called once per frame with the frame's duration and takes a sample whenever a sample time
``t0 + k / rate`` has come, stamped with the frame's own time (so keys sit where the posture was
seen, at most ``rate`` per second; a slow frame gives one key, never copies). :meth:`Recorder.stop`
takes a last sample and puts the tracks on the document's timeline (made when the document has
none) as **one undoable command**, replacing the keys of those parts within the recorded span and
keeping keys outside it; the timeline's clock moves to the end of the take.

Which parts: those given, or by default the parts that were *driven*, as the behaviors' state
says: a hand with a goal (dragged, or a palm sensor's target) whose palm moved, the pelvis with a
user goal, the balance point while it was dragged, head and eyes with a gaze target; a foot whose
ball moved (a foot drag or a step). "Moved" is more than :data:`MOVE_TOLERANCE` (5 mm, 1 deg, 0.01
of the balance) during the take. Parts that only followed along (an arm hanging from a leaning
torso) are not recorded unless asked for.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from jackpy.motion.keyframes import POSE_PARTS, KeyTrack, capture

if TYPE_CHECKING:
    from jackpy.behaviors.sensor_drive import SensorDrive
    from jackpy.devices.recording import Recording
    from jackpy.document import Document

#: the parts a take may record when none are named (joint keys only when named)
AUTO_PARTS = ("hand.right", "hand.left", "foot.right", "foot.left", "pelvis", "com", "head", "eyes")
#: a part counts as driven when its target moved more than this: (metres, radians, balance units)
MOVE_TOLERANCE = (0.005, np.radians(1.0), 0.01)
DEFAULT_RATE = 10.0


def _moved(part: str, a: np.ndarray, b: np.ndarray) -> bool:
    dist, angle, balance = MOVE_TOLERANCE
    if part in POSE_PARTS or part == "pelvis":
        ra, rb = (a[:3, :3], b[:3, :3])
        cos = np.clip((np.trace(ra.T @ rb) - 1.0) / 2.0, -1.0, 1.0)
        if np.arccos(cos) > angle:
            return True
        return part != "pelvis" and float(np.linalg.norm(a[:3, 3] - b[:3, 3])) > dist
    if part == "com":
        return float(np.max(np.abs(a - b))) > balance
    if part.startswith("joint:"):
        return float(np.max(np.abs(a - b), initial=0.0)) > angle
    return float(np.linalg.norm(a - b)) > dist


class Recorder:
    """Samples figure ``figure`` of ``doc`` at ``rate`` Hz into key tracks (module docstring).

    ``parts``: key parts to record (None: the driven ones); ``joints``: joint names recorded as
    joint-angle keys as well (a Flock session's spine, say); ``interpolation``: the tracks'
    (``cubic`` passes through every sample smoothly; ``linear``).
    """

    def __init__(self, doc: "Document", figure: str, rate: float = DEFAULT_RATE,
                 parts: Sequence[str] | None = None, joints: Iterable[str] = (),
                 interpolation: str = "cubic") -> None:
        if figure not in doc.loops:
            raise ValueError(f"figure {figure!r} has no behavior loop to record (only standard humans record)")
        if not rate > 0:
            raise ValueError(f"recording rate must be > 0 Hz, not {rate}")
        self.doc, self.figure, self.rate, self.interpolation = doc, figure, float(rate), interpolation
        self.named = parts is not None
        self.parts = list(parts if parts is not None else AUTO_PARTS) + [f"joint:{j}" for j in joints]
        for p in self.parts:
            KeyTrack(figure, p)  # (rejects an unknown part now, not at the end of a take)
        self.samples: dict[str, list[tuple[float, np.ndarray]]] = {p: [] for p in self.parts}
        self.driven: set[str] = set()
        self.recording = False
        self.t0 = 0.0
        self.elapsed = 0.0
        self._next = 0

    @property
    def time(self) -> float:
        """The timeline time of the frame now being recorded (s)."""
        return self.t0 + self.elapsed

    def start(self, t0: float | None = None) -> None:
        """Begin a take at timeline time ``t0`` (default: the document's clock); the first sample
        is the posture now."""
        self.t0 = float(self.doc.time if t0 is None else t0)
        self.elapsed, self._next = 0.0, 0
        self.samples = {p: [] for p in self.parts}
        self.driven = set()
        self.recording = True
        self.sample()

    def tick(self, dt: float) -> bool:
        """A frame of ``dt`` seconds has been shown: sample it if a sample time has come; True when
        it took one."""
        if not self.recording:
            return False
        self.elapsed += max(0.0, float(dt))
        if self.elapsed * self.rate + 1e-9 < self._next:
            return False
        self.sample()
        return True

    def sample(self) -> None:
        """Store every part's current target at :attr:`time`."""
        loop = self.doc.loops[self.figure]
        st = loop.state
        flags = {"head": st.head_target is not None, "eyes": st.eyes_target is not None,
                 "pelvis": bool(st.pelvis_user), "com": st.com_drag is not None,
                 "foot.left": True, "foot.right": True}
        for side, hs in st.hands.items():
            flags[f"hand.{side}"] = hs.goal is not None
        self.driven |= {p for p, on in flags.items() if on}
        t = self.time
        for p in self.parts:
            self.samples[p].append((t, np.array(capture(loop, p), dtype=float)))
        self._next = int(np.floor(self.elapsed * self.rate + 1e-9)) + 1

    def recorded_parts(self) -> list[str]:
        """The parts the take keeps: all named ones, else the driven ones (module docstring)."""
        if self.named:
            return [p for p in self.parts if self.samples[p]]
        out = []
        for p in self.parts:
            s = self.samples[p]
            if not s:
                continue
            if p.startswith("joint:"):
                out.append(p)
            elif p in self.driven and (p in ("head", "eyes") or any(_moved(p, s[0][1], v) for _, v in s[1:])):
                out.append(p)
        return out

    def tracks(self) -> list[KeyTrack]:
        """The take as key tracks (not yet on the timeline)."""
        return [KeyTrack(self.figure, p, list(self.samples[p]), self.interpolation) for p in self.recorded_parts()]

    def stop(self) -> list[KeyTrack]:
        """End the take: a last sample, then the tracks onto the timeline as one undoable command
        ("record"); returns the timeline's tracks that now hold the take."""
        if not self.recording:
            return []
        if not self.samples[self.parts[0]] or self.samples[self.parts[0]][-1][0] < self.time - 1e-12:
            self.sample()
        self.recording = False
        take = self.tracks()
        if not take:
            self.doc.info("record: nothing moved, no keys")
            return []
        t_end = self.time
        doc = self.doc
        result: list[KeyTrack] = []
        if doc.timeline is None:  # (made before the command, so undo empties it rather than keeping the take)
            from jackpy.motion.timeline import Timeline

            doc.timeline = Timeline()

        def act() -> None:
            tl = doc.timeline
            result.clear()
            for tr in take:
                target = tl.track(self.figure, tr.part)
                keep = [(t, v) for t, v in target.keys if not self.t0 - 1e-9 <= t <= t_end + 1e-9]
                target.keys = sorted(keep + [(t, v.copy()) for t, v in tr.keys], key=lambda k: k[0])
                target.interpolation = tr.interpolation
                result.append(target)
            doc.time = t_end

        doc.command(f"record {', '.join(tr.part for tr in take)}", act)
        return result


def record_recording(doc: "Document", drive: "SensorDrive", recording: "Recording",
                     rate: float = DEFAULT_RATE, every: int = 1, **kw: object) -> list[KeyTrack]:
    """A Flock of Birds recording replayed into ``drive``'s figure (every ``every``-th frame,
    calibrated on its first frame) and recorded as key tracks on ``doc``'s timeline from its clock,
    on the recording's own clock (sample times). ``kw`` go to :class:`Recorder` (``parts``,
    ``joints``, ``interpolation``)."""
    from jackpy.behaviors.sensor_drive import replay_into

    frames = recording.frames()
    if not frames:
        return []
    times = [min(s.time for s in fr.values()) for fr in frames]
    rec = Recorder(doc, drive.loop.figure.name, rate, **kw)  # type: ignore[arg-type]
    started = False
    last = times[0]
    for k, _report in replay_into(drive, recording, every=every):
        if not started:
            rec.start()
            started = True
        else:
            rec.tick(times[k] - last)
        last = times[k]
    return rec.stop()


__all__ = ["AUTO_PARTS", "MOVE_TOLERANCE", "Recorder", "record_recording"]
