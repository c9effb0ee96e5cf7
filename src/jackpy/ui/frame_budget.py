"""The frame budget: adaptive quality that keeps the workbench at its target frame rate.

Each :meth:`App.step <jackpy.ui.app.App.step>` asks :meth:`FrameBudget.plan` for the frame's
:class:`FramePlan` and reports the frame back with :meth:`FrameBudget.record`. The budget keeps an
estimate of what a frame costs besides the solve (the draw, the GPU's work, the panels, the swap:
the frame period less the solve, measured from one step to the next) and gives the solve what is
left of the target period (``1 / fps``) as its time box, between ``min_box_s`` and the document's
own box (``settings.ik_time_budget_s``). The solve keeps its box (:class:`BehaviorLoop` stops its
passes by the deadline), so the frame rate follows.

When even the smallest box does not fit, or frames stay over the target, the budget steps down the
quality :data:`LADDER` one rung at a time (fewer solver iterations per pass, fewer COM passes, a
smaller 3-D view drawn while things move, at 1/2 with the skins' coarse level of detail: see
``Renderer.coarse_skin_scale``; on the last rung the behaviors and IK run on every other frame of a
drag only, the frames between draw what moved, the dragged goal; once the button is up every frame
solves again, so the figure settles as fast as on the rung above); after ``RECOVER_FRAMES`` frames
well under the target it steps back up (from the last rung: ``RECOVER_FRAMES`` solving frames
that would fit every frame). A still frame is always drawn at full size and anti-aliased
by the renderer.

The window switches the budget on (:class:`~jackpy.ui.window.Window`); an App without a window
(scripts, tests) runs the frame loop as without one unless ``app.frame_budget.adaptive`` is set.
The status bar shows the rung, the box and the frames whose solve overran its box by more than
``OVERRUN`` (the promise: none); its menu switches the adaptation off (the full rung, the
document's box) or picks the target frame rate.
"""

from __future__ import annotations

from dataclasses import dataclass

from jackpy.document.document import SolveLimits


@dataclass(frozen=True)
class Quality:
    """One rung: caps on every behavior pass's solver iterations and on the COM loop's passes
    (None: the loops' own), the 3-D view's draw scale (fraction of each side) while moving, and
    every how many frames the behaviors and IK run (1: every frame)."""

    name: str
    iterations: int | None
    passes: int | None
    render_scale: float
    solve_every: int = 1


LADDER: tuple[Quality, ...] = (
    Quality("full", None, None, 1.0),
    Quality("2 passes, 3/4 view", 10, 2, 0.75),
    Quality("8 iterations, 1/2 view", 8, 2, 0.5),
    Quality("1 pass, 8 iterations, 1/2 view", 8, 1, 0.5),
    Quality("1 pass, 8 iterations, 1/2 view, IK every 2nd frame", 8, 1, 0.5, 2),
)
"""From the full quality down: each rung is cheaper in the solve and in the draw. No rung caps the
solver below 8 iterations a pass: at 5 the figure drifted away from a released hand's goal (the hand
18 cm off after 30 frames in the window's drag test, against 6 mm at 8). The last rung halves the
behaviors' and IK's rate instead: on llvmpipe a frame's draw alone costs ~20 ms, so a solve on
every frame leaves no 30 frames/s under load."""

OVERRUN = 1.2
"""A solve taking longer than this times its box breaks the promise (counted in ``overruns``)."""
HEADROOM_S = 0.001
"""Kept free of the target period besides the estimated cost (s)."""
SETTLE_FRAMES = 4
"""Frames after a change of rung before the next step down (the estimates must see it)."""
RECOVER_FRAMES = 30
"""Consecutive frames under ``RECOVER_FRACTION`` of the target before one step back up."""
RECOVER_FRACTION = 0.6
RECOVER_FRACTION_SOLVING = 0.8
"""On a rung that solves one frame in ``solve_every``, the rung above solves every frame with the
same caps and view, so its frames cost what this rung's solving frames cost: only those count
towards the step back up, calm under this fraction of the target. (With the frames that draw only
counted too, a drag that solves in 24 ms and draws in 14 ms on llvmpipe never went back up:
every other frame was over 0.6 of the target, and half the frames went without a solve at 40
frames/s that could all have solved.) Not while the smallest box is squeezed out of the target
(the rung above would step straight back down: in the window's whole-figure drag it went up and
down every ~45 frames)."""


@dataclass(frozen=True)
class FramePlan:
    """What one frame may do: the solve's ``limits`` (None: the document's own box, counting
    whole behavior frames, as without a frame budget), the 3-D view's ``render_scale``,
    ``solve``: whether the frame may solve at all, and ``box_s``: the solve's box (s)."""

    limits: SolveLimits | None
    render_scale: float
    level: int
    solve: bool = True
    box_s: float = 0.0


