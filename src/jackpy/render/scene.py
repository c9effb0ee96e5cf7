"""What the renderer draws, as plain data: one :class:`Scene` per frame.

All positions are in the world frame in metres, transforms 4x4 float column-vector matrices
(``p_world = T @ p_local``), colours RGBA floats in [0, 1]. A pick id is a positive integer
reported by :meth:`Renderer.pick`; ``None`` (the default) keeps a thing out of picking, though an
opaque thing still hides what is behind it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

Color = Sequence[float]
"""RGBA in [0, 1]; RGB alone means opaque."""


@dataclass
class DrawItem:
    """One instance of a cached mesh (see :meth:`Renderer.add_mesh`) placed in the world.

    ``transparent`` draws it blended and depth-sorted without writing depth (CAD and analysis
    volumes); ``wireframe`` overlays its edges; ``highlighted`` tints it and adds a rim glow.
    """

    mesh: str
    transform: np.ndarray
    color: Color = (0.8, 0.8, 0.8, 1.0)
    pick_id: int | None = None
    transparent: bool = False
    wireframe: bool = False
    highlighted: bool = False


@dataclass
class SkinnedItem:
    """A skinned mesh (see :meth:`Renderer.add_skinned_mesh`) posed by ``bones`` (b, 4, 4) world
    skinning matrices (each maps rest positions to world, e.g. ``W_b @ inverse_bind_b``); per bone
    its owned vertices' colour (one RGBA or (b, 4)), pick id and highlight. Always opaque.

    ``bone_items``: per bone the mesh key of an opaque :class:`DrawItem` the skin stands in for
    (a rigid segment surface). Such items are not drawn; their colour, pick id and highlight go to
    the bone's vertices, so whatever recolours, highlights or removes items also acts on the skin."""

    mesh: str
    bones: np.ndarray
    colors: Color | np.ndarray = (0.8, 0.8, 0.8, 1.0)
    pick_ids: Sequence[int | None] | None = None
    highlighted: Sequence[bool] | bool = False
    bone_items: Sequence[str] | None = None


@dataclass
class Spheres:
    """Skeleton-mode balls: ``centers`` (N, 3) m, radius scalar or (N,) m, colour one or (N, 4)."""

    centers: np.ndarray
    radius: float | np.ndarray = 0.02
    color: Color | np.ndarray = (0.9, 0.75, 0.3, 1.0)
    pick_ids: Sequence[int | None] | None = None


@dataclass
class Sticks:
    """Skeleton-mode cylinders from ``starts`` (N, 3) to ``ends`` (N, 3) m, ``radius`` m."""

    starts: np.ndarray
    ends: np.ndarray
    radius: float | np.ndarray = 0.01
    color: Color | np.ndarray = (0.75, 0.75, 0.8, 1.0)
    pick_ids: Sequence[int | None] | None = None


@dataclass
class Triad:
    """Axes of a frame (a site, the manipulation transform): red x, green y, blue z arrows.

    ``transform`` places the frame in the world; ``size`` is the arrow length in m.
    """

    transform: np.ndarray
    size: float = 0.1
    pick_id: int | None = None


@dataclass
class GoalMarker:
    """A 3-D cross of half-size ``size`` m at ``position``; with ``direction``, an arrow too.

    The arrow starts at the position and points along ``direction`` (aim and gaze goals),
    ``2 * size`` long.
    """

    position: np.ndarray
    color: Color = (1.0, 0.3, 0.1, 1.0)
    size: float = 0.04
    direction: np.ndarray | None = None
    pick_id: int | None = None


@dataclass
class Lines:
    """Line segments ``segments`` (N, 2, 3) m, one colour or (N, 4).

    ``on_top`` draws them over everything (operator feedback such as the wheel and spoke).
    """

    segments: np.ndarray
    color: Color | np.ndarray = (1.0, 1.0, 1.0, 1.0)
    on_top: bool = False


@dataclass
class Grid:
    """Floor grid on y = 0, fading out ``fade_distance`` m from the point under the camera."""

    spacing: float = 0.1
    major_every: int = 10
    fade_distance: float = 12.0
    minor_color: Color = (0.55, 0.57, 0.6, 0.35)
    major_color: Color = (0.7, 0.72, 0.75, 0.7)


@dataclass
class Scene:
    """Everything drawn in one frame."""

    items: list[DrawItem] = field(default_factory=list)
    skins: list[SkinnedItem] = field(default_factory=list)
    spheres: list[Spheres] = field(default_factory=list)
    sticks: list[Sticks] = field(default_factory=list)
    triads: list[Triad] = field(default_factory=list)
    markers: list[GoalMarker] = field(default_factory=list)
    lines: list[Lines] = field(default_factory=list)
    grid: Grid | None = field(default_factory=Grid)
    background: Color = (0.16, 0.17, 0.19, 1.0)
