"""Regenerate the box-reach example's CAD file (run from this folder: ``python make_scene.py``).

A closed box 40 x 40 x 40 cm (walls 1.5 cm thick, metres, y up) with a 15 cm square hole in the side
that faces the figure. box_reach.json puts it in front of the right shoulder of a figure standing at
the origin facing +z and names a site inside it, behind the hole and lower than it, so that the
hand has to go in through the hole.
"""

import trimesh

SIZE, WALL, HOLE = 0.40, 0.015, 0.15


def box(lo, hi):
    return trimesh.creation.box(bounds=[lo, hi])


def main() -> None:
    s, w, h = SIZE, WALL, HOLE
    c = s / 2  # the hole's centre in the front wall (x, y)
    parts = [
        box([0, 0, 0], [s, w, s]), box([0, s - w, 0], [s, s, s]),  # bottom, top
        box([0, 0, 0], [w, s, s]), box([s - w, 0, 0], [s, s, s]),  # sides
        box([0, 0, s - w], [s, s, s]),  # back
        # front wall (z = 0 .. w) around the hole
        box([0, 0, 0], [s, c - h / 2, w]), box([0, c + h / 2, 0], [s, s, w]),
        box([0, c - h / 2, 0], [c - h / 2, c + h / 2, w]), box([c + h / 2, c - h / 2, 0], [s, c + h / 2, w]),
    ]
    trimesh.util.concatenate(parts).export("box.stl")


if __name__ == "__main__":
    main()
