"""Reach with both hands, look at a point and stay balanced; then drag one hand (runs in < 1 s).

    python examples/ik_reach.py
"""

import numpy as np

from jackpy import ik
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import rotation, translation

figure = human_like_tree()  # 136 DOFs, pelvis root 1 m above the floor, y up, metres
problem = ik.Problem(figure)

# the left hand onto a frame in front of the chest, palm turned (orientation counts 1 cm per degree)
left = problem.add(ik.PositionOrientation(
    "palm_left.tip", translation(0.25, 1.25, 0.35) @ rotation("x", -1.2), chain="spine1",
    cx=ik.unit_factor(1.0, 0.01)))
# the right hand only to a point; the head looks at it; the centre of mass stays over the pelvis
problem.add(ik.Position("palm_right.tip", (-0.2, 1.3, 0.4), chain="spine1"))
problem.add(ik.Aim("head.tip", (-0.2, 1.3, 0.4), axis=(0, 0, 1), chain="spine1"))
problem.add(ik.CentreOfMass(figure.centre_of_mass()))

result = ik.solve(problem)
print(result)

# interactive drag: move the left-hand goal 5 mm per frame, warm-starting from the last posture
for frame in range(20):
    target = left.target.copy()
    target[:3, 3] += (0.005, 0.0, 0.0)
    left.target = target
    r = ik.solve(problem, max_iterations=20)
print(f"after dragging 10 cm: {r.status}, left hand off by {r.goals[0].metres * 1e3:.3f} mm")
print("left palm now at", np.round(figure.site_world("palm_left", "tip")[:3, 3], 4))
