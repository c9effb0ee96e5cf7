"""Acceptance: every public BVH file imports onto the default human and onto a 5th-percentile
woman; planted feet slide < 1 cm per stance; no joint leaves its limits; the walk walks.

The files are retargeted at 10 frames per second here (the importer's default is the file's rate,
at most 30), to keep the suite's time; stance detection and the solve are the same at any rate.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from jackpy.motion import cast
from jackpy.motion.bvh import read
from jackpy.motion.retarget import LANDMARKS, SIDES, choose_map, import_bvh, targets_for

MOCAP = Path("/work/shared/data/mocap")
if not MOCAP.exists():
    MOCAP = Path(__file__).resolve().parents[3] / "shared" / "data" / "mocap"
FILES = sorted(p.name for p in MOCAP.glob("*.bvh"))
FPS = 10.0


def test_all_six_files_are_there():
    assert len(FILES) == 6


@pytest.mark.parametrize("human", ["male:50", "female:5"])
@pytest.mark.parametrize("name", FILES)
def test_import_onto_a_human(name, human):
    path = MOCAP / name
    mf = import_bvh(path, human, fps=FPS)
    fig_name = next(iter(mf.baked))
    baked = mf.baked[fig_name]
    bvh = read(str(path))
    nmap = choose_map(bvh)
    assert baked.n_frames == int(np.floor((bvh.frames.shape[0] - 1 - nmap.skip_frames) / bvh.fps * FPS + 1e-9)) + 1
    assert mf.duration == pytest.approx((baked.n_frames - 1) / FPS)
    fig = cast.make_figure(fig_name, {"human": human})
    tg, _, _ = targets_for(cast.make_figure("ref", {"human": human}), bvh, nmap, FPS)
    lo, hi = fig.lower, fig.upper
    balls = {s: [] for s in SIDES}
    for i in range(baked.n_frames):
        baked.posture(fig, i).apply_to(fig)
        q = fig.q
        assert np.all(q >= lo - 1e-9) and np.all(q <= hi + 1e-9), f"frame {i}: a joint outside its limits"
        for s in SIDES:
            balls[s].append(fig.site_world(*LANDMARKS[f"{s}_ball"])[:3, 3])
    n_stances = 0
    for s in SIDES:
        b = np.array(balls[s])
        for a, e in tg.stance[s]:
            slide = np.linalg.norm((b[a:e + 1] - b[a])[:, [0, 2]], axis=1).max()
            assert slide < 0.01, f"{s} foot slid {slide * 100:.2f} cm in frames {a}-{e}"
            n_stances += 1
    if "walk" in name:
        assert n_stances >= 4


def test_the_walk_walks():
    """cmu_02_01: about 3.4 m straight ahead (scaled to the human), feet in alternating stances,
    the pelvis at a walking height all along."""
    path = MOCAP / "cmu_02_01_walk.bvh"
    mf = import_bvh(path, "female:5", fps=FPS)
    baked = next(iter(mf.baked.values()))
    fig = cast.make_figure("w", {"human": "female:5"})
    stand_hip = fig.site_world("pelvis", "centre")[1, 3]
    pelvis = []
    for i in range(baked.n_frames):
        baked.posture(fig, i).apply_to(fig)
        pelvis.append(fig.site_world("pelvis", "centre")[:3, 3])
    pelvis = np.array(pelvis)
    travel = np.linalg.norm(pelvis[-1, [0, 2]] - pelvis[0, [0, 2]])
    bvh = read(str(path))
    tg, s, _ = targets_for(cast.make_figure("ref", {"human": "female:5"}), bvh, choose_map(bvh), FPS)
    # the capture's 3.4 m (README), in CMU units of 1/0.45 inch, scaled by the size ratio
    assert travel == pytest.approx(3.4 / 0.0564444 * s, rel=0.15)
    assert np.all(pelvis[:, 1] > 0.85 * stand_hip) and np.all(pelvis[:, 1] < 1.05 * stand_hip)
    events = sorted([(a, side) for side in SIDES for a, _ in tg.stance[side]])
    sides = [side for _, side in events]
    assert sum(1 for x, y in zip(sides, sides[1:]) if x != y) >= 3  # left, right, left, right ...
