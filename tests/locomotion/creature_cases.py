"""Shared, cached walks of the shipped creatures (computed once per test session; 10 fps keeps
the suite short, every check is per frame)."""

from __future__ import annotations

import functools
from pathlib import Path

from jackpy.locomotion.config import WalkConfig
from jackpy.locomotion.creature_walk import WalkResult, walk
from jackpy.locomotion.terrain import Terrain, load
from jackpy.peabody.reader import load as load_figures

ROOT = Path(__file__).resolve().parents[2]
CREATURES = ROOT / "examples" / "creatures"
NAMES = ("hexapod", "quadruped", "biped")
TERRAINS = ("rolling_hills", "steps")
TEST_FPS = 10.0


def creature(name: str):
    return load_figures(CREATURES / f"{name}.fig").figures[name]


@functools.lru_cache(maxsize=None)
def terrain(name: str) -> Terrain:
    return load(CREATURES / f"{name}.terrain.json")


@functools.lru_cache(maxsize=None)
def shipped_walk(name: str, terrain_name: str) -> WalkResult:
    """``name`` walks 5 m straight ahead (+z) over ``terrain_name``."""
    return walk(creature(name), terrain(terrain_name), (0.0, 5.0), config=WalkConfig(fps=TEST_FPS))
