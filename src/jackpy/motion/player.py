"""Playback of a document's timeline (headless; the timeline panel draws it).

The player bakes the timeline on a **copy** of the scene (the document's figures, objects and
behavior settings at the time playback starts), a little every frame within a time budget, and
shows baked postures on the document's figures: during playback time runs at the real rate
(times ``speed``) and the view shows the latest baked frame at or before it, **dropping frames
rather than slowing time**; scrubbing shows the baked frame of that time, baking up to it from the
nearest kept state when it is not baked yet. Every edit of the timeline (a document command, so
undo covers it) is noticed by its changed contents and re-bakes from the start. When playback
stops, each behavior loop takes the posture shown as its new standing state.
"""

from __future__ import annotations

import copy
import json
from typing import TYPE_CHECKING, Any

from jackpy.motion.bake import Baker, Posture

if TYPE_CHECKING:
    from jackpy.document import Document
    from jackpy.motion.base import Motion


class Player:
    """Plays ``doc.timeline`` (see the module docstring); ``fps`` is the bake rate."""

    def __init__(self, doc: "Document", fps: float = 30.0) -> None:
        self.doc = doc
        self.fps = fps
        self.speed = 1.0
        self.loop = False
        self.playing = False
        self.baker: Baker | None = None
        self._signature: str | None = None
        self._start: dict[str, Posture] = {}
        self.shown: int | None = None

    @property
    def timeline(self) -> Any:
        return self.doc.timeline

    @property
    def time(self) -> float:
        return float(self.doc.time)

    @time.setter
    def time(self, t: float) -> None:
        self.doc.time = float(t)

    def signature(self) -> str:
        return json.dumps(self.timeline.to_dict(), sort_keys=True)

    # ----- the bake -----------------------------------------------------------------------------------
    def ensure_baker(self) -> Baker:
        """The baker of the current timeline contents (a new one after any edit)."""
        sig = self.signature()
        if self.baker is None or sig != self._signature:
            self._signature = sig
            if self.baker is None or not self._start:
                self._start = {n: Posture.of(f) for n, f in self.doc.env.figures.items() if n in self.doc.loops}
            self.baker = self._make_baker()
        return self.baker

    def _make_baker(self) -> Baker:
        from jackpy.motion.cast import loop_for

        env = copy.copy(self.doc.env)
        env.figures = {}
        for name, fig in self.doc.env.figures.items():
            twin = copy.deepcopy(fig)
            if name in self._start:
                self._start[name].apply_to(twin)
            env.figures[name] = twin
        loops = {}
        for name, live in self.doc.loops.items():
            if name not in self.timeline.figures():
                continue
            loop = loop_for(env.figures[name])
            for b, src in zip(loop.behaviors, live.behaviors):
                b.enabled, b.params = src.enabled, copy.deepcopy(src.params)
            loops[name] = loop
        return Baker(self.timeline, loops, env, self.fps)

    # ----- showing ------------------------------------------------------------------------------------
    def show(self, i: int) -> None:
        """Pose the document's figures as baked frame ``i``."""
        frames = self.ensure_baker().frames
        if not frames:
            return
        i = max(0, min(i, len(frames) - 1))
        for name, posture in frames[i].items():
            fig = self.doc.env.figures.get(name)
            if fig is not None:
                posture.apply_to(fig)
        self.shown = i
        self.doc.changed = True
        self.doc.dirty = True

    def scrub(self, t: float) -> None:
        """Go to time ``t`` (s): show its baked frame (baked now from the nearest kept state if needed)."""
        baker = self.ensure_baker()
        t = max(0.0, min(float(t), self.timeline.duration))
        self.time = t
        i = baker.frame_at(t)
        if i >= len(baker.frames):
            baker.seek(i)
        self.show(i)

    def step_frame(self, k: int) -> None:
        """Frame step by ``k`` frames."""
        self.scrub((self.ensure_baker().frame_at(self.time) + k) / self.fps)

    def play(self) -> None:
        if self.time >= self.timeline.duration:
            self.time = 0.0
        self.playing = True

    def pause(self) -> None:
        """Stop; the behavior loops stand in the posture shown."""
        self.playing = False
        for loop in self.doc.loops.values():
            loop.reset_state()

    def update(self, dt: float, budget_s: float = 0.03) -> None:
        """One window frame: bake a little, advance the clock when playing, show the frame."""
        baker = self.ensure_baker()
        baker.bake_some(budget_s)
        if not self.playing:
            return
        t = self.time + dt * self.speed
        if t > self.timeline.duration:
            if self.loop and self.timeline.duration > 0:
                t = t % self.timeline.duration
            else:
                t = self.timeline.duration
                self.time = t
                self.show(baker.frame_at(t))
                self.pause()
                return
        self.time = t
        self.show(baker.frame_at(t))  # the latest baked frame at or before t: frames are dropped, not time

    # ----- edits (document commands, undoable) -------------------------------------------------------
    def retime(self, motion: "Motion", t0: float, t1: float, label: str = "retime motion") -> None:
        def act() -> None:
            motion.t0, motion.t1 = max(0.0, float(t0)), max(float(t0), float(t1))
        self.doc.command(label, act)

    def shift(self, motion: "Motion", dt: float) -> None:
        d = max(-motion.t0, float(dt))
        self.retime(motion, motion.t0 + d, motion.t1 + d, "shift motion")

    def toggle(self, motion: "Motion") -> None:
        self.doc.command("toggle motion", lambda: setattr(motion, "enabled", not motion.enabled))

    def delete(self, motion: "Motion") -> None:
        self.doc.command("delete motion", lambda: self.timeline.remove(motion))

    def set_key(self, figure: str, part: str) -> None:
        """"Set key": the part's current target at the current time (one undo step)."""
        loop = self.doc.loops[figure]
        self.doc.command(f"set key {part}", lambda: self.timeline.set_key(loop, part, self.time))


def load_into(doc: "Document", path: str) -> None:
    """Load the motion file ``path`` as ``doc``'s timeline; figures it names that the scene lacks are
    made from its cast (standard humans) and given behavior loops."""
    from jackpy.motion import cast, motion_file

    mf = motion_file.load(path)
    tl = mf.timeline
    added = False
    for name in tl.figures():
        if name not in doc.env.figures:
            doc.env.add(cast.make_figure(name, tl.cast.get(name)))
            added = True
    if added:
        doc.make_loops()
    doc.timeline, doc.time, doc.playing = tl, 0.0, False
