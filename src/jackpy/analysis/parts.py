"""The parts of a figure the analyses name: each hand (its reference site and the joint its arm
chain starts at) and the eyes (a point between them, the gaze forward and up in the head's frame).

Recognises :func:`jackpy.body.make_human` (``right_palm.grip`` from ``right_clavicle``,
``head.view``) and :func:`jackpy.peabody.synthetic.human_like_tree` (``palm_right.tip`` from
``clavicle_right``, the midpoint of ``head.eye_left``/``eye_right``). Both face +z with y up in the
head's frame when standing neutral.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from jackpy.errors import FigureError
from jackpy.peabody.model import Figure


@dataclass(frozen=True)
class Hand:
    """A hand's reference point ``segment.site`` and the first joint of its arm chain."""

    segment: str
    site: str
    start_joint: str


@dataclass(frozen=True)
class Eyes:
    """The point between the eyes on ``segment`` (segment frame, metres) and the gaze ``forward``
    and ``up`` unit vectors in that frame."""

    segment: str
    point: np.ndarray
    forward: np.ndarray
    up: np.ndarray

    def world(self, figure: Figure) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(eye point, forward, up) in world coordinates at the figure's posture."""
        t = figure.world_transforms()[self.segment]
        return t[:3, :3] @ self.point + t[:3, 3], t[:3, :3] @ self.forward, t[:3, :3] @ self.up


@dataclass(frozen=True)
class Parts:
    hands: dict[str, Hand]
    eyes: Eyes


def figure_parts(figure: Figure) -> Parts:
    """The hands and eyes of a standard or synthetic human; :class:`FigureError` for other figures."""
    segs = figure.segments
    fwd, up = np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0])
    if "right_palm" in segs and "head" in segs:
        hands = {s: Hand(f"{s}_palm", "grip", f"{s}_clavicle") for s in ("right", "left")}
        eyes = Eyes("head", figure.site_location("head", "view")[:3, 3].copy(), fwd, up)
        return Parts(hands, eyes)
    if "palm_right" in segs and "head" in segs:
        hands = {s: Hand(f"palm_{s}", "tip", f"clavicle_{s}") for s in ("right", "left")}
        mid = (figure.site_location("head", "eye_left")[:3, 3] + figure.site_location("head", "eye_right")[:3, 3]) / 2
        return Parts(hands, Eyes("head", mid, fwd, up))
    raise FigureError(f"figure {figure.name!r}: no recognised hands and eyes (expected the standard "
                      "human's right_palm/left_palm and head.view)")
