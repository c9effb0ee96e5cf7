"""Run a study on one body: build its figure from its parameters, stand it in the scene and apply
every criterion; one row per body.

The row holds the body (``index``, ``sex``, ``label``, its controlled dimensions in SI units), then
per criterion ``<id>`` (1 pass, 0 fail) and ``<id>:<metric>`` (reach ``shortfall_m``, view
``visible``, clearance ``distance_m``, strength ``max_utilisation``, ergonomics ``score``), and
``all`` (1 when every criterion passes). The figure is skeleton-only unless a criterion needs
surfaces or masses (:attr:`Study.needs_surfaces`). Reach is the arm-mode IK of
:func:`jackpy.analysis.reach.point_reach` on the arm alone (:mod:`jackpy.population.arm_reach`),
started from the mean body's solution of that target (:meth:`SweepContext.prepare`). Everything is deterministic: the same body gives
the same row in any process.
"""

from __future__ import annotations

import pickle
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from jackpy.analysis.reach import Posture
from jackpy.analysis.view import VIEW_CONES, eye_view
from jackpy.peabody.model import Figure
from jackpy.population.arm_reach import apply_to_figure, arm_figure
from jackpy.population.arm_reach import reach as arm_reach
from jackpy.population.generate import CONTROLLED, Body, make_figure
from jackpy.population.sightline import Sightlines
from jackpy.population.study import Criterion, Study
from jackpy.scene.workplace import Workplace, resolve_target, stand_figure

METRIC = {"reach": "shortfall_m", "view": "visible", "clearance": "distance_m", "strength": "max_utilisation",
          "ergonomics": "score"}
BODY_COLUMNS = ("index", "sex", "label") + CONTROLLED


def columns(study: Study) -> list[str]:
    """The per-body table's columns, in order."""
    out = list(BODY_COLUMNS)
    for c in study.criteria:
        out += [c.id, f"{c.id}:{METRIC[c.kind]}"]
    return out + ["all"]


@dataclass
class SweepContext:
    """What every body of a sweep shares: the scene, the study, and (built on first use in each
    process) the scene's sightlines and target points."""

    workplace: Workplace
    study: Study
    #: (sex, criterion id) -> the mean body's arm posture reaching for it (:func:`prepare`)
    reach_starts: dict[tuple[str, str], tuple[np.ndarray, dict[str, np.ndarray]]] = field(default_factory=dict)
    _sightlines: Sightlines | None = field(default=None, repr=False)
    _targets: dict[str, tuple[str, np.ndarray]] = field(default_factory=dict, repr=False)

    def __getstate__(self) -> dict[str, Any]:
        return {"workplace": self.workplace, "study": self.study, "reach_starts": self.reach_starts}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__init__(state["workplace"], state["study"], state["reach_starts"])

    def prepare(self, sexes: tuple[str, ...] = ("female", "male")) -> SweepContext:
        """Solve every reach target for each sex's mean body (from the neutral posture); each body
        then starts its IK there (the same start in every process). Returns self."""
        from jackpy.population.generate import make_body

        for sex in sexes:
            fig = make_figure(make_body(0, sex, {}), surfaces=False)
            stand_figure(fig, self.workplace.stand)
            for c in self.study.of_kind("reach"):
                arm = arm_figure(fig, c.params["hand"])
                r = arm_reach(arm, self.target(c.target)[1], c.params["hand"], c.params["tolerance_m"])
                self.reach_starts[(sex, c.id)] = (r.q, r.group_angles)
        return self

    def to_bytes(self) -> bytes:
        return pickle.dumps(self, protocol=pickle.HIGHEST_PROTOCOL)

    @property
    def sightlines(self) -> Sightlines:
        if self._sightlines is None:
            self._sightlines = Sightlines(self.workplace.objects)
        return self._sightlines

    def target(self, ref: str) -> tuple[str, np.ndarray]:
        """(object name, world point) of ``object.site`` or ``object``."""
        if ref not in self._targets:
            obj, p = resolve_target(self.workplace.env, ref)
            self._targets[ref] = (obj.name, p)
        return self._targets[ref]


def evaluate_body(ctx: SweepContext, body: Body) -> dict[str, Any]:
    """The study's row for ``body`` (module docstring)."""
    study = ctx.study
    fig = make_figure(body, surfaces=study.needs_surfaces)
    stand_figure(fig, ctx.workplace.stand)
    row: dict[str, Any] = {"index": body.index, "sex": body.sex, "label": body.label}
    row.update({k: body.values[k] for k in CONTROLLED})
    neutral = Posture.of(fig)
    postures: dict[str, Posture] = {}
    passed_all = True
    for c in study.criteria:
        ok, value = _CRITERIA[c.kind](ctx, fig, c, postures, neutral)
        row[c.id] = int(ok)
        row[f"{c.id}:{METRIC[c.kind]}"] = float(value)
        passed_all &= ok
    row["all"] = int(passed_all)
    return row


