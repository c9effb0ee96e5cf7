"""The one renderer: plain-data scenes drawn with moderngl, for the window, ``jackpy screenshot``,
report pictures and ID-buffer visibility alike.

Input is a :class:`Scene` of draw items (cached meshes with transforms), skeleton spheres and
sticks, frame triads, goal markers and lines; output is an anti-aliased image, readable as pixels,
and an ID buffer (one pixel for picking, the whole frame for visibility). :mod:`jackpy.render.bodies`
draws lists of meshes (analyses, reports) through the same renderer; :mod:`jackpy.render.projection`
holds the camera matrices. Nothing here knows about figures or windows.
"""

from jackpy.render.bodies import Body, BodyRenderer
from jackpy.render.image import write_png
from jackpy.render.mesh import Mesh, arrow, box, cone, cylinder, lathe, uv_sphere, vertex_normals
from jackpy.render.offscreen import create_egl_context, offscreen_renderer
from jackpy.render.projection import linear_depth, look_at, orthographic_matrix, perspective_matrix
from jackpy.render.renderer import Renderer
from jackpy.render.scene import DrawItem, GoalMarker, Grid, Lines, Scene, SkinnedItem, Spheres, Sticks, Triad
from jackpy.render.skinning import SkinnedMesh

__all__ = [
    "Body", "BodyRenderer", "DrawItem", "GoalMarker", "Grid", "Lines", "Mesh", "Renderer", "Scene", "SkinnedItem",
    "SkinnedMesh", "Spheres",
    "Sticks", "Triad", "arrow", "box", "cone", "create_egl_context", "cylinder", "lathe", "linear_depth", "look_at",
    "offscreen_renderer", "orthographic_matrix", "perspective_matrix", "uv_sphere", "vertex_normals", "write_png",
]
