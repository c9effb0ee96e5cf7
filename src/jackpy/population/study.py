"""The study a sweep runs on every body (``STUDY.json``): its criteria and what each one needs.

::

    {"jackpy_study": 1,
     "hand": "right",                                     # default reaching hand
     "reach": ["desk.button", {"target": "shelf.box_handle", "hand": "left", "tolerance_m": 0.01}],
     "view": ["gauge", {"target": "panel.switch", "min_visible": 0.5, "cone": "binocular"}],
     "clearance": [{"object": "shelf", "min_m": 0.05, "posture": "shelf.box_handle"}],
     "strength": {"load_kg": 5, "posture": "desk.button", "max_utilisation": 1.0},
     "ergonomics": [{"method": "rula", "posture": "desk.button", "max_score": 4}]}

Reach: the hand's grip point within ``tolerance_m`` (default 5 mm) of the target after the arm's IK
(:func:`jackpy.analysis.reach.point_reach`, arm mode) from the neutral standing posture at the
scene's stand. View: visible fraction from the eyes (:mod:`jackpy.population.sightline`) at least
``min_visible`` (default 0.5; a site is seen or not), and, with ``cone``, the target inside that view
cone of :data:`jackpy.analysis.view.VIEW_CONES`. Clearance: the figure's surfaces at least ``min_m``
(default 0) from the object, neutral or in a reach target's posture. Strength: joint-torque
utilisation (:mod:`jackpy.analysis.strength`) at most ``max_utilisation`` (default 1.0) holding
``load_kg`` in the reaching hand, in a reach target's posture (default: the first). Ergonomics: a
method of :mod:`jackpy.ergonomics` (when installed) with its score at most ``max_score``.
Targets are ``object.site`` or ``object`` names of the scene.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from jackpy import jsonfile
from jackpy.analysis.view import VIEW_CONES
from jackpy.errors import JackpyError, ParseError

FORMAT_VERSION = 1
HANDS = ("right", "left")


class StudyError(ParseError):
    """A study file that cannot be read or does not fit the scene."""


@dataclass(frozen=True)
class Criterion:
    """One pass/fail test of the study: ``kind`` (reach, view, clearance, strength, ergonomics), its
    ``target`` (scene name, or the method for ergonomics) and ``params``. ``id`` names its columns."""

    kind: str
    target: str
    params: dict[str, Any] = field(default_factory=dict)

    @property
    def id(self) -> str:
        return f"{self.kind}:{self.target}"


@dataclass(frozen=True)
class Study:
    """The criteria in file order and the default hand."""

    criteria: tuple[Criterion, ...]
    hand: str = "right"
    source: str = ""

    @property
    def needs_surfaces(self) -> bool:
        """Clearance, strength (masses) and ergonomics need the full figure; reach and view the skeleton."""
        return any(c.kind in ("clearance", "strength", "ergonomics") for c in self.criteria)

    def of_kind(self, kind: str) -> list[Criterion]:
        return [c for c in self.criteria if c.kind == kind]

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"jackpy_study": FORMAT_VERSION, "hand": self.hand}
        for kind in ("reach", "view", "clearance", "ergonomics"):
            items = [{_TARGET_KEY[kind]: c.target, **c.params} for c in self.of_kind(kind)]
            if items:
                out[kind] = items
        strength = self.of_kind("strength")
        if strength:
            out["strength"] = dict(strength[0].params)
        return out


_TARGET_KEY = {"reach": "target", "view": "target", "clearance": "object", "ergonomics": "method"}


def load_study(path: str | os.PathLike) -> Study:
    """Read ``STUDY.json``; :class:`StudyError` with file:line:column or the key path at fault."""
    p = Path(path)
    try:
        data = jsonfile.load(p, StudyError)
    except FileNotFoundError:
        raise StudyError(f"{p}: no such study file") from None
    except OSError as exc:
        raise StudyError(f"{p}: cannot read the study: {exc.strerror or exc}") from None
    try:
        return parse_study(data, str(p))
    except jsonfile.Invalid as exc:
        raise jsonfile.schema_error(StudyError, str(p), exc) from None


def parse_study(data: Any, source: str = "<study>") -> Study:
    """A :class:`Study` from parsed JSON (raises :class:`jackpy.jsonfile.Invalid` with the key path)."""
    d = jsonfile.obj(data, "")
    if d.get("jackpy_study") != FORMAT_VERSION:
        raise jsonfile.Invalid("jackpy_study", f"expected {FORMAT_VERSION} (not a jackpy study file?)")
    known = {"jackpy_study", "hand", "reach", "view", "clearance", "strength", "ergonomics"}
    for k in d:
        if k not in known:
            raise jsonfile.Invalid(k, f"unknown key (known: {', '.join(sorted(known))})")
    hand = jsonfile.string(d.get("hand", "right"), "hand", HANDS)
    criteria: list[Criterion] = []
    for kind, parse in (("reach", _reach), ("view", _view), ("clearance", _clearance), ("ergonomics", _ergonomics)):
        for k, item in enumerate(jsonfile.arr(d.get(kind, []), kind)):
            criteria.append(parse(item, f"{kind}[{k}]", hand))
    if "strength" in d:
        criteria.append(_strength(d["strength"], "strength", hand))
    ids = [c.id for c in criteria]
    dup = next((i for i in ids if ids.count(i) > 1), None)
    if dup:
        raise jsonfile.Invalid("", f"criterion {dup!r} is given twice")
    if not criteria:
        raise jsonfile.Invalid("", "the study has no criteria (reach, view, clearance, strength, ergonomics)")
    return Study(tuple(criteria), hand, source)


def _item(item: Any, where: str, key: str, allowed: set[str]) -> tuple[str, dict[str, Any]]:
    if isinstance(item, str):
        return item, {}
    d = jsonfile.obj(item, where)
    for k in d:
        if k not in allowed | {key}:
            raise jsonfile.Invalid(jsonfile.key(where, k), f"unknown key (known: {', '.join(sorted(allowed | {key}))})")
    return jsonfile.string(jsonfile.required(d, key, where), jsonfile.key(where, key)), d


def _reach(item: Any, where: str, hand: str) -> Criterion:
    target, d = _item(item, where, "target", {"hand", "tolerance_m"})
    return Criterion("reach", target, {
        "hand": jsonfile.string(d.get("hand", hand), jsonfile.key(where, "hand"), HANDS),
        "tolerance_m": jsonfile.num(d.get("tolerance_m", 0.005), jsonfile.key(where, "tolerance_m"), 1e-4, 1.0)})


def _view(item: Any, where: str, hand: str) -> Criterion:
    target, d = _item(item, where, "target", {"min_visible", "cone"})
    params: dict[str, Any] = {"min_visible": jsonfile.num(d.get("min_visible", 0.5), jsonfile.key(where, "min_visible"),
                                                          0.0, 1.0)}
    if d.get("cone") is not None:
        params["cone"] = jsonfile.string(d["cone"], jsonfile.key(where, "cone"), [n for n, _ in VIEW_CONES])
    return Criterion("view", target, params)


def _posture(d: dict[str, Any], where: str) -> str | None:
    v = d.get("posture")
    return None if v is None else jsonfile.string(v, jsonfile.key(where, "posture"))


def _clearance(item: Any, where: str, hand: str) -> Criterion:
    target, d = _item(item, where, "object", {"min_m", "posture"})
    return Criterion("clearance", target, {"min_m": jsonfile.num(d.get("min_m", 0.0), jsonfile.key(where, "min_m"), 0.0),
                                           "posture": _posture(d, where)})


def _strength(item: Any, where: str, hand: str) -> Criterion:
    d = jsonfile.obj(item, where)
    allowed = {"load_kg", "posture", "max_utilisation", "hand"}
    for k in d:
        if k not in allowed:
            raise jsonfile.Invalid(jsonfile.key(where, k), f"unknown key (known: {', '.join(sorted(allowed))})")
    return Criterion("strength", "joints", {
        "load_kg": jsonfile.num(d.get("load_kg", 0.0), jsonfile.key(where, "load_kg"), 0.0, 500.0),
        "posture": _posture(d, where),
        "hand": jsonfile.string(d.get("hand", hand), jsonfile.key(where, "hand"), HANDS),
        "max_utilisation": jsonfile.num(d.get("max_utilisation", 1.0), jsonfile.key(where, "max_utilisation"), 0.0)})


def _ergonomics(item: Any, where: str, hand: str) -> Criterion:
    method, d = _item(item, where, "method", {"posture", "max_score", "options"})
    return Criterion("ergonomics", method, {
        "posture": _posture(d, where),
        "max_score": jsonfile.num(d.get("max_score", 1e9), jsonfile.key(where, "max_score")),
        "options": jsonfile.obj(d.get("options", {}), jsonfile.key(where, "options"))})


def check_against_scene(study: Study, env) -> None:
    """Every target, object and posture the study names exists in the scene (:class:`StudyError`)."""
    from jackpy.scene.workplace import resolve_target

    reach_ids = {c.target for c in study.of_kind("reach")}
    for c in study.criteria:
        try:
            if c.kind in ("reach", "view", "clearance"):
                resolve_target(env, c.target)
        except JackpyError as exc:
            raise StudyError(f"{study.source}: {c.id}: {exc}") from None
        if c.kind == "ergonomics":
            _check_ergonomics(study, c)
        posture = c.params.get("posture")
        if posture is not None and posture not in reach_ids:
            raise StudyError(f"{study.source}: {c.id}: posture {posture!r} is not one of the study's reach targets "
                             f"({', '.join(sorted(reach_ids)) or 'none'})")


def _check_ergonomics(study: Study, c: Criterion) -> None:
    try:
        from jackpy.ergonomics import Task, method
    except ImportError as exc:
        raise StudyError(f"{study.source}: {c.id}: jackpy.ergonomics is not available ({exc})") from None
    try:
        method(c.target)
        Task.from_dict(c.params.get("options", {}), f"{c.id}.options")
    except JackpyError as exc:
        raise StudyError(f"{study.source}: {c.id}: {exc}") from None
