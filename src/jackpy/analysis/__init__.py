"""jackpy.analysis: reach (workspace volumes, point reach), view (eye view, cones, visibility),
collision and clearance, static torques and strength, and the workplace report."""

from jackpy.analysis.clearance import Clearance, ClearanceChecker
from jackpy.analysis.parts import Eyes, Hand, Parts, figure_parts
from jackpy.analysis.reach import PointReach, point_reach
from jackpy.analysis.statics import GRAVITY, Load, joint_torques
from jackpy.analysis.strength import (
    DofStrength, StrengthBar, dof_strengths, joint_utilisation, strength_bars, strength_colour,
    torque_vertex_colours, utilisation,
)
from jackpy.analysis.surface import mesh_volume, surface_nets
from jackpy.analysis.view import (
    VIEW_CONES, EyeView, Visibility, environment_bodies, eye_view, figure_bodies, object_visibility,
    point_visibility,
)
from jackpy.analysis.workspace import Chain, Progress, Workspace, reachable_workspace

__all__ = ["Chain", "Clearance", "ClearanceChecker", "DofStrength", "EyeView", "Eyes", "GRAVITY", "Hand", "Load",
           "Parts", "PointReach", "Progress", "StrengthBar", "VIEW_CONES", "Visibility", "Workspace",
           "dof_strengths", "environment_bodies", "eye_view", "figure_bodies", "figure_parts", "joint_torques",
           "joint_utilisation", "mesh_volume", "object_visibility", "point_reach", "point_visibility",
           "reachable_workspace", "strength_bars", "strength_colour", "surface_nets", "torque_vertex_colours",
           "utilisation"]
