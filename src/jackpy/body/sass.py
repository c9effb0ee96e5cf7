"""SASS scaling rules (book §2.7.3): the body specification and how editing one value moves the others.

A :class:`BodySpec` is the figure's anthropometry: sex, population, overall percentile, body mass and
every segment dimension in metres. **Stature is the sum of the stature-path lengths** (ankle height,
shank, thigh, pelvis, spine, neck, head), exactly as the generated figure stacks them.

Rules:

* **free**: changing a path length changes stature by the same amount; changing stature changes the
  path lengths linearly.
* **fixed**: changing a path length changes the other path lengths the opposite way so stature holds;
  no length leaves its 5th-95th percentile range (clamped, the rest shared by the others); when it
  cannot hold, :class:`ScalingError` is raised.
* **mass-stature** (``tie_mass=True``) **[proposal; the book gives no form]**: body mass follows
  stature at constant body-mass index, ``m' = m (S'/S)^2``, and setting mass sets stature the inverse way.

"Linearly" is made concrete **[proposal]**: a stature change is shared in proportion to each path
length's population spread (``(p95 - p5)``), which is the regression of each length on stature when
all lengths correlate equally with it. Widths and depths never follow stature (book: no rule exists).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from jackpy.body.anthropometry import (
    AnthropometryError,
    Population,
    check_percentile,
    check_sex,
    load_population,
)
from jackpy.peabody.geometry import Mesh, Psurf
from jackpy.peabody.model import Figure

#: the stature path from the floor up (book: foot, lower leg, upper leg, lower/centre/upper torso, neck, head)
STATURE_PATH = ("foot.height", "shank.length", "thigh.length", "pelvis.length", "spine.length",
                "neck.length", "head.height")
#: globals of a population table that are not segment dimensions
GLOBALS = ("stature", "mass", "eye_height")
RULES = ("free", "fixed")


class ScalingError(AnthropometryError):
    """A scaling rule cannot be satisfied (e.g. the fixed-stature rule cannot hold stature)."""


@dataclass
class BodySpec:
    """Anthropometry of one figure (SI units). ``dims`` maps dimension name -> metres.

    ``eye_drop`` is the vertical distance from the top of the head down to the eyes (m).
    """

    sex: str
    percentile: float
    population: str
    mass: float
    dims: dict[str, float]
    eye_drop: float
    overrides: dict[str, float] = field(default_factory=dict)
    #: ``"shoe"`` (a labelled outline allowance around the barefoot foot: heel +8 mm, toe +10 mm, sides
    #: +5 mm; heights stay barefoot as in ANSUR II) or ``"barefoot"`` (foot surfaces of the ANSUR foot length)
    footwear: str = "shoe"

    @property
    def stature(self) -> float:
        """Floor to top of head, standing (m): the sum of the stature-path lengths."""
        return float(sum(self.dims[k] for k in STATURE_PATH))

    @property
    def eye_height(self) -> float:
        """Floor to the eyes, standing (m)."""
        return self.stature - self.eye_drop

    def table(self) -> Population:
        return load_population(self.population)

    def dim_percentile(self, name: str) -> float:
        """Percentile of a dimension (or ``stature``/``mass``) in this spec's population."""
        value = {"stature": self.stature, "mass": self.mass, "eye_height": self.eye_height}.get(name)
        return self.table().percentile(self.sex, name, self.dims[name] if value is None else value)

    def copy(self) -> BodySpec:
        return replace(self, dims=dict(self.dims), overrides=dict(self.overrides))


