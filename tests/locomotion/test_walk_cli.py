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
