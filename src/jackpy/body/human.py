"""Make the standard human for a population, sex and percentile; rescale a figure in place.

``make_human("female", 5)`` builds the structure (:mod:`skeleton`), the surfaces (:mod:`shapes`) and the
mass properties (:mod:`segment_inertia`) from the SASS body specification (:mod:`sass`) and stands the
figure in the neutral posture: feet on the floor (y = 0), facing +z, arms down. The figure keeps its
specification as ``figure.body_spec`` (see :func:`body_spec`).
"""

from __future__ import annotations

import numpy as np

from jackpy.body.sass import BodySpec, apply_overrides, spec_for
from jackpy.body.segment_inertia import assign_mass_properties
from jackpy.body.shapes import body_shapes
from jackpy.body.shoulder import SHOULDER_ANGLES
from jackpy.body.skeleton import NEUTRAL_ARM_ELEVATION, SIDES, build_skeleton
from jackpy.errors import FigureError
from jackpy.peabody.geometry import Psurf
from jackpy.peabody.model import Figure

#: sites that touch the floor in the neutral posture
SUPPORT_SITES = tuple((f"{side}_foot", n) for side, _ in SIDES for n in ("heel", "ball", "toe"))


def figure_name(spec: BodySpec) -> str:
    """Default figure name, e.g. ``female_p5`` or ``male_p50_ansur2`` for other populations."""
    p = f"{spec.percentile:g}".replace(".", "_")
    return f"{spec.sex}_p{p}" + ("" if spec.population == "ansur2" else f"_{spec.population}")


FOOTWEAR = ("shoe", "barefoot")


def build_spec(sex: str, percentile: float, population: str = "ansur2",
               overrides: dict[str, float] | None = None, rule: str = "free", footwear: str = "shoe") -> BodySpec:
    """The body specification: population percentile then ``overrides`` (SI units) under ``rule``;
    ``footwear`` is ``"shoe"`` (labelled outline allowance) or ``"barefoot"``."""
    if footwear not in FOOTWEAR:
        raise FigureError(f"footwear must be one of {', '.join(FOOTWEAR)}, not {footwear!r}")
    spec = apply_overrides(spec_for(sex, percentile, population), overrides, rule)
    spec.footwear = footwear
    return spec


def make_human(sex: str, percentile: float = 50.0, population: str = "ansur2",
               overrides: dict[str, float] | None = None, rule: str = "free", name: str | None = None,
               footwear: str = "shoe") -> Figure:
    """A standard human standing in the neutral posture (feet on y = 0, facing +z, left = +x).

    ``overrides`` maps dimension names (``stature``, ``mass``, ``thigh.length`` ...) to values in metres
    (kilograms for ``mass``); ``rule`` is the SASS stature rule (``free`` or ``fixed``) they follow.
    ``footwear``: ``"shoe"`` (the default look: a shoe outline 8 mm behind the heel, 10 mm beyond the
    toes, 5 mm each side, heights barefoot) or ``"barefoot"`` (the ANSUR II foot).
    """
    spec = build_spec(sex, percentile, population, overrides, rule, footwear)
    return figure_from_spec(spec, name or figure_name(spec))


def figure_from_spec(spec: BodySpec, name: str) -> Figure:
    """Build the figure of ``spec`` (structure, surfaces, mass) in the neutral posture."""
    sk = build_skeleton(spec, name)
    fig = sk.figure
    for seg, (mesh, attribute) in body_shapes(spec, sk).items():
        s = fig.segment(seg)
        s.psurf = Psurf(f"{seg}.pss", np.eye(4), mesh)
        s.attribute = attribute
    assign_mass_properties(fig, spec.sex, spec.mass)
    fig.body_spec = spec  # type: ignore[attr-defined]
    set_neutral_posture(fig)
    return fig


def body_spec(figure: Figure) -> BodySpec:
    """The :class:`BodySpec` a figure was made from (raises FigureError for other figures)."""
    spec = getattr(figure, "body_spec", None)
    if spec is None:
        raise FigureError(f"figure {figure.name!r} was not made by jackpy.body (no body specification)")
    return spec


def set_neutral_posture(figure: Figure) -> None:
    """Neutral standing: every displacement and group angle zero except the arms, which hang
    ``NEUTRAL_ARM_ELEVATION`` degrees out from the body; the lowest support site on the floor."""
    figure.q = np.zeros(figure.ndof)
    for g in figure.groups.values():
        theta = np.zeros(g.nangles)
        if g.name.endswith("_shoulder_complex"):
            theta[SHOULDER_ANGLES.index("elevation")] = np.radians(NEUTRAL_ARM_ELEVATION)
        g.set_angles(figure, theta)
    place_on_floor(figure)


