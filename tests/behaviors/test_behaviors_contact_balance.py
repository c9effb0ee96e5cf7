"""Acceptance (issue 19 item 7): 500 frames of random hand drags and forced steps on the standard
human; the COM's floor point never leaves the *actual* contact region (the convex hull of the sole
vertices within 4 mm of the floor, measured from the posed foot surfaces) by more than 1 cm, unless
a step is under way and the COM is over the stance sole."""

import numpy as np
import pytest

from jackpy.behaviors import BehaviorLoop
from jackpy.behaviors import manipulation as m
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.behaviors.support import convex_hull, floor, signed_distance
from jackpy.body.human import make_human
from jackpy.body.measure import surface_points

SOLE_TOLERANCE = 0.004  # m: a sole vertex this close to the floor is in contact
ALLOWED = 0.01  # m


def contact_region(fig, sides=("left", "right")) -> np.ndarray:
    pts = surface_points(fig, [f"{s}_{p}" for s in sides for p in ("foot", "toes")])
    low = pts[pts[:, 1] < SOLE_TOLERANCE]
    return convex_hull(floor(low)) if len(low) else np.zeros((0, 2))


@pytest.mark.timeout(1500)  # 500 full behavior-loop frames (about 60-300 s, by machine load)
def test_com_stays_over_the_actual_contact_through_drags_and_steps():
    rng = np.random.default_rng(3)
    fig = make_human("male", 50)
    lp = BehaviorLoop(fig, human_anatomy(fig))
    violations, steps, side, start, target = [], 0, "left", None, None
    for i in range(500):
        phase = i % 50
        if phase == 0:  # a new random hand drag over 30 frames
            side = "left" if rng.random() < 0.5 else "right"
            shoulder = fig.site_world(f"{side}_upper_arm", "base")[:3, 3]
            target = shoulder + rng.uniform([-0.5, -0.7, 0.1], [0.5, 0.4, 0.9])
            start = fig.site_world(f"{side}_palm", "base")[:3, 3].copy()
        if phase < 30:
            u = (phase + 1) / 30
            m.move_hand(lp, side, position=(1 - u) * start + u * target)
        elif phase == 30:
            m.end_drag(lp)
            if rng.random() < 0.6:  # force a step: drag the COM out past the feet
                b = lp.state.balance_point + rng.uniform(-0.25, 0.25, 2)
                m.move_com(lp, np.array([b[0], 0.0, b[1]]))
        elif phase == 40:
            m.end_drag(lp)
        lp.step()
        com = floor(fig.centre_of_mass())
        outside = signed_distance(com, contact_region(fig))
        step = lp.behavior("stepping").step
        if step is not None:
            stance = "right" if step.side == "left" else "left"
            if signed_distance(com, contact_region(fig, (stance,))) <= ALLOWED:
                continue
        if outside > ALLOWED:
            violations.append((i, round(outside, 4)))
    steps = lp.state.steps_taken
    assert steps >= 2, "the forced drags must make the figure step"
    assert not violations, violations