def evaluate_chunk(payload: bytes | SweepContext | None, bodies: list[dict]) -> list[dict[str, Any]]:
    """Rows of a chunk of bodies (``Body.to_dict`` form). ``payload``: a context, its pickle
    (unpickled once per process and kept), or None for the one :func:`init_worker` installed."""
    ctx = _context(payload)
    return [evaluate_body(ctx, Body.from_dict(b)) for b in bodies]


_CACHE: dict[int | None, SweepContext] = {}


def init_worker(payload: bytes) -> None:
    """Process-pool initializer: install the sweep's context for :func:`evaluate_chunk` (None)."""
    _CACHE.clear()
    _CACHE[None] = pickle.loads(payload)


def _context(payload: bytes | SweepContext | None) -> SweepContext:
    if isinstance(payload, SweepContext):
        return payload
    key = None if payload is None else hash(payload)
    if key not in _CACHE:
        _CACHE.clear()
        _CACHE[key] = pickle.loads(payload)
    return _CACHE[key]


# ---- criteria ----------------------------------------------------------------------------------
def _reach(ctx: SweepContext, fig: Figure, c: Criterion, postures: dict, neutral: Posture) -> tuple[bool, float]:
    _, p = ctx.target(c.target)
    hand = c.params["hand"]
    arm = arm_figure(fig, hand)
    r = arm_reach(arm, p, hand, c.params["tolerance_m"], start=ctx.reach_starts.get((fig.body_spec.sex, c.id)))
    if ctx.study.needs_surfaces:  # a strength, clearance or ergonomics test may take this posture
        apply_to_figure(arm, fig)
        postures[c.target] = Posture.of(fig)
        neutral.apply(fig)
    return r.reached, r.shortfall


def _view(ctx: SweepContext, fig: Figure, c: Criterion, postures: dict, neutral: Posture) -> tuple[bool, float]:
    name, p = ctx.target(c.target)
    ev = eye_view(fig)
    if "." in c.target:
        visible = float(ctx.sightlines.site_visible(ev.position, p))
    else:
        visible = ctx.sightlines.object_fraction(ev.position, name)
    ok = visible >= c.params["min_visible"] and visible > 0.0
    cone = c.params.get("cone")
    if cone is not None:
        ok &= ev.angle_to(p) <= dict(VIEW_CONES)[cone]
    return bool(ok), visible


def _in_posture(fig: Figure, c: Criterion, postures: dict, neutral: Posture) -> None:
    name = c.params.get("posture")
    (postures[name] if name else neutral).apply(fig, root=neutral.root)


def _clearance(ctx: SweepContext, fig: Figure, c: Criterion, postures: dict, neutral: Posture) -> tuple[bool, float]:
    from jackpy.analysis.clearance import ClearanceChecker

    _in_posture(fig, c, postures, neutral)
    obj = ctx.workplace.objects[c.target.partition(".")[0]]
    distance = ClearanceChecker(fig, [obj], self_collision=False).clearance(obj.name).distance
    neutral.apply(fig)
    return distance >= c.params["min_m"], distance


def _strength(ctx: SweepContext, fig: Figure, c: Criterion, postures: dict, neutral: Posture) -> tuple[bool, float]:
    from jackpy.analysis.parts import figure_parts
    from jackpy.analysis.statics import Load, joint_torques
    from jackpy.analysis.strength import dof_strengths, utilisation
    from jackpy.body.strength import strength_table

    if c.params.get("posture") is None and postures:
        c = Criterion(c.kind, c.target, {**c.params, "posture": next(iter(postures))})
    _in_posture(fig, c, postures, neutral)
    hand = figure_parts(fig).hands[c.params["hand"]]
    kg = c.params["load_kg"]
    loads = [Load.held_mass(fig, hand.segment, hand.site, kg)] if kg > 0 else []
    util = utilisation(fig, joint_torques(fig, loads), dof_strengths(strength_table(fig)))
    worst = float(np.nanmax(util)) if np.any(~np.isnan(util)) else 0.0
    neutral.apply(fig)
    return worst <= c.params["max_utilisation"], worst


def _ergonomics(ctx: SweepContext, fig: Figure, c: Criterion, postures: dict, neutral: Posture) -> tuple[bool, float]:
    from jackpy.ergonomics import Task, assess

    _in_posture(fig, c, postures, neutral)
    task = Task.from_dict(c.params.get("options", {}), f"{c.id}.options")
    value = float(assess(fig, [c.target], task)[c.target].score)
    neutral.apply(fig)
    return value <= c.params["max_score"], value


_CRITERIA = {"reach": _reach, "view": _view, "clearance": _clearance, "strength": _strength,
             "ergonomics": _ergonomics}
