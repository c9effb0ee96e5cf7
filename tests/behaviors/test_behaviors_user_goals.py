"""User goals solved together with the behaviors (BehaviorLoop.add_user_goal): the pass they go
to, planted feet above them, reuse of compiled problems, removal."""

import numpy as np
import pytest

from jackpy.behaviors import BehaviorLoop
from jackpy.behaviors import manipulation as m
from jackpy.behaviors.anatomy import human_anatomy
from jackpy.body.human import make_human
from jackpy.ik.goals import Aim, HalfSpace, Position

ELBOW = ("right_upper_arm", "elbow")
PALM = ("right_palm", "palm_centre")
DRAG = np.array([0.15, 0.2, 0.35])  # up, forward and inwards: the elbow swings out on its own


@pytest.fixture(scope="module")
def human():
    return make_human("male", 50)


def make_loop(human):
    import copy

    fig = copy.deepcopy(human)
    loop = BehaviorLoop(fig, human_anatomy(fig))
    for side in ("left", "right"):
        m.set_foot_behavior(loop, side, mode="hold")
    return fig, loop


def feet(fig):
    return {s: fig.site_world(f"{s}_foot", "ball").copy() for s in ("left", "right")}


def drag_hand(loop, fig, frames=40, settle=15):
    h0 = fig.site_world(*PALM)[:3, 3].copy()
    worst_x = np.inf
    for k in range(frames):
        m.move_hand(loop, "right", position=h0 + (k + 1) / frames * DRAG, lean=True)
        loop.step()
        worst_x = min(worst_x, fig.site_world(*ELBOW)[0, 3])
    m.end_drag(loop)
    for _ in range(settle):
        loop.step()
    return h0 + DRAG, worst_x


def test_half_space_on_the_elbow_holds_while_the_hand_is_dragged(human):
    fig, loop = make_loop(human)
    feet0 = feet(fig)
    e0 = fig.site_world(*ELBOW)[:3, 3].copy()
    u = loop.add_user_goal(HalfSpace("right_upper_arm.elbow", e0, [1.0, 0.0, 0.0], name="elbow in"))
    assert u.part == "right"  # a chain from the root through the arm: the arm moves it
    target, worst_x = drag_hand(loop, fig, settle=30)
    # while dragging the hand and the elbow trade by weight (same level); free, the elbow swings
    # 6 cm out (next test); settled, both hold
    assert worst_x > e0[0] - 0.02
    assert fig.site_world(*ELBOW)[0, 3] > e0[0] - 2e-3
    assert np.linalg.norm(fig.site_world(*PALM)[:3, 3] - target) < 2e-3
    for s, w in feet(fig).items():
        assert np.allclose(w, feet0[s], atol=1e-5)
    assert "user" in loop.step().errors


def test_without_the_goal_the_elbow_swings_out_and_removing_it_restores_that(human):
    fig, loop = make_loop(human)
    e0 = fig.site_world(*ELBOW)[:3, 3].copy()
    _, free_x = drag_hand(loop, fig)
    assert free_x < e0[0] - 0.05  # the region the user goal keeps the elbow out of
    fig2, loop2 = make_loop(human)
    loop2.add_user_goal(HalfSpace("right_upper_arm.elbow", e0, [1.0, 0.0, 0.0]), key="elbow")
    loop2.remove_user_goal("elbow")
    assert loop2.user_goals == []
    _, x2 = drag_hand(loop2, fig2)
    assert x2 == pytest.approx(free_x, abs=0.01)
    assert "user" not in loop2.step().errors


def test_head_aim_holds_while_the_hand_moves_and_feet_stay(human):
    fig, loop = make_loop(human)
    feet0 = feet(fig)
    view = fig.site_world("head", "view")
    point = view[:3, 3] + np.array([0.5, 0.3, 1.0])  # up and to the figure's left
    u = loop.add_user_goal(Aim("head.view", point, axis=(0, 0, 1), name="look"), key="look")
    assert u.part == "head"
    drag_hand(loop, fig)
    w = fig.site_world("head", "view")
    d = (point - w[:3, 3]) / np.linalg.norm(point - w[:3, 3])
    assert np.degrees(np.arccos(np.clip(w[:3, 2] @ d, -1, 1))) < 1.0
    for s, f in feet(fig).items():
        assert np.allclose(f, feet0[s], atol=1e-5)
    # disabled: the head is left alone again (no aim goal in the problem)
    loop.set_user_goal("look", enabled=False)
    loop.step()
    assert all(g is not u.goal for g, _ in loop._problems["limbs"][1]._entries)


def test_body_goals_sit_below_the_planted_feet(human):
    fig, loop = make_loop(human)
    feet0 = feet(fig)
    pelvis = fig.site_world("pelvis", "centre")[:3, 3]
    u = loop.add_user_goal(Position("pelvis.centre", pelvis + [0.0, -0.6, 0.8], weight=100.0), level=0)
    assert u.part == "body"
    for _ in range(20):
        loop.step()
    levels = {g: lv for g, lv in loop._problems["body"][1]._entries}
    feet_level = loop.behavior("feet").params.level
    assert levels[u.goal] == feet_level + 1
    assert fig.site_world("pelvis", "centre")[1, 3] < pelvis[1] - 0.02  # honoured as far as it can be
    for s, f in feet(fig).items():
        assert np.allclose(f[:3, 3], feet0[s][:3, 3], atol=1e-4)


def test_compiled_problems_are_reused_until_the_set_of_goals_changes(human):
    fig, loop = make_loop(human)
    e0 = fig.site_world(*ELBOW)[:3, 3].copy()
    loop.add_user_goal(HalfSpace("right_upper_arm.elbow", e0, [1.0, 0.0, 0.0]), key="elbow")
    h0 = fig.site_world(*PALM)[:3, 3].copy()
    m.move_hand(loop, "right", position=h0 + [0.0, 0.1, 0.2])
    loop.step()
    first = loop._problems["limbs"][1]
    comp = first.compile()
    for k in range(5):
        m.move_hand(loop, "right", position=h0 + [0.0, 0.1 + 0.02 * k, 0.2])
        loop.set_user_goal("elbow", weight=2.0 + k)  # a weight is read at evaluation: no recompile
        loop.user_goal("elbow").goal.point = e0 + [0.001 * k, 0, 0]  # nor is a target
        loop.step()
        assert loop._problems["limbs"][1] is first and first.compile() is comp
    loop.set_user_goal("elbow", level=1)
    loop.step()
    assert loop._problems["limbs"][1] is not first


def test_bad_arguments():
    fig = make_human("male", 50)
    loop = BehaviorLoop(fig, human_anatomy(fig))
    g = HalfSpace("right_upper_arm.elbow", [0, 0, 0], [1, 0, 0])
    with pytest.raises(ValueError):
        loop.add_user_goal(g, part="legs")
    with pytest.raises(ValueError):
        loop.add_user_goal(g, level=-1)
    with pytest.raises(KeyError):
        loop.remove_user_goal("nothing")
    u = loop.add_user_goal(g, chain=["right_shoulder", "right_elbow"])
    assert g.chain == ["right_shoulder", "right_elbow"] and u.part == "right"
    assert loop.add_user_goal(Position("pelvis.centre", [0, 1, 0]), part="body").part == "body"
