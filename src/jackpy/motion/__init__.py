"""Motion over time: timed motions, keyframes, baking, the motion file, BVH/glTF in and out,
URDF/MJCF export of a figure's kinematic tree.

Submodules are imported by name (``jackpy.motion.model``, ``jackpy.motion.bvh``, ...); this
package's ``__init__`` imports nothing so that one part can be used without the others.
"""
