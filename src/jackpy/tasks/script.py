"""The Python front end ``Script`` and the simulation that runs it into a motion timeline.

```python
s = Script()
s.agent("John", "male", 50)
s.add(LookAt("John", "twf-1"), name="look1")
s.add(Turn("John", "twf-1", state="4"), on_failure=[...])
with s.together():
    s.add(LookAt("Jane", "twf-3")); s.add(LookAt("John", "tglJ-2"))
result = s.run(scene="examples/tasks/panel.json")
result.timeline; result.rows; result.reports
```

Running simulates the figures' behavior loops step by step (``fps``): each command starts when
its start condition holds, grounds its names then, and each of its steps takes its Fitts duration
from the posture the figure has reached by then (lazy evaluation, [SH6] §6.3.5). The motions
it adds form the timeline (``jackpy.motion``), which the workbench plays and edits.
"""

from __future__ import annotations

import contextlib
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterator

from jackpy.tasks import fitts
from jackpy.tasks import steps as st
from jackpy.tasks.kb import KnowledgeBase
from jackpy.tasks.schedule import After, At, Entry, Start, With
from jackpy.tasks.semantics import TaskError


@dataclass
class AgentSpec:
    """An agent: a standard human by sex and percentile, its pace factor and stand."""

    name: str
    sex: str
    percentile: float
    pace: float | None = None
    position: tuple[float, float] | None = None
    heading_deg: float | None = None

    @property
    def human(self) -> str:
        return f"{self.sex}:{self.percentile:g}"


@dataclass
class Report:
    """What happened to one entry: times (s), status ``done``/``failed``/``skipped`` and the reason."""

    name: str
    actor: str
    command: str
    start: float
    end: float
    status: str
    reason: str = ""
    origin: str = ""
    checks: dict[str, float] = field(default_factory=dict)


@dataclass
class Result:
    timeline: Any
    rows: list[fitts.Timing]
    reports: list[Report]
    controls: dict[str, str]
    placements: list[dict[str, Any]]
    env: Any
    loops: dict[str, Any]
    kb: KnowledgeBase

    @property
    def failures(self) -> list[Report]:
        return [r for r in self.reports if r.status != "done"]

    def report(self, name: str) -> Report:
        return next(r for r in self.reports if r.name == name)


class Script:
    """A task script: agents and command entries (sequential by default)."""

    def __init__(self, config: fitts.FittsConfig = fitts.FittsConfig(), fps: float = 15.0) -> None:
        self.agents: dict[str, AgentSpec] = {}
        self.entries: list[Entry | list[Entry]] = []
        self.config = config
        self.fps = fps
        self._block: list[Entry] | None = None
        self._count = 0

    def agent(self, name: str, sex: str, percentile: float, pace: float | None = None,
              position: tuple[float, float] | None = None, heading_deg: float | None = None) -> AgentSpec:
        """Declare an agent (``pace`` defaults to the book's: 3 for a man, 1.5 for a woman)."""
        if sex not in ("male", "female"):
            raise TaskError(f"agent {name!r}: sex must be male or female, not {sex!r}")
        if not 0 < percentile < 100:
            raise TaskError(f"agent {name!r}: percentile must be in (0, 100)")
        a = AgentSpec(name, sex, float(percentile), pace, position, heading_deg)
        self.agents[name] = a
        return a

    def entry(self, action: Any, name: str | None = None, start: Start | None = None,
              duration: float | None = None, on_success: list[Entry] | None = None,
              on_failure: list[Entry] | None = None, origin: str = "") -> Entry:
        """An entry that is not (yet) in the script: for hooks."""
        self._count += 1
        e = Entry(action, name or f"{self._count}", start, duration, list(on_success or []),
                  list(on_failure or []), origin)
        for h in e.on_success + e.on_failure:
            h.hook = True
        return e

    def add(self, action: Any, name: str | None = None, start: Start | None = None, duration: float | None = None,
            on_success: list[Any] | None = None, on_failure: list[Any] | None = None, origin: str = "") -> Entry:
        """Append a command; hooks may be commands or entries."""
        wrap = lambda hs: [h if isinstance(h, Entry) else self.entry(h) for h in (hs or [])]  # noqa: E731
        e = self.entry(action, name, start, duration, wrap(on_success), wrap(on_failure), origin)
        if self._block is not None:
            self._block.append(e)
        else:
            self.entries.append(e)
        return e

    @contextlib.contextmanager
    def together(self) -> Iterator[None]:
        """Entries added inside start together (after what precedes the block)."""
        if self._block is not None:
            raise TaskError("together() blocks do not nest")
        self._block = []
        try:
            yield
        finally:
            block, self._block = self._block, None
            if block:
                self.entries.append(block)

    def run(self, scene: str | os.PathLike | None = None, env: Any = None, max_time: float = 120.0) -> Result:
        """Simulate the script on ``scene`` (a scene file with its semantics sidecars)."""
        return Simulation(self, scene, env).run(max_time)


