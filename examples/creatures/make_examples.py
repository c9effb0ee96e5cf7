"""Regenerate the shipped creature examples: the three drawings, their built figures and the two
terrains. Run from the repository root: ``python examples/creatures/make_examples.py``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from jackpy.locomotion.creature_editor import Drawing, build, save_figure
from jackpy.locomotion.terrain import Terrain, save

HERE = Path(__file__).resolve().parent


def _leg(nodes: list, links: list, base: int, y: float, side: int, lengths: tuple[float, ...]) -> None:
    prev, x, bx = base, 0.0, nodes[base][0]
    for length in lengths:
        x += length
        nodes.append([bx + side * x, y])
        links.append([prev, len(nodes) - 1])
        prev = len(nodes) - 1


def hexapod() -> dict:
    """An insect: a straight body of three nodes, a two-link leg out of each side at each node."""
    nodes, links = [[0, -20], [0, 0], [0, 20]], [[0, 1], [1, 2]]
    for k, y in enumerate((-20, 0, 20)):
        for side in (-1, 1):
            _leg(nodes, links, k, y, side, (14, 18))
    return dict(name="hexapod", style="insect", units="cm", thickness=2, body_thickness=6, nodes=nodes, links=links)


def quadruped() -> dict:
    """A mammal: a spine of three nodes, legs at the shoulders and hips, a head and a tail."""
    nodes, links = [[0, -22], [0, 0], [0, 22]], [[0, 1], [1, 2]]
    for k, y in ((0, -22), (2, 22)):
        for side in (-1, 1):
            _leg(nodes, links, k, y, side, (14, 16))
    a = len(nodes)
    nodes += [[0, -32], [0, -40]]
    links += [[0, a], [a, a + 1]]
    nodes += [[0, 36]]
    links += [[2, a + 2]]
    return dict(name="quadruped", style="mammal", units="cm", thickness=3, body_thickness=10, nodes=nodes, links=links)


def biped() -> dict:
    """A bird-like mammal-style biped: a triangular body, two legs, a beak."""
    nodes, links = [[-6, 0], [6, 0], [0, -10]], [[0, 1], [1, 2], [2, 0]]
    for k, side in ((0, -1), (1, 1)):
        _leg(nodes, links, k, 0, side, (14, 16))
    nodes += [[0, -20]]
    links += [[2, len(nodes) - 1]]
    return dict(name="biped", style="mammal", units="cm", thickness=3, body_thickness=10, nodes=nodes, links=links)


def rolling_hills() -> Terrain:
    """Three crossed sine waves, at most 9 cm high and 11 degrees steep: no forbidden zones."""
    def h(x, z):
        return (0.04 * np.sin(2 * np.pi * z / 1.6) + 0.03 * np.sin(2 * np.pi * x / 1.3 + 0.5)
                + 0.02 * np.sin(2 * np.pi * (x + z) / 2.1))
    t = Terrain.from_function(h, (-1.5, 1.5), (-1.5, 7.5), 0.05, name="rolling_hills")
    t.heights = np.round(t.heights, 5)
    return t


def steps() -> Terrain:
    """Flat ground, a 5 cm step up at z = 1.5 m and another at z = 3 m, each a 60-degree bank, then a
    steep 6 cm bank down at z = 4.2 m: each bank is forbidden with a foot-radius band below it."""
    def h(x, z):
        up1 = np.clip((z - 1.5) / 0.03, 0, 1) * 0.05
        up2 = np.clip((z - 3.0) / 0.03, 0, 1) * 0.05
        down = np.clip((z - 4.2) / 0.035, 0, 1) * 0.06
        return up1 + up2 - down
    t = Terrain.from_function(h, (-1.5, 1.5), (-1.5, 7.5), 0.05, name="steps")
    t.heights = np.round(t.heights, 5)
    return t


def main() -> None:
    for make in (hexapod, quadruped, biped):
        d = make()
        (HERE / f"{d['name']}.drawing.json").write_text(json.dumps(d, indent=1) + "\n")
        save_figure(build(Drawing.from_dict(d)), HERE / f"{d['name']}.fig")
    save(rolling_hills(), HERE / "rolling_hills.terrain.json")
    save(steps(), HERE / "steps.terrain.json")


if __name__ == "__main__":
    main()
