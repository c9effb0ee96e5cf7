"""Figures for any point of the population model, through the SASS body specification.

A body is given by target values of the **controlled dimensions** (:data:`CONTROLLED`; the model's
dimensions are a subset, the others are filled in by the regression of the ANSUR II normal model).
Each controlled dimension is set through SASS overrides of the 50th-percentile specification:

* stature and sitting height: the stature-path lengths, legs (ankle height, shank, thigh) and trunk
  (pelvis, spine, neck, head) each scaled in their 50th-percentile proportions;
* weight: body mass; span: upper arm and forearm lengths (in proportion);
* bideltoid breadth, hip breadth (sitting), foot length: ``bideltoid.breadth``, ``hip.breadth``,
  ``foot.length``.

How the overrides move the dimensions measured on the figure (:mod:`jackpy.body.measure`) is
**calibrated** per sex: the Jacobian of the measured dimensions with respect to the overrides and to
the regression-filled secondary dimensions (hand, chest, waist, buttock, foot and head sizes, limb
and neck girths, biacromial breadth), by finite differences of 1 SD at the mean body, and the mean body solved by
Newton steps so that its measurements equal the model's means; and the floor the shoulder tops put
under the measured bideltoid breadth (a narrow-deltoid body gets narrower acromia, as it must).
Overrides are then linear in the targets, so a figure measures what its body asks for to within the figure's small nonlinearity.
Bodies carry their overrides (:class:`Body`): workers build figures from them without calibrating.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from functools import cache

import numpy as np

from jackpy.body.anthropometry import load_population
from jackpy.body.human import build_spec, figure_from_spec, set_neutral_posture
from jackpy.body.sass import BodySpec, apply_overrides
from jackpy.body.skeleton import build_skeleton
from jackpy.peabody.model import Figure
from jackpy.population.model import PopulationModel

#: dimensions a body's figure is made to measure (model keys; measured by jackpy.body.measure)
CONTROLLED = ("stature", "sitting_height", "weight", "span", "bideltoid_breadth", "hip_breadth_sitting",
              "foot_length")
#: the measure of jackpy.body.measure for each controlled dimension
MEASURE_OF = {"stature": "stature", "sitting_height": "sitting_height", "weight": "weight", "span": "arm_span",
              "bideltoid_breadth": "bideltoid_breadth", "hip_breadth_sitting": "hip_breadth_sitting",
              "foot_length": "foot_length"}
#: secondary ANSUR II key dimension -> SASS dimension it sets (in standard scores: the population
#: tables' definitions differ from ANSUR's for some, so the SASS value is mean + z * sd of its own table).
#: The upper arm's girth is left at the 50th-percentile body's: with thin upper arms the figure's
#: shoulder-top surface, not the deltoid, would set the measured bideltoid breadth (a kink the
#: linear calibration cannot follow)
SECONDARY = {"hand_length": "hand.length", "hand_breadth": "hand.breadth", "biacromial_breadth": "shoulder.breadth",
             "chest_breadth": "chest.breadth", "chest_depth": "chest.depth", "waist_breadth": "waist.breadth",
             "waist_depth": "waist.depth", "buttock_depth": "buttock.depth", "foot_breadth": "foot.breadth",
             "head_breadth": "head.breadth", "head_length": "head.length", "neck_circumference": "neck.breadth",
             "forearm_circumference_flexed": "forearm.breadth",
             "wrist_circumference": "wrist.breadth", "thigh_circumference": "thigh.breadth",
             "calf_circumference": "calf.breadth", "bimalleolar_breadth": "ankle.breadth"}
LEGS = ("foot.height", "shank.length", "thigh.length")
TRUNK = ("pelvis.length", "spine.length", "neck.length", "head.height")
ARM = ("upper_arm.length", "forearm.length")
#: the override controls, in the order of CONTROLLED: leg + trunk length, trunk length, mass, arm
#: (SASS span, or upper arm + forearm), bideltoid breadth, hip breadth (sitting), foot length
CONTROLS = ("path", "trunk", "mass", "arm", "bideltoid", "hip", "foot")
POPULATION = "ansur2"
#: how far below a body's bideltoid breadth its shoulder tops' floor is kept (m)
FLOOR_MARGIN = 0.002


@dataclass(frozen=True)
class Body:
    """One body of a population or family: ``index`` in its sweep, ``sex``, the target ``values``
    of the controlled dimensions (SI), a ``label`` (``mc``, ``boundary 3``, ``centre``) and the SASS
    ``overrides`` (SI) its figure is built from."""

    index: int
    sex: str
    values: dict[str, float]
    label: str = "mc"
    overrides: dict[str, float] = field(default_factory=dict)

    def to_dict(self) -> dict:
        return {"index": self.index, "sex": self.sex, "label": self.label, "values": dict(self.values),
                "overrides": dict(self.overrides)}

    @classmethod
    def from_dict(cls, d: Mapping) -> Body:
        return cls(int(d["index"]), str(d["sex"]), {k: float(v) for k, v in d["values"].items()},
                   str(d.get("label", "mc")), {k: float(v) for k, v in d.get("overrides", {}).items()})


@cache
def _full_model() -> PopulationModel:
    return PopulationModel.ansur2(CONTROLLED + tuple(SECONDARY))


def complete(sex: str, values: Mapping[str, float]) -> dict[str, float]:
    """Every controlled and secondary dimension (SI) of a body given some of them (regression)."""
    known = {k: float(v) for k, v in values.items() if k in _full_model().dims}
    return _full_model().sex(sex).conditional_mean(known)


def _base_spec(sex: str) -> BodySpec:
    spec = build_spec(sex, 50.0, POPULATION)
    return replace(spec, footwear="barefoot") if hasattr(spec, "footwear") else spec


def _sass_sd(sex: str, name: str) -> float:
    v = load_population(POPULATION).dimension(sex, name).values  # p1 p5 p25 p50 p75 p95 p99
    return float(v[5] - v[1]) / (2 * 1.6448536)


def overrides_for(sex: str, full: Mapping[str, float], u: np.ndarray,
                  floor: tuple[float, float] | None = None) -> dict[str, float]:
    """SASS overrides (SI) for control vector ``u`` (:data:`CONTROLS`) and the secondary dimensions
    of ``full`` (a :func:`complete` result). ``floor = (c, k)``: the figure's bideltoid breadth is
    never less than ``c + k * shoulder.breadth`` (its shoulder tops), so the biacromial breadth is
    lowered where the bideltoid asked for is below that floor (less ``FLOOR_MARGIN``)."""
    base = _base_spec(sex)
    d = base.dims
    sm = _full_model().sex(sex)
    out: dict[str, float] = {}
    for key, name in SECONDARY.items():
        if name not in d:
            continue
        z = (full[key] - sm.mean[sm.index(key)]) / sm.sd[sm.index(key)]
        out[name] = d[name] + z * _sass_sd(sex, name)
    path, trunk, mass, arm = u[:4]
    groups = [(LEGS, path - trunk), (TRUNK, trunk)]
    if "span" in d:
        out["span"] = float(arm)
    else:
        groups.append((ARM, arm))
    for names, total in groups:
        base_total = sum(d[n] for n in names)
        out.update({n: d[n] * total / base_total for n in names})
    out["mass"] = float(mass)
    out["bideltoid.breadth"], out["foot.length"] = float(u[4]), float(u[6])
    # hip: the sitting breadth when the population has it, the standing breadth moved by as much
    hip = "hip.breadth_sitting" if "hip.breadth_sitting" in d else "hip.breadth"
    out["hip.breadth"] = d["hip.breadth"] + float(u[5]) - d[hip]
    out[hip] = float(u[5])
    if floor is not None and "shoulder.breadth" in out:
        c, k = floor
        out["shoulder.breadth"] = min(out["shoulder.breadth"], (float(u[4]) - FLOOR_MARGIN - c) / k)
    return {k: float(v) for k, v in out.items()}


def _arm_control(dims: Mapping[str, float]) -> tuple[float, float]:
    """Starting value of the arm control and its step per SD of span: SASS ``span`` when the
    population has it, else the upper-arm + forearm length (half the span's change)."""
    return (dims["span"], 1.0) if "span" in dims else (sum(dims[n] for n in ARM), 0.5)


def spec_from_overrides(sex: str, overrides: Mapping[str, float]) -> BodySpec:
    """The body specification of a body's overrides (50th-percentile spec, free rule, barefoot)."""
    return apply_overrides(_base_spec(sex), dict(overrides), "free")


def make_figure(body: Body, surfaces: bool = True, name: str | None = None) -> Figure:
    """The body's figure standing neutral; ``surfaces=False`` builds the skeleton only (segments,
    joints, sites, groups: enough for reach and the eye view; no surfaces and no mass)."""
    spec = spec_from_overrides(body.sex, body.overrides)
    name = name or f"{body.sex}_{body.index}"
    if surfaces:
        return figure_from_spec(spec, name)
    fig = build_skeleton(spec, name).figure
    fig.body_spec = spec  # type: ignore[attr-defined]
    set_neutral_posture(fig)
    return fig


def measure_controlled(fig: Figure) -> np.ndarray:
    """The controlled dimensions measured from a full figure (SI), in :data:`CONTROLLED` order."""
    from jackpy.body.measure import measure

    return np.array([measure(fig, MEASURE_OF[k]) for k in CONTROLLED])


@dataclass(frozen=True)
class Calibration:
    """Linear map from a body's controlled targets ``t`` to its controls: ``u = u0 + gain (t - t0)``;
    ``floor``: the bideltoid floor ``(c, k)`` of :func:`overrides_for`."""

    t0: np.ndarray
    u0: np.ndarray
    gain: np.ndarray
    floor: tuple[float, float]

    def controls(self, t: np.ndarray) -> np.ndarray:
        return self.u0 + self.gain @ (np.asarray(t, dtype=float) - self.t0)


def _measured(sex: str, full: Mapping[str, float], u: np.ndarray) -> np.ndarray:
    spec = spec_from_overrides(sex, overrides_for(sex, full, u))
    return measure_controlled(figure_from_spec(spec, "calibration"))


@cache
def calibration(sex: str) -> Calibration:
    """The per-sex calibration (module docstring); about 20 full figures, cached per process."""
    sm = _full_model().sex(sex)
    t0 = sm.mean[:len(CONTROLLED)].copy()
    sd = sm.sd[:len(CONTROLLED)]
    mean_body = complete(sex, {})
    base = _base_spec(sex)
    trunk0 = sum(base.dims[n] for n in TRUNK)
    arm0, arm_step = _arm_control(base.dims)
    hip0 = base.dims.get("hip.breadth_sitting", base.dims["hip.breadth"])
    u = np.array([t0[0], trunk0, t0[2], arm0, t0[4], hip0, t0[6]])
    # the controls move the measurements about one for one (trunk: sitting height)
    step = sd * np.array([1.0, 1.0, 1.0, arm_step, 1.0, 1.0, 1.0])
    m = _measured(sex, mean_body, u)
    jac_u = np.column_stack([(_measured(sex, mean_body, u + np.eye(len(u))[i] * step[i]) - m) / step[i]
                             for i in range(len(u))])
    for _ in range(3):
        u = u + np.linalg.solve(jac_u, t0 - m)
        m = _measured(sex, mean_body, u)
        if np.all(np.abs(t0 - m) < 1e-4 * sd):
            break
    jac_t = []
    for i, key in enumerate(CONTROLLED):
        full = complete(sex, {k: (t0[j] + (sd[j] if j == i else 0.0)) for j, k in enumerate(CONTROLLED)})
        jac_t.append((_measured(sex, full, u) - m) / sd[i])
    gain = np.linalg.solve(jac_u, np.eye(len(u)) - np.column_stack(jac_t))
    # the shoulder tops' floor under the bideltoid breadth: measured with a vanishing deltoid at two
    # biacromial breadths
    narrow = u.copy()
    narrow[4] = 0.5 * t0[4]
    floors = []
    for db in (0.0, 0.02):
        o = overrides_for(sex, mean_body, narrow)
        o["shoulder.breadth"] += db
        floors.append(measure_controlled(figure_from_spec(spec_from_overrides(sex, o), "calibration"))[4])
    k = (floors[1] - floors[0]) / 0.02
    c = floors[0] - k * overrides_for(sex, mean_body, narrow)["shoulder.breadth"]
    return Calibration(t0, u, gain, (float(c), float(k)))


def make_body(index: int, sex: str, values: Mapping[str, float], label: str = "mc") -> Body:
    """A :class:`Body` for target ``values`` (any of the controlled dimensions, SI; the rest are
    their regression on the given ones), with its calibrated overrides."""
    full = complete(sex, values)
    t = np.array([full[k] for k in CONTROLLED])
    cal = calibration(sex)
    u = cal.controls(t)
    targets = {k: full[k] for k in CONTROLLED}
    return Body(index, sex, targets, label, overrides_for(sex, full, u, cal.floor))
