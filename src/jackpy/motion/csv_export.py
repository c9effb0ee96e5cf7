"""CSV export of baked motion: one row per frame, ``time_s``, the root site's world position (m)
and rotation (quaternion x, y, z, w), then every DOF (``joint.k``, radians or metres)."""

from __future__ import annotations

import csv
import io
import os

from scipy.spatial.transform import Rotation

from jackpy.atomic import atomic_write_text


def write_csv(figure, baked, fps: float, path: str | os.PathLike) -> None:
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["time_s", "root", "x_m", "y_m", "z_m", "qx", "qy", "qz", "qw", *baked.dofs])
    for i in range(baked.n_frames):
        loc = baked.location[i]
        q = Rotation.from_matrix(loc[:3, :3]).as_quat()
        w.writerow([repr(i / fps), baked.roots[int(baked.root[i])], *(repr(float(v)) for v in loc[:3, 3]),
                    *(repr(float(v)) for v in q), *(repr(float(v)) for v in baked.q[i])])
    atomic_write_text(path, out.getvalue())
