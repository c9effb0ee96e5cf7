"""Live driving of a figure from Flock of Birds sensors ([SH4] §4.5; behaviors.md §5).

:class:`SensorDrive` turns the latest sensor samples into goals of a :class:`BehaviorLoop`, one
frame at a time, in the book's order:

1. **pelvis**: the waist sensor's target sets the pelvis orientation goal
   (:func:`~jackpy.behaviors.manipulation.move_pelvis` with ``rotation``) and its floor position:
   each frame the balance point is dragged (``move_pelvis`` with ``translation``, at most
   ``pelvis_max_shift``) towards the COM's floor point plus ``pelvis_gain`` × the horizontal
   distance from the pelvis site to its target, so the pelvis settles on the sensor while the COM
   stays the balance goal; when the feet hold the body back the point reaches the edge of the
   support polygon and the stepping behavior takes a step. [proposal]
   The book roots the figure through the pelvis and sets its pose outright; jackpy keeps its feet
   planted and balanced, so the pelvis is servoed instead. Its height follows the legs.
2. **spine**: the neck sensor against the waist sensor gives the spine target (flexion, lateral
   bend, axial twist; :func:`~jackpy.devices.sensors.spine_angles` measured from the calibration
   pose), sent straight to the spine (:func:`~jackpy.behaviors.manipulation.bend_torso`), with
   ``spine_iterations`` corrections so the base of the neck really turns by the target.
3. **arms**: each palm sensor's target is the palm site's position + orientation goal
   (:func:`~jackpy.behaviors.manipulation.hand_on_site`); the arm pass solves it.
4. **COM, stepping and legs**: :meth:`BehaviorLoop.step` runs the behaviors (balance, the stepping
   behavior when the dragged balance point nears the edge of the feet or the pelvis twists past
   the feet) and the IK passes.

**Split frames** (``DriveConfig.split``, live driving): a sample's frame solves only what the
sensors drive at their rate: the spine (2., by forward kinematics) and the arms (3., the loop's
own arm/head pass with its cached problem, the body frozen). The pelvis servo and the loop's full
step (4.: every behavior and pass) run in :meth:`SensorDrive.idle` after every ``idle_every``
split frames, in the time before the next sample is due, time-boxed to end by then, and after
``body_every - 1`` of them whatever the time left; when ``idle`` is not called, every
``body_every``-th sample frame is a full one, and so is every frame while a step is under way.
[proposal]

Samples are read without blocking (the driver's latest-value store); a frame with no new sample
still steps the loop (a step in progress goes on). Smoothing (one-euro, per part) is off by
default. :meth:`SensorDrive.calibrate` captures the transmitter placement and each sensor's offset
to its body site while the operator stands in the figure's current (neutral) pose.

:func:`replay_into` drives a figure from a recording, frame by frame or at real speed.
"""

from __future__ import annotations

import collections
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from jackpy.behaviors import manipulation as m
from jackpy.behaviors.anatomy import SIDES
from jackpy.behaviors.loop import BehaviorLoop, Frame, FrameReport
from jackpy.behaviors.support import floor
from jackpy.devices.flock.driver import Sample
from jackpy.devices.recording import Recording
from jackpy.devices.sensors import (
    Calibration,
    SensorConfig,
    TargetSmoother,
    calibrate,
    default_config,
    sensor_targets,
    spine_angles,
)
from jackpy.errors import DeviceError
from jackpy.ik import solve

HANDS = {"left_palm": "left", "right_palm": "right"}
#: behaviors whose goals go only to the loop's head-and-arm pass (a split frame runs these)
ARM_BEHAVIORS = ("gaze", "hands", "limit springs")


