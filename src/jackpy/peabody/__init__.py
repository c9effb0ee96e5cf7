"""The Peabody figure graph (book §2.2): figures, segments, sites, joints, groups, kinematics."""

from jackpy.peabody.geometry import Mesh, Psurf
from jackpy.peabody.groups import JointGroup, LinearDriver, VariableMap
from jackpy.peabody.kinematics import FKResult, Kinematics
from jackpy.peabody.model import Dof, Environment, Figure, Joint, Segment, Site

__all__ = ["Dof", "Environment", "FKResult", "Figure", "Joint", "JointGroup", "Kinematics",
           "LinearDriver", "Mesh", "Psurf", "Segment", "Site", "VariableMap"]
