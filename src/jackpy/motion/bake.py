"""Baking: a timeline evaluated at a frame rate gives the posture of every figure per frame.

Frame ``i`` is at ``t = i / fps``; it is :meth:`Timeline.apply` at ``t`` followed by one behavior
loop step of each figure (goals -> behaviors -> IK -> FK), figures in name order. Baking is
**deterministic**: the same timeline, scene and figures give the same bits (nothing depends on the
clock, threads or hash order). It is **incremental**: every ``checkpoint_every`` frames the whole
simulation state (each figure's displacements, root and placement, its behaviors' state and
internal memory, the timeline's run state, objects' placements) is kept, so :meth:`Baker.seek`
re-simulates from the nearest kept state at or before the frame asked for, not from 0; editing the
timeline invalidates the frames from the edit's earliest time on (:meth:`Baker.invalidate`).
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from jackpy.behaviors.loop import BehaviorLoop
    from jackpy.motion.timeline import Timeline
    from jackpy.peabody.model import Environment, Figure


@dataclass
class Posture:
    """One figure at one frame: displacements ``q`` (figure DOF order), root ``(segment, site)`` and
    ``location`` (root-site world 4x4)."""

    q: np.ndarray
    root: tuple[str, str] | None
    location: np.ndarray

    @classmethod
    def of(cls, figure: "Figure") -> "Posture":
        return cls(figure.q, None if figure.root is None else tuple(figure.root), figure.location.copy())

    def apply_to(self, figure: "Figure") -> None:
        """Pose ``figure`` like this (re-rooting when the root differs)."""
        if self.root is not None and tuple(figure.root or ()) != self.root:
            figure.reroot(*self.root)
        figure.q = self.q
        figure.location = self.location.copy()

    def same(self, other: "Posture") -> bool:
        """Bit-for-bit equal."""
        return (self.root == other.root and np.array_equal(self.q, other.q)
                and np.array_equal(self.location, other.location))


class SimState:
    """Everything a bake needs to resume at one frame (see the module docstring)."""

    def __init__(self, timeline: "Timeline", loops: Mapping[str, "BehaviorLoop"], env: "Environment") -> None:
        memo = _pins(loops, env)
        self.figures = {}
        for name, loop in loops.items():
            fig = loop.figure
            self.figures[name] = (Posture.of(fig), {g: gr.angles.copy() for g, gr in fig.groups.items()},
                                  copy.deepcopy(loop.state, memo),
                                  [copy.deepcopy(b.__dict__, memo) for b in loop.behaviors],
                                  [(u.key, copy.deepcopy(u, memo)) for u in loop.user_goals
                                   if (u.key or "").startswith("motion ")])
        self.objects = {n: f.location.copy() for n, f in env.figures.items() if n not in loops}
        self.runs = [copy.deepcopy(item.run) for item in timeline.items()]
        self.last_t = timeline._last_t

    def restore(self, timeline: "Timeline", loops: Mapping[str, "BehaviorLoop"], env: "Environment") -> None:
        memo = _pins(loops, env)
        for name, loop in loops.items():
            posture, angles, state, behaviors, goals = self.figures[name]
            fig = loop.figure
            posture.apply_to(fig)
            for g, a in angles.items():
                fig.groups[g].angles = a.copy()
            loop.state.__dict__.clear()
            loop.state.__dict__.update(copy.deepcopy(state.__dict__, memo))
            for b, d in zip(loop.behaviors, behaviors):
                b.__dict__.clear()
                b.__dict__.update(copy.deepcopy(d, memo))
            loop.user_goals[:] = [u for u in loop.user_goals if not (u.key or "").startswith("motion ")]
            loop.user_goals.extend(copy.deepcopy(u, memo) for _, u in goals)
        for n, loc in self.objects.items():
            env.figures[n].location = loc.copy()
        for item, run in zip(timeline.items(), self.runs):
            item.run.clear()
            item.run.update(copy.deepcopy(run))
        timeline._last_t = self.last_t


def _pins(loops: Mapping[str, "BehaviorLoop"], env: "Environment") -> dict[int, Any]:
    """Deep-copy memo keeping the scene's figures, their anatomies and loops shared (not copied)."""
    memo: dict[int, Any] = {}
    for f in env.figures.values():
        memo[id(f)] = f
    for loop in loops.values():
        memo[id(loop)] = loop
        memo[id(loop.figure)] = loop.figure
        memo[id(loop.anatomy)] = loop.anatomy
        kin = loop.figure.kinematics()
        memo[id(kin)] = kin
    return memo


