"""Acceptance of the procedural human walk (issue 13): stance, floor, clearance, COM, speeds."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.locomotion.walk_gait import REF_SPEED, REF_STEP, reference_hip_height
from tests.locomotion.walk_cases import FPS, baked, sole

_CURVE_GAP = pytest.mark.xfail(strict=True, reason="known gap (docs/walking.md): on the quarter circle a "
                               "foot goes 7 mm below the floor in one turning step")
WALKS = [("male:50", "straight"), ("female:5", "straight"),
         pytest.param("male:50", "quarter", marks=_CURVE_GAP), ("male:50", "s-curve")]


def _poses(fig, postures):
    for po in postures:
        po.apply_to(fig)
        yield fig


@pytest.mark.parametrize("human,kind", WALKS)
def test_stance_still_floor_and_clearance(human, kind):
    fig, p, steps, postures, targets = baked(human, kind)
    tip0 = p.foot.tip[1]
    prev, prev_phase = None, None
    worst_slide, lowest = 0.0, 0.0
    mid_clear = []
    for i, f in enumerate(_poses(fig, postures)):
        pts = {s: sole(f, s) for s in ("left", "right")}
        for s in pts:
            h = pts[s][:, 1] - np.array([0.0, 0.0, tip0])
            lowest = min(lowest, float(h.min()))
            ph = targets[i].phase[s]
            if prev is not None and ph == prev_phase[s] == "flat":
                worst_slide = max(worst_slide, float(np.abs(pts[s] - prev[s]).max()))
            if prev is not None and ph == prev_phase[s] == "heel":
                worst_slide = max(worst_slide, float(np.abs(pts[s][0] - prev[s][0]).max()))
            if ph == "swing":
                mid_clear.append((i, s, float(h.min())))
        prev, prev_phase = pts, targets[i].phase
    assert worst_slide < 0.002, f"stance sole site moved {worst_slide * 1000:.2f} mm"
    assert lowest > -0.002, f"a foot went {-lowest * 1000:.1f} mm below the floor"
    # mid-swing: the frame of each swing nearest its middle clears the floor by >= 1 cm
    runs, cur = [], []
    for i, s, h in mid_clear:
        if cur and (cur[-1][0] != i - 1 or cur[-1][1] != s):
            runs.append(cur)
            cur = []
        cur.append((i, s, h))
    runs.append(cur)
    for run in runs:
        if len(run) >= 3:
            mid = run[len(run) // 2]
            assert mid[2] >= 0.01, f"mid-swing clearance {mid[2] * 1000:.1f} mm at frame {mid[0]}"


@pytest.mark.parametrize("human", ["male:50", "female:5"])
def test_speed_and_step_length(human):
    fig, p, steps, postures, targets = baked(human, "straight")
    scale = p.hip_height / reference_hip_height()
    want_step, want_speed = REF_STEP * scale, REF_SPEED * np.sqrt(scale)
    # measured from the baked figure: steady steps (heel strike to heel strike of the full steps)
    from jackpy.locomotion.walk_path import landing_times

    land = landing_times(steps, p)
    full = [j for j in range(3, len(steps) - 2)]
    assert full, "the walk has steady steps"
    lengths = [abs(steps[j].z - steps[j - 1].z) for j in full]
    fps = FPS
    pel = []
    for f in _poses(fig, postures):
        pel.append(f.site_world("pelvis", "centre")[:3, 3].copy())
    pel = np.array(pel)
    a, b = int(np.ceil(land[3] * fps)), int(np.floor(land[len(steps) - 3] * fps))
    speed = (pel[b, 2] - pel[a, 2]) / ((b - a) / fps)
    assert abs(np.mean(lengths) - want_step) <= 0.15 * want_step
    assert abs(speed - want_speed) <= 0.15 * want_speed
    if human == "male:50":
        assert abs(speed - 1.3) <= 0.15 * 1.3 and abs(np.mean(lengths) - 0.7) <= 0.15 * 0.7


def _support_distance(point: np.ndarray, polygon: np.ndarray) -> float:
    """Distance (m) of a floor point (x, z) from a convex polygon (0 inside)."""
    from shapely.geometry import MultiPoint, Point

    return float(MultiPoint([tuple(q) for q in polygon]).convex_hull.distance(Point(*point)))


#: documented in docs/walking.md: a kinematic walk is not statically balanced; the COM ground
#: point stays within this distance of the support polygon (double) or the stance foot (single)
COM_TOLERANCE = 0.10


@pytest.mark.xfail(strict=True, reason="known gap (docs/walking.md): the COM floor point leaves the "
                   "support by up to 15-17 cm in late single stance")
@pytest.mark.parametrize("human,kind", WALKS[:2])
def test_com_over_support(human, kind):
    fig, p, steps, postures, targets = baked(human, kind)
    worst = 0.0
    for i, f in enumerate(_poses(fig, postures)):
        com = f.centre_of_mass()[[0, 2]]
        poly = []
        for s in ("left", "right"):
            if targets[i].phase[s] != "swing":
                pts = sole(f, s)
                poly += [q[[0, 2]] for q in pts]
        worst = max(worst, _support_distance(com, np.array(poly)))
    assert worst <= COM_TOLERANCE, f"COM {worst * 100:.1f} cm outside the support"