class Simulation:
    """One run of a script: figures, loops, the knowledge base, the timeline being built."""

    def __init__(self, script: Script, scene: str | os.PathLike | None, env: Any = None) -> None:
        from jackpy.motion import cast
        from jackpy.motion.timeline import Timeline

        self.script, self.config = script, script.config
        if env is None:
            if scene is not None:
                from jackpy.scene.workplace import load_workplace

                env = load_workplace(scene).env
            else:
                from jackpy.peabody.model import Environment

                env = Environment()
        self.env = env
        self.kb = KnowledgeBase.for_scene(env, Path(scene).parent) if scene is not None else KnowledgeBase(env)
        castd = {}
        for a in script.agents.values():
            stand = self.kb.stands.get(a.name, self.kb.stands.get("default", {}))
            pos = a.position if a.position is not None else stand.get("position", [0.0, 0.0])
            hd = a.heading_deg if a.heading_deg is not None else stand.get("heading_deg", 0.0)
            castd[a.name] = {"human": a.human, "position": [float(pos[0]), float(pos[1])], "heading_deg": float(hd)}
            self.kb.add_agent(a.name)
        self.timeline = Timeline(cast=castd)
        _, self.loops = cast.build(self.timeline, env=env)
        self.rows: list[fitts.Timing] = []
        self.reports: list[Report] = []
        self.holds: dict[tuple[str, str], Any] = {}
        self.placements: list[dict[str, Any]] = []
        self.dt = 1.0 / script.fps
        self._parent: dict[str, str] = {}
        self._waiting: dict[str, tuple[set[str], float, str]] = {}

    def pace(self, agent: str) -> float:
        a = self.script.agents[agent]
        return a.pace if a.pace is not None else fitts.BOOK_PACE[a.sex]

    def timed(self, agent: str, label: str, limb: str, amplitude: float, t: float) -> float:
        """Fitts duration (s) of a step starting at ``t``, recorded in the timing table."""
        row = fitts.timing(agent, label, limb, amplitude, self.pace(agent), self.config)
        row.start_s = t
        self.rows.append(row)
        return row.seconds

    # ----- the run ---------------------------------------------------------------------------------
    def run(self, max_time: float) -> Result:
        pending: list[tuple[Entry, Start | None]] = []
        blocks: dict[str, list[str]] = {}  # a together() block's end marker -> its entries
        prev: str | None = None
        for item in self.script.entries:
            block = item if isinstance(item, list) else [item]
            for e in block:
                pending.append((e, e.start if e.start is not None else (After(prev) if prev else At(0.0))))
            prev = f"__block_end_{id(item)}" if isinstance(item, list) else block[0].name
            if isinstance(item, list):
                blocks[prev] = [e.name for e in block]
        started: dict[str, float] = {}
        ended: dict[str, tuple[float, str]] = {}
        active: list[dict[str, Any]] = []  # running entries: entry, steps left, current step, its end
        t, step = 0.0, 0
        while True:
            t = step * self.dt
            # start due entries
            for e, cond in list(pending):
                due, why = self._due(cond, t, started, ended, blocks)
                if due is None:
                    continue
                pending.remove((e, cond))
                started[e.name] = due
                if why:
                    self._waiting[e.name] = (set(), due, "skipped")
                    self._settle(e.name, ended)
                    self.reports.append(Report(e.name, e.action.agent, e.action.text, due, due, "skipped", why, e.origin))
                    continue
                run = {"entry": e, "start": due, "steps": None, "step": None, "end": due, "checks": {}}
                active.append(run)
            # advance running entries whose current step ended
            for run in list(active):
                self._advance(run, t, active, ended, pending)
            if not pending and not active:
                break
            if t > max_time:
                for e, _ in pending:
                    self.reports.append(Report(e.name, e.action.agent, e.action.text, t, t, "skipped",
                                               "the script ran past its time limit", e.origin))
                break
            self.timeline.apply(t, self.loops, self.env)
            for name in sorted(self.loops):
                self.loops[name].step()
            step += 1
        end = max([r.end for r in self.reports] + [0.0])
        for _, tb in self.holds.values():
            tb.t1 = max(end, tb.t0 + self.dt)
        self.timeline.duration = max(end, self.timeline.duration if self.timeline.items() else 0.0)
        controls = {f"{o}.{c.name}": c.state for o, s in self.kb.semantics.items() for c in s.controls.values()}
        self.reports.sort(key=lambda r: (r.start, r.name))
        return Result(self.timeline, self.rows, self.reports, controls, self.placements, self.env, self.loops, self.kb)

    def _due(self, cond, t, started, ended, blocks) -> tuple[float | None, str]:
        """(start time, skip reason) when ``cond`` holds at ``t``; (None, '') while it does not."""
        if isinstance(cond, At):
            return (cond.t, "") if t + 1e-9 >= cond.t else (None, "")
        if isinstance(cond, With):
            return (started[cond.name], "") if cond.name in started else (None, "")
        names = blocks.get(cond.name, [cond.name])
        if not all(n in ended for n in names):
            if not any(n in started or n in ended for n in names) and cond.name not in blocks and \
                    cond.name not in {e.name for e in self._all_entries()}:
                return t, f"no entry named {cond.name!r}"
            return None, ""
        when = max(ended[n][0] for n in names) + cond.delay
        if t + 1e-9 < when:
            return None, ""
        return when, ""

    def _all_entries(self) -> list[Entry]:
        out = []

        def walk(e):
            out.append(e)
            for h in e.on_success + e.on_failure:
                walk(h)

        for item in self.script.entries:
            for e in (item if isinstance(item, list) else [item]):
                walk(e)
        return out

    def _advance(self, run: dict, t: float, active: list, ended: dict, pending: list) -> None:
        e: Entry = run["entry"]
        while run["end"] <= t + 1e-9:
            try:
                cur = run["step"]
                if cur is not None:
                    extra = cur.finish(self, t)
                    run["checks"].update({f"{cur.label}: {k}": v for k, v in cur.run.items() if isinstance(v, float)})
                    run["steps"][:0] = extra
                if run["steps"] is None:
                    run["steps"] = e.action.expand(self)
                    n = sum(isinstance(s, (st.Look, st.Reach, st.Carry)) for s in run["steps"])
                    run["n_timed"] = max(n, 1)
                if not run["steps"]:
                    self._close(run, t, "done", "", active, ended, pending)
                    return
                nxt = run["steps"].pop(0)
                run["step"] = nxt
                begin = max(run["end"], run["start"])
                dur = nxt.begin(self, begin)
                if e.duration is not None and isinstance(nxt, (st.Look, st.Reach, st.Carry)):
                    dur = self._explicit(e.duration / run["n_timed"])
                run["end"] = begin + max(dur, 1e-6)
            except TaskError as err:
                self._close(run, t, "failed", str(err), active, ended, pending)
                return

    def _explicit(self, dur: float) -> float:
        """Replace the Fitts duration of the motion just added by an explicit one."""
        m = self.timeline.motions[-1]
        m.t1 = m.t0 + dur
        return dur

    def _close(self, run, t, status, reason, active, ended, pending) -> None:
        """End an entry; it counts as ended for ``After`` only once the hooks it triggered end."""
        e: Entry = run["entry"]
        end = min(run["end"], t) if status == "failed" else run["end"]
        active.remove(run)
        self.reports.append(Report(e.name, e.action.agent, e.action.text, run["start"], end, status, reason,
                                   e.origin, run["checks"]))
        hooks = e.on_success if status == "done" else e.on_failure
        for h in (e.on_failure if status == "done" else e.on_success):
            ended[h.name] = (end, "skipped")
        for h in hooks:
            pending.append((h, At(end)))
            self._parent[h.name] = e.name
        self._waiting[e.name] = ({h.name for h in hooks}, end, status)
        self._settle(e.name, ended)

    def _settle(self, name: str, ended: dict) -> None:
        waiting, end, status = self._waiting[name]
        if waiting:
            return
        ended[name] = (end, status)
        parent = self._parent.pop(name, None)
        if parent is not None:
            w, pend, pstatus = self._waiting[parent]
            w.discard(name)
            self._waiting[parent] = (w, max(pend, end), pstatus)
            self._settle(parent, ended)