class Baker:
    """Bakes ``timeline`` over ``loops`` (by figure name) at ``fps`` frames per second."""

    def __init__(self, timeline: "Timeline", loops: Mapping[str, "BehaviorLoop"], env: "Environment",
                 fps: float = 30.0, checkpoint_every: int = 15) -> None:
        if not fps > 0:
            raise ValueError(f"fps must be > 0, not {fps}")
        self.timeline, self.loops, self.env = timeline, dict(sorted(loops.items())), env
        self.fps = float(fps)
        self.checkpoint_every = max(1, int(checkpoint_every))
        self.timeline.reset()
        #: the state before frame 0, and after every ``checkpoint_every``-th frame
        self._start = SimState(timeline, self.loops, env)
        self.checkpoints: dict[int, SimState] = {}
        self.frames: list[dict[str, Posture]] = []
        self.current = -1  # the frame the live figures are at
        #: frames simulated since creation (for the incremental-scrub test and progress)
        self.simulated = 0

    @property
    def n_frames(self) -> int:
        """Frames 0 .. floor(duration x fps), both ends included."""
        return int(math.floor(self.timeline.duration * self.fps + 1e-9)) + 1

    def time_of(self, i: int) -> float:
        return i / self.fps

    def frame_at(self, t: float) -> int:
        """The frame shown at time ``t`` (s): the last one at or before it, within the bake."""
        return min(self.n_frames - 1, max(0, int(math.floor(t * self.fps + 1e-9))))

    def _step(self) -> None:
        i = self.current + 1
        self.timeline.apply(self.time_of(i), self.loops, self.env)
        for loop in self.loops.values():
            loop.step()
        self.current = i
        self.simulated += 1
        posture = {name: Posture.of(loop.figure) for name, loop in self.loops.items()}
        if i < len(self.frames):
            self.frames[i] = posture
        else:
            self.frames.append(posture)
        if i % self.checkpoint_every == 0 and i not in self.checkpoints:
            self.checkpoints[i] = SimState(self.timeline, self.loops, self.env)

    def bake(self, progress: Callable[[int, int], None] | None = None) -> list[dict[str, Posture]]:
        """Bake every frame not yet baked (continuing from the last); returns all frames."""
        n = self.n_frames
        if self.current != len(self.frames) - 1:
            self.seek(len(self.frames) - 1 if self.frames else -1)
        while len(self.frames) < n:
            self._step()
            if progress is not None:
                progress(len(self.frames), n)
        return self.frames

    def bake_some(self, budget_s: float) -> bool:
        """Bake further frames for at most about ``budget_s`` seconds; True when all are baked."""
        import time

        end = time.perf_counter() + budget_s
        if self.current != len(self.frames) - 1:
            self.seek(len(self.frames) - 1 if self.frames else -1)
        while len(self.frames) < self.n_frames and time.perf_counter() < end:
            self._step()
        return len(self.frames) >= self.n_frames

    def seek(self, i: int) -> dict[str, Posture] | None:
        """Bring the live figures to frame ``i`` (-1: before frame 0), re-simulating from the nearest
        kept state at or before it (or going on from the current frame when that is nearer)."""
        i = min(int(i), self.n_frames - 1)
        if i != self.current:
            start = max((k for k in self.checkpoints if k <= i), default=-1)
            if not (start <= self.current < i):
                (self.checkpoints[start] if start >= 0 else self._start).restore(self.timeline, self.loops, self.env)
                self.current = start
            while self.current < i:
                self._step()
        return None if i < 0 else self.frames[i]

    def invalidate(self, t: float = 0.0) -> None:
        """Drop frames and kept states from time ``t`` on (after an edit of the timeline)."""
        first = max(0, int(math.floor(t * self.fps + 1e-9)))
        del self.frames[first:]
        self.checkpoints = {k: v for k, v in self.checkpoints.items() if k < first}
        if self.current >= first:
            self.seek(first - 1)
