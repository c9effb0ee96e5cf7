"""Inverse kinematics: goals, priority levels, the BFGS-with-projection solver, the analytic 7-DOF arm.

    problem = ik.Problem(figure)
    problem.add(ik.Position("palm_left.tip", target, chain="shoulder_left"))
    result = ik.solve(problem)

Knows nothing of humans: sites, chains and joints are named by the caller.
"""

from jackpy.ik.goals import (
                             Aim,
                             AllOf,
                             AnyOf,
                             CentreOfMass,
                             Goal,
                             HalfSpace,
                             Line,
                             Orientation,
                             Plane,
                             Position,
                             PositionOrientation,
                             unit_factor,
)
from jackpy.ik.problem import Problem
from jackpy.ik.result import ACHIEVED, ITERATION_LIMIT, TIME_LIMIT, UNREACHABLE, GoalReport, Result
from jackpy.ik.solver import solve

__all__ = ["ACHIEVED", "ITERATION_LIMIT", "TIME_LIMIT", "UNREACHABLE", "Aim", "AllOf", "AnyOf", "CentreOfMass", "Goal",
           "GoalReport", "HalfSpace", "Line", "Orientation", "Plane", "Position", "PositionOrientation",
           "Problem", "Result", "solve", "unit_factor"]