def support_height(figure: Figure) -> float:
    """Lowest world height (m) of the heel, ball and toe sites of both feet."""
    return min(float(figure.site_world(*s)[1, 3]) for s in SUPPORT_SITES)


def place_on_floor(figure: Figure, floor: float = 0.0) -> None:
    """Move the figure vertically so its lowest support site is at height ``floor`` (m)."""
    figure.location = figure.location.copy()
    figure.location[1, 3] += floor - support_height(figure)


def rescale_in_place(figure: Figure, sex: str, percentile: float, population: str = "ansur2",
                     overrides: dict[str, float] | None = None, rule: str = "free", footwear: str | None = None) -> None:
    """Give ``figure`` the body of another sex/percentile/population, keeping its posture.

    Joint displacements, group angles, root and the root's horizontal placement are kept; the figure
    is moved vertically so its lowest support site stays at the height it had (on the floor). Sites,
    surfaces and mass properties are replaced. Goals are not re-solved here.
    """
    old_spec = getattr(figure, "body_spec", None)
    if footwear is None:
        footwear = old_spec.footwear if old_spec is not None else "shoe"
    spec = build_spec(sex, percentile, population, overrides, rule, footwear)
    new = figure_from_spec(spec, figure.name)
    if set(new.segments) != set(figure.segments) or set(new.joints) != set(figure.joints):
        raise FigureError(f"figure {figure.name!r} does not have the standard human's structure")
    floor = support_height(figure)
    q = figure.q
    angles = {n: g.angles.copy() for n, g in figure.groups.items()}
    for name, seg in new.segments.items():
        old = figure.segment(name)
        for site_name, site in seg.sites.items():
            old.add_site(site_name, site.location)
        old.psurf, old.attribute = seg.psurf, seg.attribute
        old.mass, old.com, old.inertia = seg.mass, seg.com, seg.inertia
    figure.topology_changed()
    figure.q = q
    for n, g in figure.groups.items():
        g.angles = angles[n]
    figure.body_spec = spec  # type: ignore[attr-defined]
    place_on_floor(figure, floor)


def peabody_copy(figure: Figure, psurf_dir: str = "") -> Figure:
    """A figure sharing ``figure``'s segments, joints and groups for writing as Peabody text: psurf
    names are prefixed with ``psurf_dir``; the spine and shoulder groups are written with their
    driver kinds, and a human marker (:func:`jackpy.body.saved.human_marker`) carries the body
    specification, so the file reads back as the same human."""
    from jackpy.body.saved import human_marker
    from jackpy.peabody.model import Segment

    out = Figure(figure.name)
    for seg in figure.segments.values():
        ps = seg.psurf
        if ps is not None:
            ps = Psurf(f"{psurf_dir}/{seg.name}.pss" if psurf_dir else f"{seg.name}.pss", ps.transform, ps.mesh)
        out.segments[seg.name] = Segment(seg.name, ps, seg.attribute, seg.sites, seg.mass, seg.com, seg.inertia)
    out.joints = dict(figure.joints)
    out.groups = dict(figure.groups)
    out.root, out.location = figure.root, figure.location.copy()
    spec = getattr(figure, "body_spec", None)
    out.human = human_marker(spec) if spec is not None else figure.human
    return out


def attach_groups(figure: Figure) -> None:
    """Add the spine and shoulder-complex groups to a standard human read from a Peabody file, with
    group angles recovered exactly from the member displacements the drivers produced. Files
    written now carry the groups themselves (their drivers have registered kinds): then this
    does nothing."""
    from jackpy.body.shoulder import shoulder_group
    from jackpy.body.spine import SPINE_ANGLES, SPINE_DOFS, spine_group

    if "spine" in figure.groups:
        return

    g = spine_group()
    member = np.concatenate([figure.joint(j).displacement for j in g.joints]).reshape(-1, 3)
    g.angles = np.array([member[:, SPINE_DOFS.index(a)].sum() for a in SPINE_ANGLES])
    figure.add_group(g)
    for side, _ in SIDES:
        g = shoulder_group(side)
        theta_c = np.degrees(figure.joint(f"{side}_clavicle").displacement[1])
        first, phi, _theta_s = np.degrees(figure.joint(f"{side}_shoulder").displacement)
        theta = theta_c / 0.2
        g.angles = np.radians([phi, theta, first + theta])  # the driver's first angle is tau - theta
        figure.add_group(g)
