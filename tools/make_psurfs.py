"""Generate the psurf geometry shipped in figures/ (run from the repository root).

Every file is a polygon mesh in centimetres (see docs/peabody-format.md); boxes are written as
quads and prisms as quads plus two n-gon caps, so the files stay short and readable.
"""

from __future__ import annotations

import math
from pathlib import Path

from jackpy.atomic import atomic_write_text

Box = tuple[tuple[float, float, float], tuple[float, float, float]]


def _num(v: float) -> str:
    s = format(v, ".6g")
    return "0" if s == "-0" else s


def polygons_text(title: str, vertices: list[tuple[float, float, float]], faces: list[list[int]]) -> str:
    """``.pss`` text from vertices (cm) and 0-based polygons (counter-clockwise from outside)."""
    lines = [f"# {title}", "# jackpy psurf: v X Y Z (cm); f I J K ... (1-based, counter-clockwise from outside)"]
    lines += ["v " + " ".join(_num(c) for c in v) for v in vertices]
    lines += ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def boxes(parts: list[Box]) -> tuple[list[tuple[float, float, float]], list[list[int]]]:
    """Vertices and quads of axis-aligned boxes given by (min corner, max corner) in cm."""
    verts: list[tuple[float, float, float]] = []
    faces: list[list[int]] = []
    quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    for lo, hi in parts:
        base = len(verts)
        verts += [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2])
                  for i in range(8)]
        faces += [[base + k for k in q] for q in quads]
    return verts, faces


def prism(sides: int, length: float, radius: float) -> tuple[list[tuple[float, float, float]], list[list[int]]]:
    """A regular prism along +x from 0 to ``length`` with circumradius ``radius`` (cm)."""
    ring = [(radius * math.cos(2 * math.pi * k / sides), radius * math.sin(2 * math.pi * k / sides))
            for k in range(sides)]
    verts = [(0.0, y, z) for y, z in ring] + [(length, y, z) for y, z in ring]
    faces = [[k, (k + 1) % sides, sides + (k + 1) % sides, sides + k] for k in range(sides)]
    faces += [list(range(sides - 1, -1, -1)), list(range(sides, 2 * sides))]
    return verts, faces


def main(out: Path = Path("figures")) -> None:
    seat_h, leg_w = 43.0, 4.0
    chair = [((-22.5, seat_h, -22.5), (22.5, seat_h + 4, 22.5)),
             ((-22.5, seat_h + 4, -22.5), (22.5, seat_h + 49, -18.5))]
    chair += [((x, 0, z), (x + leg_w, seat_h, z + leg_w)) for x in (-22.5, 18.5) for z in (-22.5, 18.5)]
    table = [((-60, 72, -40), (60, 76, 40))]
    table += [((x, 0, z), (x + 5, 72, z + 5)) for x in (-58, 53) for z in (-38, 33)]
    shapes = {
        "cube.pss": ("cube, 100 cm, corner at the origin (the book's table top, scaled)",
                     boxes([((0, 0, 0), (100, 100, 100))])),
        "leg.pss": ("table leg, 10 x 75 x 10 cm, base corner at the origin", boxes([((0, 0, 0), (10, 75, 10))])),
        "link.pss": ("octagonal link along +x, 100 cm long, radius 50 cm (scale it)", prism(8, 100.0, 50.0)),
        "chair.pss": ("chair, seat 45 x 45 cm at 47 cm, origin on the floor under the seat centre",
                      boxes(chair)),
        "worktable.pss": ("work table, top 120 x 80 cm at 76 cm, origin on the floor under the centre",
                          boxes(table)),
    }
    for name, (title, (verts, faces)) in shapes.items():
        atomic_write_text(out / name, polygons_text(title, verts, faces))


if __name__ == "__main__":
    main()