def spec_for(sex: str, percentile: float, population: str = "ansur2") -> BodySpec:
    """The population's body at an overall ``percentile``.

    Stature and body mass are the population's values at ``percentile`` (normal quantile; lognormal
    for mass). Every other dimension is its **regression on stature and weight** (the population
    file's least-squares coefficients), so a 5th-percentile figure has the arms, breadths and head
    that 5th-percentile-stature, 5th-percentile-weight people have on average, not each dimension's
    own 5th percentile. The stature-path regressions sum to stature; any rounding residue is shared
    by the path lengths so that stature is exact. Populations without regressions take each
    dimension at ``percentile``.
    """
    check_sex(sex)
    check_percentile(percentile)
    pop = load_population(population)
    stature = pop.value(sex, "stature", percentile)
    mass = pop.value(sex, "mass", percentile)

    def at(name: str) -> float:
        dim = pop.dimension(sex, name)
        return dim.predict(stature, mass) if dim.regression is not None else dim.value(percentile)

    dims = {n: at(n) for n in pop.names(sex) if n not in GLOBALS}
    missing = [k for k in STATURE_PATH if k not in dims]
    if missing:
        raise AnthropometryError(f"population {population!r} lacks stature-path dimensions {missing}")
    eye_drop = stature - at("eye_height")
    spec = BodySpec(sex, float(percentile), population, mass, dims, eye_drop)
    _share(spec, stature - spec.stature, list(STATURE_PATH), clamp=False)
    return spec


def _spread(spec: BodySpec, name: str) -> float:
    d = spec.table().dimension(spec.sex, name).values
    return float(d[5] - d[1])


def _range_5_95(spec: BodySpec, name: str) -> tuple[float, float]:
    d = spec.table().dimension(spec.sex, name).values
    return float(d[1]), float(d[5])


def _share(spec: BodySpec, delta: float, names: list[str], clamp: bool) -> None:
    """Add ``delta`` metres over ``names`` in proportion to their spreads; with ``clamp`` keep each in
    its 5th-95th range, handing the excess to the others (raises ScalingError if they cannot take it)."""
    free = list(names)
    while abs(delta) > 1e-12:
        if not free:
            raise ScalingError(f"fixed-stature rule: the other stature-path segments cannot absorb "
                               f"{delta * 100:.2f} cm within their 5th-95th percentile ranges")
        w = np.array([_spread(spec, n) for n in free])
        w = w / w.sum()
        rest = 0.0
        for n, wi in zip(list(free), w):
            new = spec.dims[n] + delta * wi
            if clamp:
                lo, hi = _range_5_95(spec, n)
                bounded = min(max(new, lo), hi)
                rest += new - bounded
                if bounded != new:
                    free.remove(n)
                new = bounded
            spec.dims[n] = new
        delta = rest


def set_dimension(spec: BodySpec, name: str, value: float, rule: str = "free") -> BodySpec:
    """A new spec with dimension ``name`` set to ``value`` (m; kg for ``mass``) under ``rule``.

    ``stature`` and ``mass`` go to :func:`set_stature` / :func:`set_mass` (with ``tie_mass=False``).
    """
    if rule not in RULES:
        raise AnthropometryError(f"rule must be one of {', '.join(RULES)}, not {rule!r}")
    if not (np.isfinite(value) and value > 0):
        raise AnthropometryError(f"{name} must be a positive value, not {value}")
    if name == "stature":
        return set_stature(spec, value, rule)
    if name == "mass":
        return set_mass(spec, value)
    if name not in spec.dims:
        raise AnthropometryError(f"unknown dimension {name!r} (known: stature, mass, "
                                 f"{', '.join(sorted(spec.dims))})")
    out = spec.copy()
    delta = value - out.dims[name]
    out.dims[name] = float(value)
    out.overrides[name] = float(value)
    if rule == "fixed" and name in STATURE_PATH:
        _share(out, -delta, [n for n in STATURE_PATH if n != name], clamp=True)
    return out


