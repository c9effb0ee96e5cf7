"""Collision-free reach motion (issue 16 acceptance): a hand reaching into a box through a 15 cm
hole in its side (examples/box_reach). The planned motion (OMPL RRT-Connect, seeded) is free on
every frame at 5 mm steps of hand travel, checked here by a clearance checker of its own (full-size
segments, no contact at all) and ends within 1 cm of the target; the straight ways there collide:
the joint-space line to the same goal posture and the IK following the hand's straight line."""

from __future__ import annotations

import copy
import json
from pathlib import Path

import numpy as np
import pytest

from jackpy import ik
from jackpy.analysis.clearance import ClearanceChecker
from jackpy.body.human import make_human
from jackpy.cli import main
from jackpy.motion import motion_file
from jackpy.planning.reach_motion import frames_at_hand_steps, plan_reach_motion, straight_line
from jackpy.scene.workplace import load_workplace, resolve_target, stand_figure

BOX = Path(__file__).resolve().parents[2] / "examples" / "box_reach" / "box_reach.json"


@pytest.fixture(scope="module")
def scene():
    wp = load_workplace(BOX)
    f = make_human("male", 50)
    stand_figure(f, wp.stand)
    _, target = resolve_target(wp.env, "box.inside")
    return wp, f, target


@pytest.fixture(scope="module")
def planned(scene):
    wp, f, target = scene
    q_before = f.q.copy()
    m = plan_reach_motion(f, target, "right", list(wp.objects.values()), seed=0, time_limit=600.0)  # never the limit
    assert np.array_equal(f.q, q_before)  # the caller's figure is not moved
    return m


def _check(figure, objects, postures) -> tuple[list[tuple[int, list]], np.ndarray]:
    """(frame, touching pairs) for every posture in which any segment touches any object, and the
    hand's position in every posture."""
    c = copy.deepcopy(figure)
    checker = ClearanceChecker(c, objects, self_collision=False)
    out, hand = [], []
    for k, p in enumerate(postures):
        p.apply(c, root=tuple(figure.root))
        checker.update()
        hand.append(c.site_world("right_palm", "grip")[:3, 3].copy())
        hits = checker.object_collisions()
        if hits:
            out.append((k, hits))
    return out, np.array(hand)


def test_planned_motion_is_free_at_5_mm_steps_and_ends_at_the_target(scene, planned):
    wp, f, target = scene
    assert planned.planned, planned.status
    touching, hand = _check(f, list(wp.objects.values()), planned.postures())
    assert touching == []
    assert np.linalg.norm(np.diff(hand, axis=0), axis=1).max() <= 0.005 + 1e-9
    assert np.linalg.norm(hand[0] - f.site_world("right_palm", "grip")[:3, 3]) < 1e-9  # starts where it stands
    assert np.linalg.norm(hand[-1] - target) <= 0.01
    x = planned.frames
    assert np.all(x >= planned.space.lower - 1e-9) and np.all(x <= planned.space.upper + 1e-9)


def test_without_the_planner_the_straight_ways_collide(scene, planned):
    wp, f, target = scene
    objs = list(wp.objects.values())
    # the joint-space straight line from the start to the planner's own goal posture
    space = planned.space
    line = frames_at_hand_steps(space, straight_line(space, planned.waypoints[-1]))
    hits, _ = _check(f, objs, planned.postures(line))
    assert hits and any(b == "box" for _, pairs in hits for _, b in pairs)
    # the IK following the hand's straight line to the target in 5 mm steps
    c = copy.deepcopy(f)
    start = c.site_world("right_palm", "grip")[:3, 3].copy()
    n = int(np.ceil(np.linalg.norm(target - start) / 0.005))
    checker = ClearanceChecker(c, objs, self_collision=False)
    collided = False
    for u in np.linspace(0.0, 1.0, n + 1)[1:]:
        problem = ik.Problem(c)
        problem.add(ik.Position("right_palm.grip", start + u * (target - start), chain="right_clavicle"))
        ik.solve(problem, max_iterations=50)
        checker.update()
        if checker.object_collisions():
            collided = True
            break
    assert collided


def test_motion_file_plays_the_plan(scene, planned, tmp_path):
    _, f, _ = scene
    mf = planned.motion_file(fps=30.0, speed=0.5)
    path = tmp_path / "reach.motion.json"
    motion_file.save(mf, path)
    back = motion_file.load(path)
    baked = back.baked[f.name]
    assert baked.n_frames >= planned.hand_travel / 0.5 * 30
    c = copy.deepcopy(f)
    baked.posture(c, baked.n_frames - 1).apply_to(c)
    assert np.linalg.norm(c.site_world("right_palm", "grip")[:3, 3] - planned.hand[-1]) < 1e-6


def test_timeline_plays_the_plan(planned):
    """The motion file's timeline holds joint key tracks of the arm; baked through the behaviors
    (the workbench's player does this) the hand follows the plan within 2 cm (balance moves the
    body a little)."""
    from jackpy.motion import cast
    from jackpy.motion.bake import Baker

    tl = planned.motion_file(fps=30.0, human="male:50").timeline
    assert sorted(t.part for t in tl.tracks) == sorted(f"joint:{j}" for j in planned.space.joints)
    env, loops = cast.build(tl, scene=BOX)
    (name, loop), = loops.items()
    frames = Baker(tl, loops, env, fps=30.0).bake()
    planned_hand = planned.space.hand_positions(planned.timed(30.0, 0.5))
    fig = loop.figure
    errors = []
    for fr, want in zip(frames, planned_hand):
        fr[name].apply_to(fig)
        errors.append(np.linalg.norm(fig.site_world("right_palm", "grip")[:3, 3] - want))
    assert len(errors) >= len(planned_hand) - 1 and max(errors) < 0.02


def test_reach_command_plans(tmp_path, capsys):
    rc = main(["reach", str(BOX), "--figure", "male:50", "--target", "box.inside", "--plan", "--time-limit", "600",
               "-o", str(tmp_path)])
    assert rc == 0
    res = json.loads((tmp_path / "reach.json").read_text())
    assert res["motion"]["status"] == "planned" and res["motion"]["shortfall_m"] <= 0.01
    assert (tmp_path / "reach.motion.json").exists()
    assert "planned reach motion" in capsys.readouterr().out


def test_reach_command_refuses_a_bad_time_limit(tmp_path, capsys):
    with pytest.raises(SystemExit) as exc:
        main(["reach", str(BOX), "--target", "box.inside", "--plan", "--time-limit", "0", "-o", str(tmp_path)])
    assert exc.value.code == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]  # argparse's usage, then one line
    assert last == "jackpy reach: error: argument --time-limit: must be > 0, not 0"
