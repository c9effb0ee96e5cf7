"""A fuller face on the generated head: reshapes the front of :func:`jackpy.body.shapes._head`'s mesh.

The generated head's face read as crude (a V-shaped jaw ending in a point, eyeballs standing out of
shallow sockets, no mouth). This moves the head's vertices in the zero-pose frame (m, front +z),
scaled by stature, leaving the cranium, its top (the stature landmark) and the back alone:

- jaw: the lower face widened toward a rounded, squarer chin (up to 34 % at the chin);
- brow ridge and cheekbones forward around the eyes, so the eyeballs sit in sockets;
- the chin tip rounded back a few millimetres; fuller lips with a mouth line between them.

The amounts are a [proposal] judged by eye on the 5th-95th percentile figures (docs/workbench.md).
"""

from __future__ import annotations

import numpy as np

from jackpy.peabody.geometry import Mesh


def refine_face(head: Mesh, stature: float, view: np.ndarray, eyes_breadth: float) -> Mesh:
    """``head`` (zero-pose world frame, m) with the face reshaped (module docstring); ``view`` is
    the point between the eyes, ``eyes_breadth`` the distance between the pupils (m)."""
    v = head.vertices.copy()
    s = stature / 1.756
    lo, hi = v.min(axis=0), v.max(axis=0)
    cx, cz = 0.5 * (lo[0] + hi[0]), 0.5 * (lo[2] + hi[2])
    x, y, z = v[:, 0] - cx, v[:, 1], v[:, 2]
    front = np.clip((z - cz) / (hi[2] - cz), 0.0, 1.0)  # 0 at the ears' plane, 1 at the nose tip
    eye_y, eb = float(view[1]), 0.5 * eyes_breadth

    def bump(x0: float, y0: float, ex: float, ey: float) -> np.ndarray:
        return np.exp(-0.5 * (((x - x0) / ex) ** 2 + ((y - y0) / ey) ** 2))

    # a wider, squarer jaw: from the mouth down, the sides move out (not the back of the head)
    jaw = np.clip((eye_y - 0.03 * s - y) / (0.08 * s), 0.0, 1.0)
    jaw = jaw * jaw * (3 - 2 * jaw)
    v[:, 0] = cx + x * (1.0 + 0.34 * jaw * np.clip(2.0 * front, 0.0, 1.0))
    # the chin's point rounded back, and lifted a little
    chin = bump(0.0, lo[1] + 0.012 * s, 0.022 * s, 0.014 * s) * front ** 2
    v[:, 2] -= 0.004 * s * chin
    # brow ridge over both eyes and cheekbones under them, forward
    for sx in (1.0, -1.0):
        v[:, 2] += front ** 2 * s * (0.007 * bump(sx * eb, eye_y + 0.018 * s, 0.021 * s, 0.0095 * s)
                                     + 0.006 * bump(sx * 1.1 * eb, eye_y - 0.026 * s, 0.017 * s, 0.011 * s))
    # fuller lips with a mouth line between them
    lips = (0.003 * bump(0.0, eye_y - 0.069 * s, 0.02 * s, 0.005 * s)
            + 0.003 * bump(0.0, eye_y - 0.087 * s, 0.018 * s, 0.006 * s)
            - 0.004 * bump(0.0, eye_y - 0.078 * s, 0.021 * s, 0.0022 * s))
    v[:, 2] += s * front ** 4 * lips
    return Mesh(v, head.faces)
