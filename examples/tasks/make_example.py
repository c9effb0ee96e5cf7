"""Writes the meshes of the task examples (OBJ, metres): the book's control panel ([SH6] §6.1.5:
a slab through the six sites), a table, a 10 cm block on a closed crate and a small box (too small for the block).
Run: python3 examples/tasks/make_example.py"""

from pathlib import Path

import numpy as np
import trimesh

HERE = Path(__file__).parent
SITES_CM = np.array([[13.25, 163.02, 80.86], [64.78, 115.87, 95.00], [52.84, 129.09, 91.43],
                     [72.36, 158.77, 81.46], [9.15, 115.93, 94.98]])


def panel() -> trimesh.Trimesh:
    """A 1 cm slab just behind the sites' best-fit plane, 10 cm margin around them."""
    p = SITES_CM / 100.0
    c = p.mean(0)
    _, _, vt = np.linalg.svd(p - c)
    n = vt[2] if vt[2][2] > 0 else -vt[2]  # away from the agents (+z)
    u, v = vt[0], vt[1]
    ext_u, ext_v = np.ptp((p - c) @ u) + 0.2, np.ptp((p - c) @ v) + 0.2
    box = trimesh.creation.box([ext_u, ext_v, 0.01])
    R = np.column_stack([u, v, n])
    if np.linalg.det(R) < 0:
        R[:, 0] *= -1
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = c + n * 0.007
    box.apply_transform(T)
    return box


def main() -> None:
    panel().export(HERE / "panel" / "panel.obj")
    table = trimesh.util.concatenate([trimesh.creation.box([0.8, 0.04, 0.6], np.array(
        [[1, 0, 0, 0], [0, 1, 0, 0.73], [0, 0, 1, 0], [0, 0, 0, 1]]))] + [trimesh.creation.box(
            [0.04, 0.71, 0.04], np.array([[1, 0, 0, x], [0, 1, 0, 0.355], [0, 0, 1, z], [0, 0, 0, 1]]))
            for x in (-0.37, 0.37) for z in (-0.27, 0.27)])
    table.export(HERE / "put" / "table.obj")
    trimesh.creation.box([0.1, 0.1, 0.1]).export(HERE / "put" / "block.obj")
    trimesh.creation.box([0.3, 0.95, 0.3], np.array([[1, 0, 0, 0], [0, 1, 0, 0.475], [0, 0, 1, 0],
                                                      [0, 0, 0, 1]])).export(HERE / "put" / "crate.obj")
    walls = [([0.08, 0.005, 0.08], [0, 0.0025, 0])] + [
        ([0.005, 0.06, 0.08], [s * 0.0375, 0.03, 0]) for s in (-1, 1)] + [
        ([0.08, 0.06, 0.005], [0, 0.03, s * 0.0375]) for s in (-1, 1)]
    box = trimesh.util.concatenate([trimesh.creation.box(e, np.array(
        [[1, 0, 0, p[0]], [0, 1, 0, p[1]], [0, 0, 1, p[2]], [0, 0, 0, 1]])) for e, p in walls])
    box.export(HERE / "put" / "smallbox.obj")


if __name__ == "__main__":
    main()
