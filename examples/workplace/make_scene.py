"""Regenerate the example workplace's CAD files (run from this folder: ``python make_scene.py``).

A standing workbench (millimetres, z up, as many CAD packages write it), a shelf above it (STL, metres), a panel
with a display (OBJ, centimetres) and a partition hiding a gauge (PLY, metres). workplace.json
places them and names the sites; the figure stands at the origin facing +z.
"""

import trimesh


def box(lo, hi):
    return trimesh.creation.box(bounds=[lo, hi])


def main() -> None:
    # standing workbench in mm, z up: top 1200 x 700 x 40 at 1000 mm, four legs
    parts = [box([-600, -700, 960], [600, 0, 1000])]  # file -y becomes +z (away from the figure)
    for x in (-580, 560):
        for y in (-680, -40):
            parts.append(box([x, y, 0], [x + 20, y + 20, 960]))
    trimesh.util.concatenate(parts).export("desk.obj")
    box([-0.5, 0.0, 0.0], [0.5, 0.03, 0.35]).export("shelf.stl")  # metres, y up
    box([-30.0, 0.0, 0.0], [30.0, 40.0, 2.0]).export("panel.obj")  # cm, y up: 60 x 40 cm, 2 cm thick
    box([-0.15, 0.0, -0.02], [0.15, 0.9, 0.02]).export("partition.ply")
    box([-0.06, -0.06, -0.01], [0.06, 0.06, 0.01]).export("gauge.off")


if __name__ == "__main__":
    main()
