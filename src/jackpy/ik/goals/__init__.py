"""Goal types, one per module: each gives a residual and its analytic Jacobian (book §3.5).

Every class with a ``kind`` registers itself in :data:`GOAL_TYPES` when it is defined; importing
this package defines the built-in ones. A new goal type is one module here (imported below) or in
any module the program imports.
"""

from jackpy.ik.goals.base import GOAL_TYPES, Chain, Context, Goal, GoalEval, SiteGoal, unit_factor
from jackpy.ik.goals.aim import Aim
from jackpy.ik.goals.com import CentreOfMass
from jackpy.ik.goals.combine import AllOf, AnyOf
from jackpy.ik.goals.distance import Distance
from jackpy.ik.goals.half_space import HalfSpace
from jackpy.ik.goals.line import Line
from jackpy.ik.goals.orientation import Orientation
from jackpy.ik.goals.plane import Plane
from jackpy.ik.goals.position import Position
from jackpy.ik.goals.position_orientation import PositionOrientation

__all__ = ["GOAL_TYPES", "Aim", "AllOf", "AnyOf", "CentreOfMass", "Chain", "Context", "Distance", "Goal", "GoalEval",
           "HalfSpace", "Line", "Orientation", "Plane", "Position", "PositionOrientation", "SiteGoal", "unit_factor"]
