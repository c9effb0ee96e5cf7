"""A strength-guided lift as a baked motion (``NAME.motion.json``, :mod:`jackpy.motion.motion_file`).

The lift's iterations carry times from its rate model (:mod:`jackpy.planning.lifting`); the motion
samples them at ``fps``, interpolating the joint displacements linearly between iterations (the
steps are at most 2° per joint, so the interpolated postures stay on the path to well under a
millimetre of hand travel). The root (the pelvis) does not move.
"""

from __future__ import annotations

import numpy as np

from jackpy.motion.bake import Posture
from jackpy.motion.motion_file import BakedFigure, MotionFile
from jackpy.motion.timeline import Timeline
from jackpy.peabody.model import Figure
from jackpy.planning.lifting import LiftResult


def sample_times(result: LiftResult, fps: float) -> np.ndarray:
    """Frame times (s) 0, 1/fps, ... to the first at or after the lift's end (which holds the
    final posture)."""
    end = float(result.frames[-1].t)
    return np.arange(int(np.ceil(end * fps - 1e-9)) + 1) / fps


def lift_postures(figure: Figure, result: LiftResult, fps: float) -> list[Posture]:
    """The figure's postures at :func:`sample_times` (root and location of ``figure``)."""
    times = result.times
    qs = np.array([f.q for f in result.frames])
    root = None if figure.root is None else tuple(figure.root)
    out = []
    for t in sample_times(result, fps):
        k = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 1))
        if k + 1 < len(times) and times[k + 1] > times[k]:
            a = (t - times[k]) / (times[k + 1] - times[k])
            q = (1.0 - a) * qs[k] + a * qs[k + 1]
        else:
            q = qs[k]
        out.append(Posture(q.copy(), root, figure.location.copy()))
    return out


def lift_motion(figure: Figure, result: LiftResult, fps: float = 30.0, human: str | None = None) -> MotionFile:
    """A motion file with the lift baked at ``fps`` for ``figure`` (the figure the lift started
    from; ``human`` e.g. ``"male:50"`` names the standard human in the file)."""
    postures = lift_postures(figure, result, fps)
    tl = Timeline()
    tl.duration = (len(postures) - 1) / fps
    return MotionFile(tl, fps, {figure.name: BakedFigure.from_postures(figure, postures, human)})
