"""The support polygon is the actual contact patch: sole corners within CONTACT_HEIGHT (4 mm) of
the foot's lowest point (issue 19 item 7). A foot tilted 5 deg about its heel (ball corners 1.7 cm up, inside the old 2 cm band) keeps only the heel
corners; a flat foot keeps all six."""

import numpy as np

import jackpy.body.human as body
from jackpy.behaviors import BehaviorLoop
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.behaviors.loop import CONTACT_HEIGHT
from jackpy.behaviors.support import floor
from jackpy.peabody.transforms import rotation


def _loop() -> BehaviorLoop:
    f = body.make_human("male", 50)
    return BehaviorLoop(f, human_anatomy(f))


def _tilted_about_heel(lp: BehaviorLoop, side: str, deg: float) -> np.ndarray:
    """Ball-site pose of foot ``side`` rotated ``deg`` toes-up about the lateral axis at its heel."""
    t = lp.state.feet[side].target.copy()
    heel = lp.heel_point(side, t)
    spec = lp.anatomy.feet[side]
    loc = lp.figure.site_location(*spec.ball)
    fwd = t[:3, :3] @ (loc[:3, :3].T @ spec.forward)
    lateral = np.cross(np.array([0.0, 1.0, 0.0]), fwd)
    r = np.eye(4)
    r[:3, :3] = rotation(lateral / np.linalg.norm(lateral), np.radians(deg))[:3, :3]
    about = np.eye(4)
    about[:3, 3] = heel
    back = np.eye(4)
    back[:3, 3] = -heel
    out = about @ r @ back @ t
    corners = (lp._footprints[side] @ out[:3, :3].T + out[:3, 3])[:-1]
    if corners[:, 1].min() < heel[1] - 1e-9:  # rotated the wrong way: toes went down
        out = about @ r.T @ back @ t
    return out


def test_contact_height_is_a_few_mm():
    assert 0.002 <= CONTACT_HEIGHT <= 0.005


def test_flat_feet_contact_every_sole_corner():
    lp = _loop()
    targets = {s: f.target for s, f in lp.state.feet.items()}
    bf = lp.balance_frame_for(targets)
    corners = np.vstack([floor((lp._footprints[s] @ t[:3, :3].T + t[:3, 3])[:-1]) for s, t in targets.items()])
    for c in corners:  # every corner of both soles is on the hull or inside it
        assert bf.margin(c) <= 1e-9


def test_lifted_toes_leave_the_support_polygon():
    lp = _loop()
    targets = {s: f.target for s, f in lp.state.feet.items()}
    targets["right"] = _tilted_about_heel(lp, "right", 5.0)
    tilted = lp.balance_frame_for(targets)
    right = lp._footprints["right"] @ targets["right"][:3, :3].T + targets["right"][:3, 3]
    ball = targets["right"][:3, 3]
    lift = right[2:4, 1].min() - right[:-1, 1].min()  # rows: heel, ball, toe corners (+- width)
    assert 0.01 < lift < 0.02  # the ball corners are lifted 1-2 cm: inside the old 2 cm band
    assert tilted.margin(floor(lp.heel_point("right", targets["right"]))) <= 1e-9  # heel bears
    assert tilted.margin(floor(ball)) > 0.02  # the lifted ball is well outside the contact patch