@dataclass
class DriveConfig:
    """How sensors drive the figure. ``sensors``: which bird is on which part and where the
    transmitter is; ``smoothing`` turns on the one-euro filter (``min_cutoff`` Hz, ``beta``,
    ``beta_rot``); ``pelvis``/``torso``/``hands`` switch each stage; ``pelvis_gain`` and
    ``pelvis_max_shift`` (m per frame) servo the pelvis; ``spine_iterations`` corrections of the
    spine bend; ``place_transmitter``: calibration places the transmitter from the waist sensor
    (else the configured placement is kept); ``frame_budget_ms``: bounded work per frame (live
    driving, CPU ms; :class:`FrameBudget`): the loop's solver iterations are cut while frames run
    over the budget and given back while they run well under it (None: the loop's own settings);
    ``split``: sample frames solve the spine and arms only, the rest runs in :meth:`SensorDrive.idle`
    after every ``idle_every`` of them (module docstring), or in every ``body_every``-th frame when
    no idle step came;
    ``idle_min_ms``: an idle step starts only with this much time (ms) for its solves left
    before the next sample, besides its behaviors' learned cost."""

    sensors: SensorConfig = field(default_factory=default_config)
    smoothing: bool = False
    min_cutoff: float = 1.0
    beta: float = 0.5
    beta_rot: float = 0.1
    pelvis: bool = True
    torso: bool = True
    hands: bool = True
    pelvis_gain: float = 1.0
    pelvis_max_shift: float = 0.05
    spine_iterations: int = 2
    place_transmitter: bool = True
    frame_budget_ms: float | None = None
    split: bool = False
    idle_every: int = 2
    body_every: int = 4
    idle_min_ms: float = 3.0


@dataclass
class DriveReport:
    """One frame of :meth:`SensorDrive.step`.

    ``frame`` counts steps; ``fresh`` the birds with a new sample this frame; ``skipped`` the
    samples that arrived since the last frame but were overwritten before it (latest-value
    semantics); ``targets`` the world 4x4 per part; ``errors`` the distance (m) of each driven site
    from its target after the solve; ``spine`` the spine angles set (flexion, lateral, axial, rad;
    the spine group's) so the figure's neck turns against its waist as the neck sensor does
    against the waist sensor, and ``spine_target`` that turn (same order and units);
    ``arrival`` the host time (``time.perf_counter``) the newest consumed sample arrived, or None
    for samples handed in without times of this clock; ``solved`` the time the solve ended;
    ``step_ms`` the frame's cost; ``loop`` the behavior loop's report (None when not stepped: not
    calibrated, or a split frame, which solved the spine and arms only)."""

    frame: int
    fresh: list[int]
    skipped: int
    targets: dict[str, np.ndarray]
    errors: dict[str, float]
    spine: tuple[float, float, float] | None
    arrival: float | None
    solved: float
    step_ms: float
    loop: FrameReport | None
    notes: list[str] = field(default_factory=list)
    spine_target: tuple[float, float, float] | None = None

    @property
    def latency_ms(self) -> float | None:
        """Newest consumed sample's arrival to the end of the solve (ms), for live sources."""
        return None if self.arrival is None else (self.solved - self.arrival) * 1e3


@dataclass
class DriveStatus:
    """What a Devices panel shows: ``state`` (the driver's, or "samples"), ``calibrated``,
    ``birds`` (bird -> part), ``rates`` (Hz per bird, from sequence numbers over the last second),
    ``dropped`` (broken records the driver dropped), ``skipped`` (samples overwritten before a frame
    used them), ``frames`` (steps so far), ``last_error``."""

    state: str
    calibrated: bool
    birds: dict[int, str]
    rates: dict[int, float]
    dropped: int
    skipped: int
    frames: int
    last_error: str | None


SampleSource = Callable[[], Mapping[int, Sample]]


def _source(obj: Any) -> SampleSource | None:
    if obj is None:
        return None
    if hasattr(obj, "snapshot"):  # FlockDriver, LatestSamples
        return obj.snapshot
    if isinstance(obj, Mapping):
        return lambda: obj
    if callable(obj):
        return obj
    raise DeviceError(f"cannot read samples from a {type(obj).__name__}")