def set_stature(spec: BodySpec, stature: float, rule: str = "free", tie_mass: bool = False) -> BodySpec:
    """A new spec of ``stature`` metres: path lengths follow linearly (``fixed``: within 5th-95th)."""
    if not (np.isfinite(stature) and stature > 0):
        raise AnthropometryError(f"stature must be a positive value, not {stature}")
    out = spec.copy()
    old = out.stature
    _share(out, stature - old, [n for n in STATURE_PATH if n not in spec.overrides] or list(STATURE_PATH),
           clamp=(rule == "fixed"))
    out.overrides["stature"] = float(stature)
    if tie_mass:
        out.mass = mass_for_stature(out.mass, old, stature)
    return out


def set_mass(spec: BodySpec, mass: float, tie_stature: bool = False) -> BodySpec:
    """A new spec of body ``mass`` kg; with ``tie_stature`` stature follows at constant BMI."""
    if not (np.isfinite(mass) and mass > 0):
        raise AnthropometryError(f"mass must be a positive value, not {mass}")
    out = spec.copy()
    if tie_stature:
        out = set_stature(out, out.stature * float(np.sqrt(mass / out.mass)))
    out.mass = float(mass)
    out.overrides["mass"] = float(mass)
    return out


def mass_for_stature(mass: float, old_stature: float, new_stature: float) -> float:
    """Mass-stature rule: ``mass`` (kg) carried from ``old_stature`` to ``new_stature`` at constant BMI."""
    return float(mass * (new_stature / old_stature) ** 2)


def apply_overrides(spec: BodySpec, overrides: dict[str, float] | None, rule: str = "free") -> BodySpec:
    """Apply ``{dimension: value}`` (SI) in order: stature first, then mass, then the rest."""
    if not overrides:
        return spec
    order = sorted(overrides, key=lambda k: {"stature": 0, "mass": 1}.get(k, 2))
    for name in order:
        spec = set_dimension(spec, name, float(overrides[name]), rule)
    return spec


def uneven_scale(points: np.ndarray, axis: np.ndarray, r0: np.ndarray, r1: np.ndarray,
                 s0: np.ndarray, s1: np.ndarray) -> np.ndarray:
    """Uneven scaling along a segment (quarterly report §9): each point ``x`` (n,3, segment frame) is
    scaled about the segment origin by ``s(x) = (1 - t) s0 + t s1``, ``t = ((x - r0).a) / ((r1 - r0).a)``
    clamped to [0, 1], so points beyond the reference positions keep the end scales. ``s0 == s1`` is
    Jack's uniform per-axis scaling."""
    x = np.asarray(points, dtype=float).reshape(-1, 3)
    a = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    r0, r1 = np.asarray(r0, dtype=float), np.asarray(r1, dtype=float)
    span = float(np.dot(r1 - r0, a))
    if abs(span) < 1e-12:
        raise ScalingError("uneven scaling: the two reference positions coincide along the axis")
    t = np.clip((x - r0) @ a / span, 0.0, 1.0)[:, None]
    return x * ((1.0 - t) * np.asarray(s0, dtype=float) + t * np.asarray(s1, dtype=float))


def scale_segment_unevenly(figure: Figure, segment: str, axis: np.ndarray, site0: str, site1: str,
                           s0: np.ndarray, s1: np.ndarray) -> None:
    """Apply :func:`uneven_scale` to a segment's surface and sites, between two of its sites (their
    positions are the reference positions); attached segments follow their (moved) joint sites."""
    seg = figure.segment(segment)
    r0, r1 = seg.site(site0).location[:3, 3].copy(), seg.site(site1).location[:3, 3].copy()
    if seg.psurf is not None and seg.psurf.mesh is not None:
        posed = seg.psurf.posed_mesh()
        seg.psurf = Psurf(seg.psurf.source, np.eye(4),
                          Mesh(uneven_scale(posed.vertices, axis, r0, r1, s0, s1), posed.faces))
    for site in seg.sites.values():
        site.location = site.location.copy()
        site.location[:3, 3] = uneven_scale(site.location[:3, 3], axis, r0, r1, s0, s1)[0]
    figure.topology_changed()
