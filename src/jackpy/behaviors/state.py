"""The behaviors' persistent state: goals and settings that outlive a frame (the "blackboard").

Manipulation commands and behaviors write it; the loop reads it to build each frame's goals. All
poses are world 4x4 transforms, points world metres, floor points ``(x, z)`` metres.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class FootState:
    """A foot's goal: ``target`` the ball-site pose it is held at (planted feet keep it).

    ``mode``: "pivot" (position, sole flat, yaw free) or "hold" (position and full orientation).
    ``heel``: "floor" keeps the heel on the floor, "free" lets it rise.
    """

    target: np.ndarray
    mode: str = "pivot"
    heel: str = "floor"


@dataclass
class Attachment:
    """An object (any object with a ``pose`` 4x4) carried by a hand at a fixed offset from the palm."""

    obj: object
    offset: np.ndarray


@dataclass
class HandState:
    """A hand's goal for the arm pass: ``goal`` the palm-site pose (None: arm left alone);
    ``orient`` whether the orientation is held; ``lean`` whether an out-of-reach goal may
    recruit the body (lean, then step); ``local`` an object whose motion carries the goal
    (``local_offset`` the goal in its frame); ``rules`` whether the palm-orientation rules pick the
    orientation (set while the user translates the hand); ``region`` the last rule region."""

    goal: np.ndarray | None = None
    orient: bool = True
    lean: bool = False
    local: object | None = None
    local_offset: np.ndarray | None = None
    attached: list[Attachment] = field(default_factory=list)
    rules: bool = False
    region: str = ""
    blending: bool = False


@dataclass
class SeatState:
    """Where a seated figure sits (:mod:`jackpy.behaviors.seat`): the seat plane's and the footrest's
    heights (world y, m), the two seat contacts' world points (2, 3) where they were put down, and
    whether both feet reach the footrest."""

    seat_height: float
    footrest_height: float
    contacts: np.ndarray
    feet_resting: bool = True


@dataclass
class BehaviorState:
    """Everything the behaviors keep between frames."""

    root: str = "left"
    root_claimed: bool = False
    balance: tuple[float, float] = (0.5, 0.0)
    balance_point: np.ndarray = field(default_factory=lambda: np.zeros(2))
    com_drag: np.ndarray | None = None
    feet: dict[str, FootState] = field(default_factory=dict)
    hands: dict[str, HandState] = field(default_factory=dict)
    pelvis_goal: np.ndarray | None = None
    pelvis_user: bool = False
    pelvis_offset: np.ndarray = field(default_factory=lambda: np.zeros(2))
    torso_mode: str = "vertical"
    torso_goal: np.ndarray | None = None
    spine_target: np.ndarray | None = None
    head_target: np.ndarray | None = None
    eyes_target: np.ndarray | None = None
    steps_taken: int = 0
    seat: SeatState | None = None