class SensorDrive:
    """Drives ``loop``'s figure from sensor samples.

    ``source``: a :class:`~jackpy.devices.flock.driver.FlockDriver` or
    :class:`~jackpy.devices.flock.driver.LatestSamples` (read with ``snapshot()``, never blocking),
    a mapping bird -> sample, a callable returning one, or None (pass samples to :meth:`step`).
    ``config``: a :class:`DriveConfig`, or a :class:`~jackpy.devices.sensors.SensorConfig` (other
    settings default).
    """

    def __init__(self, loop: BehaviorLoop, source: Any = None,
                 config: DriveConfig | SensorConfig | None = None) -> None:
        if isinstance(config, SensorConfig):
            config = DriveConfig(sensors=config)
        self.loop = loop
        self.config = config or DriveConfig()
        self.driver = source if hasattr(source, "stats") else None
        self._read = _source(source)
        self.calibration: Calibration | None = None
        self.smoother = (TargetSmoother(self.config.min_cutoff, self.config.beta, self.config.beta_rot)
                         if self.config.smoothing else None)
        a = loop.anatomy
        self.sites: dict[str, tuple[str, str]] = {"pelvis": (a.pelvis, a.pelvis_site), "neck": tuple(a.chest)}
        for part, side in HANDS.items():
            if side in a.hands:
                self.sites[part] = tuple(a.hands[side].palm)
        self.frames = 0
        self.skipped = 0
        self.last_error: str | None = None
        self._last_seq: dict[int, int] = {}
        self._seen: dict[int, collections.deque[tuple[float, int]]] = {}
        self._neutral: dict[str, np.ndarray] = {}
        self._spine = np.zeros(3)
        self._spine_applied = np.zeros(3)
        self._spine_offset = np.zeros(3)  # last frame's command minus target: the warm start
        self.budget = (FrameBudget(loop, self.config.frame_budget_ms)
                       if self.config.frame_budget_ms is not None else None)
        for knob in ("idle_every", "body_every"):
            if getattr(self.config, knob) < 1:
                raise DeviceError(f"{knob} must be >= 1, not {getattr(self.config, knob)}")
        self._targets: dict[str, np.ndarray] = {}
        self._owed = 0  # split frames since the loop last stepped (its behaviors and body pass)
        self.split_frames = 0  # frames that solved the spine and arms only
        self.idle_steps = 0  # loop steps run by idle()
        self._idle_overhead_s = 0.0  # learned: a loop step's cost besides its solves (s)
        self._idle_late_s = 0.0  # learned: how far an idle step runs past its loop deadline (s)

    # ----- calibration ----------------------------------------------------------------------------
    def reference_poses(self) -> dict[str, np.ndarray]:
        """World 4x4 of each configured part's site in the figure's current posture."""
        fig = self.loop.figure
        return {mt.part: fig.site_world(*self.sites[mt.part]) for mt in self.config.sensors.mounts
                if mt.part in self.sites}

    def calibrate(self, samples: Mapping[int, Sample] | None = None) -> Calibration:
        """Capture the transmitter placement and sensor offsets with the operator standing in the
        figure's current posture (normally its neutral stance). ``samples`` default to the
        source's latest; raises :class:`DeviceError` when a configured bird has no valid pose."""
        samples = self._samples(samples)
        missing = [mt.bird for mt in self.config.sensors.mounts if mt.bird not in samples]
        if missing:
            raise DeviceError(f"calibration: no sample yet from bird(s) {missing}")
        ref = self.reference_poses()
        self.calibration = calibrate(samples, ref, self.config.sensors,
                                     place_transmitter=self.config.place_transmitter)
        self._neutral = {p: r.copy() for p, r in ref.items()}
        self._spine = np.zeros(3)
        self._spine_applied = np.zeros(3)
        self._spine_offset = np.zeros(3)
        self._targets = {}
        self._owed = 0
        for b, s in samples.items():
            self._last_seq[b] = s.seq
        if self.smoother is not None:
            self.smoother = TargetSmoother(self.config.min_cutoff, self.config.beta, self.config.beta_rot)
        return self.calibration

    @property
    def calibrated(self) -> bool:
        return self.calibration is not None

    @property
    def consumed(self) -> dict[int, int]:
        """Sequence number of the last sample of each bird a frame (or the calibration) used."""
        return dict(self._last_seq)

    # ----- one frame --------------------------------------------------------------------------------
    def _samples(self, samples: Mapping[int, Sample] | None) -> Mapping[int, Sample]:
        if samples is not None:
            return samples
        if self._read is None:
            raise DeviceError("no sample source: pass samples to step() or calibrate()")
        return self._read()

    def _account(self, samples: Mapping[int, Sample]) -> tuple[list[int], int]:
        fresh, skipped = [], 0
        for b, s in samples.items():
            last = self._last_seq.get(b)
            if last is None or s.seq != last:
                fresh.append(b)
                if last is not None and s.seq > last + 1:
                    skipped += s.seq - last - 1
                self._last_seq[b] = s.seq
                seen = self._seen.setdefault(b, collections.deque(maxlen=256))
                seen.append((s.time, s.seq))
        return sorted(fresh), skipped

    def step(self, samples: Mapping[int, Sample] | None = None, live: bool | None = None) -> DriveReport:
        """Set goals from the latest samples (or ``samples``) and run one frame of the loop.

        Never blocks on the device. Before :meth:`calibrate` nothing is driven and the loop is not
        stepped (the report says so). ``live`` tells whether sample times are this process's
        ``time.perf_counter`` (default: when read from the source)."""
        t0 = time.perf_counter()
        cpu0 = time.thread_time()
        live = (samples is None) if live is None else live
        try:
            samples = self._samples(samples)
        except DeviceError as exc:
            self.last_error = str(exc)
            raise
        fresh, skipped = self._account(samples)
        self.skipped += skipped
        if self.calibration is None:
            return DriveReport(self.frames, fresh, skipped, {}, {}, None, None, time.perf_counter(),
                               (time.perf_counter() - t0) * 1e3, None, ["not calibrated"])
        cfg = self.config
        targets = sensor_targets(samples, self.calibration)
        newest = max((samples[b].time for b in fresh), default=None)
        if self.smoother is not None and targets:
            ts = max(s.time for s in samples.values())
            targets = self.smoother(targets, ts)
        loop = self.loop
        split = cfg.split and self._can_split()
        if fresh:
            self._targets = targets
            if not split:
                self._drive_pelvis(targets)
            # 2. spine from the neck against the waist, measured from the calibration pose
            pel = targets.get("pelvis")
            if cfg.torso and pel is not None and "neck" in targets and "neck" in self._neutral:
                self._spine = self._bend(pel, targets["neck"])
            # 3. arms: palm sensors are the palm sites' position + orientation goals
            if cfg.hands:
                for part, side in HANDS.items():
                    if part in targets and side in loop.state.hands:
                        m.hand_on_site(loop, side, targets[part])
        # 4. COM, stepping and legs: the behaviors and the IK (split: the arms only)
        if split:
            self._solve_arms()
            report = None
            self._owed += 1
            self.split_frames += 1
        else:
            t_loop = time.perf_counter()
            report = loop.step()
            self._owed = 0
            if cfg.split:  # what a loop step costs besides its solves: can an idle step fit
                self._idle_overhead_s = _learn(self._idle_overhead_s, time.perf_counter() - t_loop - report.solve_s)
        self.frames += 1
        solved = time.perf_counter()
        if self.budget is not None:  # the work of this thread, not the time others took the CPU
            self.budget.update((time.thread_time() - cpu0) * 1e3)
        errors = {p: float(np.linalg.norm(self._site(p)[:3, 3] - t[:3, 3]))
                  for p, t in targets.items() if p in self.sites}
        return DriveReport(self.frames, fresh, skipped, targets, errors,
                           tuple(float(v) for v in self._spine_applied) if cfg.torso else None,
                           newest if live else None, solved, (solved - t0) * 1e3, report,
                           list(report.notes) if report is not None else ["split frame"],
                           tuple(float(v) for v in self._spine) if cfg.torso else None)

    def _drive_pelvis(self, targets: Mapping[str, np.ndarray]) -> None:
        """1. pelvis: orientation goal, floor position servoed through the balance point."""
        cfg, loop = self.config, self.loop
        pel = targets.get("pelvis")
        if not cfg.pelvis or pel is None:
            return
        # where the COM belongs for the pelvis to sit on its target (the body's current
        # COM-to-pelvis offset kept); the balance point moves towards it, at most
        # pelvis_max_shift a frame. It is no integral, so nothing winds up while the feet
        # hold the body back: the point reaches the edge of the feet and a step follows.
        com = floor(loop.posture()[1])
        err = cfg.pelvis_gain * floor(pel[:3, 3] - self._site("pelvis")[:3, 3])
        st = loop.state
        base = st.com_drag if st.com_drag is not None else st.balance_point
        want = com + err
        if float(np.linalg.norm(base - com)) > 0.01 and float(np.linalg.norm(err)) > 0.02 \
                and float(err @ (base - com)) > 0.0:
            # the feet hold the COM back from its goal: push the point on towards the
            # edge of the support polygon, where the stepping behavior takes a step
            want = base + err
        shift = want - base
        n = float(np.linalg.norm(shift))
        if n > cfg.pelvis_max_shift:
            shift *= cfg.pelvis_max_shift / n
        if self._stepping():  # a step in progress owns the balance point
            shift = np.zeros(2)
        m.move_pelvis(loop, rotation=pel[:3, :3], translation=np.array([shift[0], 0.0, shift[1]]))

    # ----- split frames -------------------------------------------------------------------------------
    def _can_split(self) -> bool:
        """Whether this frame may solve the arms only: the loop stepped within the last
        ``body_every`` frames, no step is under way (its feet move every frame), the limbs are
        solved together and no user goal joins them (the limbs problem is then the loop's own)."""
        loop = self.loop
        return self._owed < self.config.body_every - 1 and loop.combine_limbs and not loop.user_goals and not self._stepping()

    def _solve_arms(self) -> None:
        """The loop's head-and-arms pass on this frame's goals, body frozen: the goals of the
        behaviors that feed only that pass, in the loop's order (so its cached, compiled problem is
        reused), within the arm pass's iteration cap and the loop's ``max_iterations`` (counted
        work, no time box: a late frame must still move the hands)."""
        loop = self.loop
        frame = Frame(loop)
        for b in sorted((b for b in loop.behaviors if b.enabled and b.name in ARM_BEHAVIORS),
                        key=lambda b: b.order):
            b.update(frame)
        goals = frame.head + [g for side in SIDES for g in frame.arms[side]]
        if not goals:
            return
        ps, head = loop.passes["arm"], loop.passes["head"]
        solve(loop.problem_for(goals, "limbs"), max_iterations=min(ps.iterations, loop.max_iterations),
              tol_position=ps.tol_position, tol_angle=min(ps.tol_angle, head.tol_angle))

    def idle(self, until: float) -> FrameReport | None:
        """Use the time before ``until`` (``time.perf_counter`` s: when the next sample is due) for
        what split frames left out: the pelvis servo on the latest targets and a full loop step
        (every behavior and pass), time-boxed to end by ``until``. None (nothing run) unless
        ``idle_every`` split frames are owed it and the time left is at least what the last loop
        steps cost besides their solves (their behaviors) plus ``idle_min_ms`` for the solves. The
        loop's time box bounds only the solves, so the box it is given ends early by how far the
        last idle steps ran past theirs (both learned, quick to rise, slow to fall). Once
        ``body_every - 1`` split frames are owed it, the step runs whatever the time left, with
        that much time: the body's work then delays the next sample's frame a little, rather than
        the next frame being a full one."""
        cfg = self.config
        start = time.perf_counter()
        need = self._idle_overhead_s + cfg.idle_min_ms * 1e-3
        forced = self._owed >= cfg.body_every - 1
        if self._owed < cfg.idle_every and not forced:
            return None
        if not forced and until - start < need:
            return None
        self._drive_pelvis(self._targets)
        deadline = start + max(until - self._idle_late_s - start, need)
        report = self.loop.step(deadline=deadline)
        end = time.perf_counter()
        self._idle_overhead_s = _learn(self._idle_overhead_s, end - start - report.solve_s)
        self._idle_late_s = _learn(self._idle_late_s, end - deadline)
        self._owed = 0
        self.idle_steps += 1
        return report

    def _site(self, part: str) -> np.ndarray:
        """World 4x4 of ``part``'s site, from the loop's cached forward kinematics (one forward
        pass per posture, shared with the behaviors)."""
        seg, site = self.sites[part]
        fk, _ = self.loop.posture()
        fig = self.loop.figure
        return fk.segments[fig.kinematics().segment_index[seg]] @ fig.site_location(seg, site)

    def _stepping(self) -> bool:
        """Whether the loop's stepping behavior is in the middle of a step."""
        for b in self.loop.behaviors:
            if b.name == "stepping" and getattr(b, "step", None) is not None:
                return True
        return False

    def _relative(self, pelvis: np.ndarray, neck: np.ndarray) -> np.ndarray:
        """Spine angles (flexion, lateral, axial; jackpy's spine-group signs) of ``neck`` against
        ``pelvis``, measured from the calibration pose."""
        p0, n0 = self._neutral["pelvis"][:3, :3], self._neutral["neck"][:3, :3]
        a = np.eye(4)
        b = np.eye(4)
        a[:3, :3] = pelvis[:3, :3] @ p0.T
        b[:3, :3] = neck[:3, :3] @ n0.T
        flex, twist, lateral = spine_angles(a, b)
        # spine_angles' lateral is about +z (forward); the spine group bends right for +z' = -z
        return np.array([flex, -lateral, twist])

    def _bend(self, pelvis: np.ndarray, neck: np.ndarray) -> np.ndarray:
        """Send the spine target to the spine, then correct the command so the figure's neck turns
        by it; returns the target (the report's ``spine_target``; the angles set are its ``spine``).
        The command starts from the target plus last frame's correction (a warm start: the
        correction changes slowly)."""
        loop = self.loop
        want = self._relative(pelvis, neck)
        theta = want + self._spine_offset
        self._spine_applied = np.asarray(m.bend_torso(loop, *theta), dtype=float)
        for _ in range(self.config.spine_iterations):
            got = self._relative(self._site("pelvis"), self._site("neck"))
            err = want - got
            if float(np.max(np.abs(err))) < 1e-3:
                break
            theta = theta + err
            self._spine_applied = np.asarray(m.bend_torso(loop, *theta), dtype=float)
        self._spine_offset = theta - want
        return want

    # ----- status -----------------------------------------------------------------------------------
    def status(self) -> DriveStatus:
        """Birds, rates, dropped and skipped samples, frames and the last error (for a panel)."""
        rates = {}
        for b, seen in self._seen.items():
            if len(seen) >= 2:
                t_new, s_new = seen[-1]
                old = [(t, s) for t, s in seen if t_new - t <= 1.0] or [seen[0]]
                t_old, s_old = old[0] if old[0] != seen[-1] else seen[-2]
                if t_new > t_old:
                    rates[b] = (s_new - s_old) / (t_new - t_old)
        drv = self.driver
        return DriveStatus(
            state=getattr(drv, "state", "samples") if drv is not None else "samples",
            calibrated=self.calibrated,
            birds={mt.bird: mt.part for mt in self.config.sensors.mounts},
            rates=rates,
            dropped=int(drv.stats.dropped) if drv is not None else 0,
            skipped=self.skipped,
            frames=self.frames,
            last_error=(getattr(drv, "last_error", None) if drv is not None else None) or self.last_error,
        )


