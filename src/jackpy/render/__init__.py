"""Rendering foundation of the workbench: plain-data scenes drawn with moderngl.

Input is a :class:`Scene` of draw items (cached meshes with transforms), skeleton spheres and
sticks, frame triads, goal markers and lines; output is an anti-aliased image, readable as
pixels, and an id buffer for picking. Nothing here knows about figures.
"""

from jackpy.render.mesh import Mesh, arrow, box, cone, cylinder, lathe, uv_sphere, vertex_normals
from jackpy.render.image import write_png
from jackpy.render.offscreen import create_egl_context, offscreen_renderer
from jackpy.render.renderer import Renderer
from jackpy.render.scene import DrawItem, GoalMarker, Grid, Lines, Scene, Spheres, Sticks, Triad

__all__ = [
    "DrawItem", "GoalMarker", "Grid", "Lines", "Mesh", "Renderer", "Scene", "Spheres", "Sticks",
    "Triad", "arrow", "box", "cone", "create_egl_context", "cylinder", "lathe", "offscreen_renderer",
    "uv_sphere", "vertex_normals", "write_png",
]
