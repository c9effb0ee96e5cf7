"""Gaits (Sims 9.2, 10.3): per-foot down and up times as fractions of the cycle, and the automatic
assignment for any number of legs.

A foot is in stance while the phase ``phi = t / T mod 1`` lies in the cyclic interval
``[down, up)``. Automatic assignment splits the legs into left and right sides, each sorted front
to back (index ``k`` of ``n_s`` on its side), and computes each side independently (digest §7.4):

- ``trot``: ``down = 0.5 (k mod 2)`` on the left, ``+ 0.5`` on the right: biped walk, quadruped
  trot, hexapod tripod;
- ``wave``: ``down = (n_s - 1 - k) / n_s`` on both sides (the wave runs back to front, as in
  insects): hexapod metachronal wave, quadruped bound, biped hop;
- ``pronk``: every foot down at 0 (all feet together).

``up = down + duty`` (mod 1).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from jackpy.locomotion.config import WalkConfig
from jackpy.locomotion.legs import Leg

GAITS = ("auto", "wave", "tripod", "trot", "pronk")


@dataclass
class Gait:
    """``down[k]``, ``up[k]`` (fractions of the cycle in [0, 1)) for foot ``k``; ``cycle`` (s)."""

    name: str
    down: np.ndarray
    up: np.ndarray
    cycle: float

    @property
    def duty(self) -> np.ndarray:
        return (self.up - self.down) % 1.0

    def phase(self, t: float) -> float:
        return (t / self.cycle) % 1.0

    def in_stance(self, t: float) -> np.ndarray:
        """Boolean per foot at time ``t`` (s)."""
        rel = (self.phase(t) - self.down) % 1.0
        return rel < self.duty

    def next_down(self, k: int, t: float) -> float:
        """The first time >= ``t`` at which foot ``k`` goes down."""
        rel = (self.down[k] - self.phase(t)) % 1.0
        return t + rel * self.cycle

    def last_up(self, k: int, t: float) -> float:
        """The latest time <= ``t`` at which foot ``k`` lifted off."""
        rel = (self.phase(t) - self.up[k]) % 1.0
        return t - rel * self.cycle


def assign(legs: Sequence[Leg], gait: str, config: WalkConfig) -> Gait:
    """The gait ``gait`` (one of :data:`GAITS`) for ``legs`` with ``config``'s cycle and duty."""
    if gait not in GAITS:
        raise ValueError(f"gait must be one of {', '.join(GAITS)}, not {gait!r}")
    if gait == "auto":
        gait = "trot" if len(legs) <= 4 else "wave"
    if gait == "tripod":
        gait = "trot"
    n = len(legs)
    down = np.zeros(n)
    for side in (1, -1):
        mine = sorted((g for g in legs if g.side == side), key=lambda g: g.order)
        ns = len(mine)
        for g in mine:
            k = legs.index(g)
            if gait == "trot":
                down[k] = (0.5 * (g.order % 2) + (0.5 if side < 0 else 0.0)) % 1.0
            elif gait == "wave":
                down[k] = (ns - 1 - g.order) / ns
    duty = {"trot": config.duty_trot, "wave": config.duty_wave, "pronk": config.duty_trot}[gait]
    if not 0.0 < duty <= 1.0:
        raise ValueError(f"duty factor must lie in (0, 1], not {duty}")
    up = (down + duty) % 1.0 if duty < 1.0 else down + 1.0 - 1e-9
    return Gait(gait, down, up, float(config.cycle_time))


def bounce(phase: float) -> float:
    """The gait-phased bounce shape: a zero-mean cyclic spline of unit amplitude, two bumps per
    cycle (one per half-cycle of the support pattern): ``cos(4 pi phase)``."""
    return math.cos(4.0 * math.pi * phase)
