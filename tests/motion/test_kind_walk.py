"""The walk motion kind (issue 13): a footstep plan on the timeline, baked and played like any
motion, saved with the timeline, the figure's behaviors resuming after it."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy import jsonfile
from jackpy.locomotion import footsteps, walk_path, walk_solve
from jackpy.locomotion.walk_gait import START_TIME, GaitParams
from jackpy.motion import cast, motion_file
from jackpy.motion.bake import Baker
from jackpy.motion.kinds.walk import WalkMotion
from jackpy.motion.timeline import Timeline

FPS = 10.0
SITES = [("left_foot", "ball"), ("right_foot", "heel"), ("right_palm", "base"), ("head", "base")]


def _scene(human="female:5", position=(0.0, 0.0), heading_deg=0.0):
    tl = Timeline(cast={"jack": {"human": human, "position": list(position), "heading_deg": heading_deg}})
    env, loops = cast.build(tl)
    return tl, env, loops, env.figures["jack"]


def _sites(fig) -> np.ndarray:
    return np.array([fig.site_world(*s)[:3, 3] for s in SITES])


def _pelvis_floor(fig) -> np.ndarray:
    return fig.site_world("pelvis", "centre")[:3, 3][[0, 2]]


def test_walk_motion_is_the_baked_walk_frame_for_frame():
    tl, env, loops, fig = _scene()
    p = GaitParams.for_figure(fig)
    steps = footsteps.from_path(p, [(0.0, 0.0), (0.8, 1.2)], facing=0.3)
    m = tl.add(WalkMotion.of_steps("jack", steps, p, label="walk"))
    assert m.t1 == pytest.approx(walk_path.duration(steps, p))
    start = _sites(fig)
    frames = Baker(tl, loops, env, fps=FPS).bake()
    # the walk starts from the figure's own standing feet (taken into the plan) ...
    run = [walk_path.Footstep(*row) for row in m.run["steps"]]
    assert run[2:] == steps[2:] and np.abs(np.array([f.point for f in run[:2]]) -
                                           [f.point for f in steps[:2]]).max() < 0.1
    ref_fig = cast.make_figure("ref", {"human": "female:5"})
    ref, _ = walk_solve.bake(ref_fig, walk_path.Walk(run, p), FPS)
    assert len(frames) == len(ref)
    # ... moves from its posture at t0 into the walk's over the weight shift, without a jump ...
    # (without the blend the palm jumps 11 cm in the first frame; the feet slide a little into place)
    prev, speed = start, 0.0
    for a in frames[:int(START_TIME * FPS) + 1]:
        a["jack"].apply_to(fig)
        speed, prev = max(speed, float(np.linalg.norm(_sites(fig) - prev, axis=1).max()) * FPS), _sites(fig)
    assert speed < 0.75
    assert np.linalg.norm(_sites(fig)[:2] - start[:2], axis=1).max() < 0.025
    # ... and is then the walk baked on its own, frame for frame (within the IK's tolerance)
    worst = 0.0
    for a, b in list(zip(frames, ref))[int(np.ceil(START_TIME * FPS)):]:
        a["jack"].apply_to(fig)
        b.apply_to(ref_fig)
        worst = max(worst, float(np.abs(_sites(fig) - _sites(ref_fig)).max()))
    assert worst < 1e-3
    frames[-1]["jack"].apply_to(fig)
    assert np.linalg.norm(_pelvis_floor(fig) - 0.5 * (steps[-1].point + steps[-2].point)) < 0.05


def test_behaviors_are_suspended_during_the_walk_and_resume_after():
    tl, env, loops, fig = _scene()
    loop = loops["jack"]
    p = GaitParams.for_figure(fig)
    m = tl.add(WalkMotion.of_steps("jack", footsteps.straight(p, 1.0), p, t0=0.2))
    tl.duration = m.t1 + 0.6
    before = [b.enabled for b in loop.behaviors]
    baker = Baker(tl, loops, env, fps=FPS)
    baker.seek(baker.frame_at(1.0))
    running = {b.name for b in loop.behaviors if b.enabled}
    assert running == {"gaze"}
    frames = baker.bake()
    assert [b.enabled for b in loop.behaviors] == before
    assert loop.state.root in ("left", "right")
    # standing after the walk: the feet stay planted while the behaviors run again
    end = baker.frame_at(m.t1) + 1
    frames[end]["jack"].apply_to(fig)
    planted = _sites(fig)[:2]
    frames[-1]["jack"].apply_to(fig)
    assert np.abs(_sites(fig)[:2] - planted).max() < 0.002
    assert _pelvis_floor(fig)[1] == pytest.approx(1.0, abs=0.05)


def test_relative_walk_starts_where_the_figure_stands():
    tl, env, loops, fig = _scene("male:50", (2.0, 1.0), 90.0)
    p = GaitParams.for_figure(fig)
    steps = footsteps.straight(p, 1.5)  # authored at the origin, facing +z
    tl.add(WalkMotion.of_steps("jack", steps, p, relative=True))
    frames = Baker(tl, loops, env, fps=FPS).bake()
    frames[1]["jack"].apply_to(fig)
    assert np.linalg.norm(_pelvis_floor(fig) - [2.0, 1.0]) < 0.03
    frames[-1]["jack"].apply_to(fig)
    assert np.linalg.norm(_pelvis_floor(fig) - [3.5, 1.0]) < 0.05  # heading 90°: +z became +x


def test_walk_motion_round_trips_and_bad_plans_name_the_key(tmp_path):
    tl, env, loops, fig = _scene()
    p = GaitParams.for_figure(fig)
    m = tl.add(WalkMotion.of_steps("jack", footsteps.straight(p, 1.0), p))
    path = tmp_path / "w.motion.json"
    motion_file.save(motion_file.MotionFile(tl, 30.0, {}), path)
    back = motion_file.load(path).timeline.motions[0]
    assert isinstance(back, WalkMotion) and back.plan == m.plan and back.t1 == m.t1
    d = tl.to_dict()
    rows = d["motions"][0]["plan"]["steps"]
    rows[3][3] = rows[2][3]  # two feet of one side in a row
    with pytest.raises(jsonfile.Invalid, match=r"motions\[0\].*footstep 3 is on the same side"):
        Timeline.from_dict(d)
    del d["motions"][0]["plan"]
    with pytest.raises(jsonfile.Invalid, match="needs a plan"):
        Timeline.from_dict(d)


def test_two_walks_of_one_figure_may_not_overlap():
    tl, env, loops, fig = _scene()
    p = GaitParams.for_figure(fig)
    steps = footsteps.straight(p, 1.0)
    tl.add(WalkMotion.of_steps("jack", steps, p))
    with pytest.raises(ValueError, match="may not overlap"):
        tl.add(WalkMotion.of_steps("jack", steps, p, t0=0.5))