class FrameBudget:
    """Bounded work per frame for a live drive: adapts ``loop.max_iterations`` (the cap of every
    pass's solver iterations) to keep a frame's work within ``budget_ms`` of CPU time (the drive
    thread's: on an idle machine that is the frame's wall time; on a loaded one, time the CPU
    spent elsewhere is no reason to cut iterations). A frame over the budget cuts the cap in proportion, never below
    ``min_iterations`` (so the solves still converge over a few frames when the budget cannot be
    met: below that the cost is the behaviors', not the iterations'); a frame under 60 % of it
    gives one iteration back, up to the loop's own settings. The COM loop keeps its passes (with
    one pass the arms' pull on the COM is never settled, so no frame's goals would hold and every
    frame would solve). The solves warm-start from the last frame's posture, so work cut from one
    frame continues in the next."""

    def __init__(self, loop: BehaviorLoop, budget_ms: float, min_iterations: int = 3) -> None:
        if not budget_ms > 0:
            raise DeviceError(f"frame budget must be > 0 ms, not {budget_ms:g}")
        self.loop = loop
        self.budget_ms = float(budget_ms)
        self.min_iterations = max(1, min(int(min_iterations), loop.max_iterations))
        self.full_iterations = loop.max_iterations
        self.cap = self.full_iterations
        self.over = 0  # frames that ran over the budget

    def update(self, frame_ms: float) -> None:
        """Adjust the loop after a frame whose work took ``frame_ms`` (CPU ms)."""
        if frame_ms > self.budget_ms:
            self.over += 1
            self.cap = max(self.min_iterations, min(self.cap - 1, int(self.cap * self.budget_ms / frame_ms)))
        elif frame_ms < 0.6 * self.budget_ms:
            self.cap = min(self.full_iterations, self.cap + 1)
        self.loop.max_iterations = self.cap


