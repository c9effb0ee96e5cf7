"""``jackpy walk``: a baked motion file and BVH; one-line errors for bad input."""

from __future__ import annotations

import subprocess
import sys

from jackpy.motion import motion_file


def _walk(*args, cwd):
    return subprocess.run([sys.executable, "-m", "jackpy", "walk", *args], capture_output=True, text=True,
                          cwd=cwd, timeout=600)


def test_walk_path_writes_motion_and_bvh(tmp_path):
    out, bvh = tmp_path / "w.motion.json", tmp_path / "w.bvh"
    r = _walk("-", "--path", "0,0.8", "--fps", "8", "-o", str(out), "--bvh", str(bvh), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    mf = motion_file.load(out)
    assert mf.fps == 8 and mf.n_frames > 10
    assert bvh.read_text().startswith("HIERARCHY")


def test_bad_point_is_one_line_exit_2(tmp_path):
    r = _walk("-", "--to", "1,x", "-o", str(tmp_path / "x.json"), cwd=tmp_path)
    assert r.returncode == 2 and "X,Z" in r.stderr


def test_walk_to_object_plays_on_the_timeline(tmp_path):
    """``--to-object desk``: the figure stops in front of the desk facing it; the file's timeline
    holds the walk as a walk motion, which the workbench's player plays to the same place."""
    from pathlib import Path

    import numpy as np

    from jackpy.document import Document
    from jackpy.motion.kinds.walk import WalkMotion
    from jackpy.motion.player import Player, load_into
    from jackpy.peabody.model import Environment

    scene = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"
    out = tmp_path / "desk.motion.json"
    r = _walk(str(scene), "--from", "0.8,-1.2", "--to-object", "desk", "--fps", "8", "-o", str(out), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    mf = motion_file.load(out)
    (m,) = mf.timeline.motions
    assert isinstance(m, WalkMotion) and m.figure == "walker"
    steps = m.plan["steps"]
    goal = 0.5 * (np.array(steps[-1][:2]) + np.array(steps[-2][:2]))
    # the desk's footprint is x in [-0.6, 0.6], z in [0.3, 1.0]: in front of its near edge, facing +z
    assert -0.6 <= goal[0] <= 0.6 and 0.25 < 0.3 - goal[1] < 0.4 and abs(steps[-1][2]) < np.radians(5)
    doc = Document(Environment())
    load_into(doc, str(out))
    player = Player(doc, fps=8)
    player.scrub(mf.timeline.duration)
    c = doc.env.figures["walker"].site_world("pelvis", "centre")[:3, 3]
    assert np.hypot(c[0] - goal[0], c[2] - goal[1]) < 0.05


def test_unknown_object_is_one_line_exit_2(tmp_path):
    from pathlib import Path

    scene = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"
    r = _walk(str(scene), "--from", "0.8,-1.2", "--to-object", "sofa", "-o", str(tmp_path / "x.json"), cwd=tmp_path)
    assert r.returncode == 2 and "sofa" in r.stderr and r.stderr.count("\n") == 1
    assert not (tmp_path / "x.json").exists()
