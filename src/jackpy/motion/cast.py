"""The figures a timeline drives: made from its ``cast`` (or the standard 50th-percentile male),
stood in the scene, each with its behavior loop."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

import numpy as np

from jackpy.errors import FigureError

if TYPE_CHECKING:
    from jackpy.behaviors.loop import BehaviorLoop
    from jackpy.motion.timeline import Timeline
    from jackpy.peabody.model import Environment, Figure

DEFAULT_HUMAN = "male:50"


def parse_human(text: str) -> tuple[str, float]:
    """``"male:50"`` / ``"female:5"`` -> (sex, percentile); FigureError for anything else."""
    sex, _, pct = text.partition(":")
    if sex not in ("male", "female"):
        raise FigureError(f"a standard human is male:PCT or female:PCT, not {text!r}")
    try:
        p = float(pct or 50)
    except ValueError:
        raise FigureError(f"percentile of {text!r} is not a number") from None
    if not 0.0 < p < 100.0:
        raise FigureError(f"percentile of {text!r} must be in (0, 100)")
    return sex, p


def make_figure(name: str, spec: dict[str, Any] | None = None) -> "Figure":
    """The standard human of ``spec`` (``human``, ``position`` [x, z] m, ``heading_deg``) named ``name``."""
    from jackpy.body.human import make_human
    from jackpy.scene.workplace import Stand, stand_figure

    spec = spec or {}
    sex, pct = parse_human(spec.get("human", DEFAULT_HUMAN))
    fig = make_human(sex, pct, name=name)
    x, z = spec.get("position", [0.0, 0.0])
    stand_figure(fig, Stand((float(x), float(z)), float(np.radians(spec.get("heading_deg", 0.0)))))
    return fig


def loop_for(figure: "Figure") -> "BehaviorLoop":
    """A behavior loop with the default behaviors for a standard human."""
    from jackpy.behaviors.anatomy import human_anatomy
    from jackpy.behaviors.loop import BehaviorLoop

    return BehaviorLoop(figure, human_anatomy(figure))


def build(timeline: "Timeline", scene: str | os.PathLike | None = None,
          env: "Environment | None" = None) -> tuple["Environment", dict[str, "BehaviorLoop"]]:
    """The environment (the scene's objects when ``scene`` is given) and one loop per figure of
    ``timeline`` (figures already in ``env`` are used as they are)."""
    from jackpy.peabody.model import Environment

    if env is None:
        if scene is not None:
            from jackpy.scene.workplace import load_workplace

            env = load_workplace(scene).env
        else:
            env = Environment()
    loops = {}
    for name in timeline.figures():
        fig = env.figures.get(name)
        if fig is None:
            fig = env.add(make_figure(name, timeline.cast.get(name)))
        loops[name] = loop_for(fig)
    return env, loops