def _learn(estimate: float, sample: float) -> float:
    """A cost estimate (s, >= 0): half way to a higher sample, a tenth of the way to a lower one."""
    w = 0.5 if sample > estimate else 0.1
    return max(0.0, estimate + w * (sample - estimate))


def replay_into(drive: SensorDrive, recording: Recording, speed: float = 0.0, every: int = 1,
                calibrate_frame: int | None = 0) -> Iterator[tuple[int, DriveReport]]:
    """Drive ``drive``'s figure from ``recording``: yields (frame index, report) per frame driven.

    ``calibrate_frame``: calibrate on that frame first (the operator's neutral stance), None to
    keep the drive's calibration. ``speed`` 0 drives every ``every``-th frame as fast as the solver
    goes (frame by frame); ``speed`` > 0 runs against the clock (× speed) and, like a live
    session, always takes the newest frame due, skipping those the solver had no time for.
    A recording without samples yields nothing.
    """
    if every < 1:
        raise DeviceError("every must be >= 1")
    frames = recording.frames()
    if not frames:  # a header and no samples: nothing to drive
        return
    # sequence numbers per bird follow the frame index, so skipped frames are counted
    seqd = [{b: Sample(b, s.record, s.time, k) for b, s in fr.items()} for k, fr in enumerate(frames)]
    merged: list[dict[int, Sample]] = []
    cur: dict[int, Sample] = {}
    for fr in seqd:  # a bird missing from a frame keeps its previous sample
        cur = {**cur, **fr}
        merged.append(cur)
    if calibrate_frame is not None:
        drive.calibrate(merged[min(calibrate_frame, len(merged) - 1)])
    if speed <= 0:
        for k in range(0, len(merged), every):
            yield k, drive.step(merged[k], live=False)
        if (len(merged) - 1) % every:
            yield len(merged) - 1, drive.step(merged[-1], live=False)
        return
    times = np.array([min(s.time for s in fr.values()) for fr in frames])
    start = time.perf_counter()
    last = -1
    while last < len(merged) - 1:
        due = int(np.searchsorted(times, (time.perf_counter() - start) * speed, side="right")) - 1
        if due <= last:
            wait = times[last + 1] / speed - (time.perf_counter() - start)
            time.sleep(max(0.0, min(wait, 0.05)))
            continue
        last = due
        yield due, drive.step(merged[due], live=False)


__all__ = ["DriveConfig", "DriveReport", "DriveStatus", "FrameBudget", "SensorDrive", "replay_into"]
