"""The picture of a staged reach's final posture (issue 16: "the report records which stage
succeeded and the final posture's picture"): the workplace and the figure in that posture, seen from
above, three-quarters in front of the figure, the target marked as a small red ball."""

from __future__ import annotations

import io

import numpy as np
import trimesh

from jackpy.analysis.reach import Posture
from jackpy.analysis.view import environment_bodies, figure_bodies
from jackpy.peabody.model import Environment, Figure
from jackpy.render.bodies import Body, BodyRenderer, look_at, perspective_matrix

SIZE = (640, 480)


def posture_picture(env: Environment, figure: Figure, posture: Posture | None, target: np.ndarray) -> bytes:
    """PNG bytes of ``figure`` (world frame, metres) in ``posture`` (its current one when None)
    among the objects of ``env``, with the target (world point) marked. The figure is left in
    that posture. Raises :class:`jackpy.errors.JackpyError` where offscreen GL is unavailable."""
    from PIL import Image

    if posture is not None:
        posture.apply(figure)
    ball = trimesh.creation.icosphere(subdivisions=2, radius=0.025)
    marker = Body("target", ball, _translation(target), (0.9, 0.1, 0.1, 1.0))
    bodies = [b for b in environment_bodies(env) if b.name.split(".")[0] != figure.name]
    bodies += figure_bodies(figure) + [marker]
    pts = np.vstack([b.mesh.vertices @ b.model[:3, :3].T + b.model[:3, 3] for b in bodies])
    centre = (pts.min(axis=0) + pts.max(axis=0)) / 2
    radius = float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0))) / 2
    facing = figure.location[:3, 2] * np.array([1.0, 0.0, 1.0])  # the figure's forward (+z) on the floor
    facing = facing / (np.linalg.norm(facing) or 1.0)
    side = np.cross(np.array([0.0, 1.0, 0.0]), facing)
    direction = 0.75 * facing + 0.65 * side + np.array([0.0, 1.1, 0.0])  # from above: over screens
    eye = centre + radius * 2.0 * direction / np.linalg.norm(direction)
    renderer = BodyRenderer(SIZE)
    try:
        rgb = renderer.render(bodies, look_at(eye, centre),
                              perspective_matrix(np.radians(40), SIZE[0] / SIZE[1], 0.05, radius * 6))
    finally:
        renderer.release()
    buf = io.BytesIO()
    Image.fromarray(rgb).save(buf, format="PNG")
    return buf.getvalue()


def _translation(p: np.ndarray) -> np.ndarray:
    m = np.eye(4)
    m[:3, 3] = p
    return m
