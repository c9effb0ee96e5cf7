"""jackpy.behaviors: the per-frame behavior loop and Jack's behaviors (book ch. 4; PB91).

See docs/behaviors.md. :class:`BehaviorLoop` runs the behaviors of :func:`default_behaviors` and the
IK each frame; :mod:`jackpy.behaviors.manipulation` holds the commands a workbench drag calls.
"""

from __future__ import annotations

from jackpy.behaviors.anatomy import Anatomy, synthetic_anatomy
from jackpy.behaviors.auto_root import AutoRoot, AutoRootParams
from jackpy.behaviors.balance import Balance, BalanceParams
from jackpy.behaviors.base import Behavior, BehaviorBase, ParamSpec, describe
from jackpy.behaviors.feet import Feet, FeetParams
from jackpy.behaviors.gaze import Gaze, GazeParams
from jackpy.behaviors.hands import Hands, HandsParams
from jackpy.behaviors.limit_springs import LimitSprings, LimitSpringsParams
from jackpy.behaviors.loop import BehaviorLoop, Frame, FrameReport
from jackpy.behaviors.pelvis import Pelvis, PelvisParams
from jackpy.behaviors.seat import Seat, SeatParams
from jackpy.behaviors.stepping import Stepping, SteppingParams
from jackpy.behaviors.torso import Torso, TorsoParams


def default_behaviors() -> list[Behavior]:
    """One instance of every behavior with default parameters, in frame order."""
    return [AutoRoot(), Seat(), Feet(), Pelvis(), Balance(), Stepping(), Torso(), Gaze(), Hands(),
            LimitSprings()]


__all__ = ["Anatomy", "AutoRoot", "AutoRootParams", "Balance", "BalanceParams", "Behavior", "BehaviorBase",
           "BehaviorLoop", "Feet", "FeetParams", "Frame", "FrameReport", "Gaze", "GazeParams", "Hands",
           "HandsParams", "LimitSprings", "LimitSpringsParams", "ParamSpec", "Pelvis", "PelvisParams", "Seat",
           "SeatParams", "Stepping", "SteppingParams", "Torso", "TorsoParams", "default_behaviors", "describe",
           "synthetic_anatomy"]
