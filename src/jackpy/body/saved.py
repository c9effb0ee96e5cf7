"""A saved standard human stays a human: the ``human { ... }`` marker of a Peabody file.

Writing (``jackpy human -o f.fig``, a session save) goes through :func:`jackpy.body.human.peabody_copy`,
which keeps the spine and shoulder groups (their drivers have the registered kinds ``spine`` and
``shoulder``, see :mod:`jackpy.peabody.groups`) and adds :func:`human_marker` of the body
specification. Reading back gives the figure with its groups; :func:`restore_human` (or
:func:`restore_humans` for an environment) turns the marker back into ``figure.body_spec`` so the
body's strength, rescaling and the behaviors treat it as the standard human it was.
:func:`is_standard_human` is the test the app uses to give a figure behaviors.
"""

from __future__ import annotations

from jackpy.body.sass import BodySpec
from jackpy.body.shoulder import SHOULDER_ANGLES
from jackpy.body.skeleton import SIDES
from jackpy.body.spine import SPINE_ANGLES
from jackpy.errors import FigureError
from jackpy.peabody.model import Environment, Figure, HumanMarker


def human_marker(spec: BodySpec) -> HumanMarker:
    """The marker of a body specification (all of it: dimensions, mass, eye drop, overrides)."""
    return HumanMarker(spec.population, spec.sex, float(spec.percentile), float(spec.mass), float(spec.eye_drop),
                       {k: float(v) for k, v in spec.dims.items()},
                       {k: float(v) for k, v in spec.overrides.items()})


def spec_from_marker(marker: HumanMarker) -> BodySpec:
    """The body specification a marker carries, exactly as it was written."""
    if not marker.dims or marker.mass <= 0:
        from jackpy.body.human import build_spec  # an older or hand-written marker: rebuild it

        return build_spec(marker.sex, marker.percentile, marker.population, marker.overrides or None)
    return BodySpec(marker.sex, marker.percentile, marker.population, marker.mass, dict(marker.dims),
                    marker.eye_drop, dict(marker.overrides))


def has_human_structure(figure: Figure) -> bool:
    """True when ``figure`` has the standard human's groups: the spine and both shoulder complexes
    with their angles (what the behaviors need)."""
    groups = figure.groups
    spine = groups.get("spine")
    if spine is None or list(spine.angle_names) != list(SPINE_ANGLES):
        return False
    for side, _ in SIDES:
        g = groups.get(f"{side}_shoulder_complex")
        if g is None or list(g.angle_names) != list(SHOULDER_ANGLES):
            return False
    return True


def is_standard_human(figure: Figure) -> bool:
    """True for a figure made by :func:`jackpy.body.make_human`, or read back from a file written
    from one (a human marker and the human's groups)."""
    if getattr(figure, "body_spec", None) is not None:
        return True
    return figure.human is not None and has_human_structure(figure)


def restore_human(figure: Figure) -> bool:
    """Give a figure read from a file its body specification from its marker; True when the figure
    is (now) a standard human. A marker on a figure without the human's groups raises FigureError."""
    if getattr(figure, "body_spec", None) is not None:
        return True
    if figure.human is None:
        return False
    if not has_human_structure(figure):
        raise FigureError(f"figure {figure.name!r} is marked as a jackpy human but lacks its spine and "
                          "shoulder groups")
    figure.body_spec = spec_from_marker(figure.human)  # type: ignore[attr-defined]
    return True


def restore_humans(env: Environment) -> list[str]:
    """:func:`restore_human` for every figure of an environment; the names of its humans."""
    return [name for name, fig in env.figures.items() if restore_human(fig)]
