"""Shared walks for the walking tests: baked once per session at a low rate (CI time)."""

from __future__ import annotations

import functools

import numpy as np

from jackpy.locomotion import footsteps, walk_path, walk_solve
from jackpy.locomotion.walk_gait import GaitParams
from jackpy.motion import cast

FPS = 12.0
#: the S-curve x = 0.5 sin(πz/3) ends at z = 6 with this heading (its tangent there)
S_END_HEADING = float(np.arctan2(0.5 * np.pi / 3, 1.0))
SOLE = [("foot", "heel"), ("foot", "ball"), ("toes", "tip")]


@functools.lru_cache(maxsize=None)
def figure_and_params(human: str):
    fig = cast.make_figure("walker", {"human": human})
    return fig, GaitParams.for_figure(fig)


@functools.lru_cache(maxsize=None)
def baked(human: str, kind: str):
    """(figure, params, steps, postures, targets) of a named walk."""
    fig, p = figure_and_params(human)
    if kind == "straight":
        steps = footsteps.straight(p, 3.0)
    elif kind == "quarter":
        a = np.linspace(0.0, np.pi / 2, 9)
        steps = footsteps.from_path(p, np.column_stack([2.0 - 2.0 * np.cos(a), 2.0 * np.sin(a)]), facing=np.pi / 2)
    elif kind == "s-curve":
        z = np.linspace(0.0, 6.0, 13)
        steps = footsteps.from_path(p, np.column_stack([0.5 * np.sin(z * np.pi / 3), z]), facing=S_END_HEADING)
    else:
        raise KeyError(kind)
    walk = walk_path.Walk(steps, p)
    postures, targets = walk_solve.bake(fig, walk, FPS)
    return fig, p, steps, postures, targets


def sole(fig, side: str) -> np.ndarray:
    """World heel, ball, toe tip of one foot (tip lowered by its standing height)."""
    return np.array([fig.site_world(f"{side}_{a}", b)[:3, 3] for a, b in SOLE])