class FrameBudget:
    """Adaptive quality for a target of ``fps`` frames per second (module docstring)."""

    def __init__(self, fps: float = 30.0, min_box_s: float = 0.010, adaptive: bool = False) -> None:
        if not fps > 0:
            raise ValueError(f"target frame rate must be > 0, not {fps:g}")
        self.fps = float(fps)
        self.min_box_s = float(min_box_s)
        self.adaptive = adaptive
        self.level = 0
        """Index into :data:`LADDER` (0: full quality)."""
        self.other_s = 0.0
        """Estimated cost of a frame besides its solve (s)."""
        self.behaviors_s = 0.0
        """Estimated cost of the behaviors' own work in a solve (s): the box is at least twice it,
        so the IK keeps half the box."""
        self.box_s = 0.0
        """The box of the last plan (s)."""
        self.worst_overrun = 0.0
        """The largest solve / box ratio seen (the promise: at most ``OVERRUN``)."""
        self._unsolved = max(q.solve_every for q in LADDER)
        """Planned frames since the last one that might solve (the first one may)."""
        self.overruns = 0
        """Frames whose solve ran past ``OVERRUN`` times its box."""
        self.solves = 0
        """Frames that solved."""
        self._since_change = SETTLE_FRAMES
        self._calm = 0

    @property
    def target_s(self) -> float:
        """The target frame period (s)."""
        return 1.0 / self.fps

    @property
    def quality(self) -> Quality:
        return LADDER[self.level if self.adaptive else 0]

    def plan(self, document_box_s: float) -> FramePlan:
        """The next frame's plan, given the document's own time box (s)."""
        if not self.adaptive:
            self.box_s = document_box_s
            return FramePlan(None, 1.0, 0, True, document_box_s)
        q = self.quality
        fits = self.target_s - self.other_s - HEADROOM_S
        self.box_s = min(document_box_s, max(self.min_box_s, 2.0 * self.behaviors_s, fits))
        solve = self._unsolved + 1 >= q.solve_every  # one frame in solve_every may solve
        self._unsolved = 0 if solve else self._unsolved + 1
        return FramePlan(SolveLimits(self.box_s, q.iterations, q.passes), q.render_scale, self.level, solve,
                         self.box_s)

    def record(self, period_s: float, solve_s: float, box_s: float, solved: bool, drawn: bool = True,
               behaviors_s: float = 0.0) -> None:
        """The previous frame is over: ``period_s`` from its start to this one's (s), ``solve_s``
        its solve (of which ``behaviors_s`` the behaviors' own work), ``box_s`` its box, ``solved``
        whether it solved, ``drawn`` whether it drew the 3-D view. A frame that did neither
        measures nothing (the window may have slept on input)."""
        if solved:
            self.solves += 1
            w = 0.5 if behaviors_s > self.behaviors_s else 0.2
            self.behaviors_s += w * (behaviors_s - self.behaviors_s)
            if solve_s > OVERRUN * box_s:
                self.overruns += 1
            if box_s > 0.0:
                self.worst_overrun = max(self.worst_overrun, solve_s / box_s)
        if not (solved or drawn):
            self._calm += 1  # an idle frame: nothing was slow
            self._recover()
            return
        other = max(0.0, period_s - solve_s)
        self.other_s = other if other > self.other_s else 0.7 * self.other_s + 0.3 * other
        self._since_change += 1
        if not self.adaptive:
            return
        floor = max(self.min_box_s, 2.0 * self.behaviors_s)
        squeezed = self.other_s + floor + HEADROOM_S > self.target_s
        slow = solved and period_s > self.target_s and self.box_s <= floor
        if (squeezed or slow) and self.level < len(LADDER) - 1 and self._since_change >= SETTLE_FRAMES:
            self.level += 1
            self._since_change, self._calm = 0, 0
            return
        if self.quality.solve_every > 1:
            if solved:  # a frame that only drew says nothing about the rung above
                self._calm = self._calm + 1 if period_s < RECOVER_FRACTION_SOLVING * self.target_s else 0
            if squeezed:  # the smallest box would not fit a solve on every frame: the rung above is too dear
                return
        else:
            self._calm = self._calm + 1 if period_s < RECOVER_FRACTION * self.target_s else 0
        self._recover()

    def _recover(self) -> None:
        if self.adaptive and self.level > 0 and self._calm >= RECOVER_FRAMES:
            self.level -= 1
            self._calm, self._since_change = 0, 0

    def describe(self) -> str:
        """One line for the status bar: the rung, the box and the overruns."""
        if not self.adaptive:
            return f"quality fixed, box {self.box_s * 1e3:.0f} ms, {self.overruns} over"
        return (f"quality {len(LADDER) - self.level}/{len(LADDER)} ({self.quality.name}), "
                f"box {self.box_s * 1e3:.0f} ms, {self.overruns} over")


__all__ = ["FrameBudget", "FramePlan", "LADDER", "Quality"]
