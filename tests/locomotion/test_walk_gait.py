"""Acceptance of the procedural human walk (issue 13): stance, floor, clearance, COM, speeds."""

from __future__ import annotations

import numpy as np
import pytest

from jackpy.locomotion.walk_gait import REF_SPEED, REF_STEP, reference_hip_height
from tests.locomotion.walk_cases import FPS, baked, sole

WALKS = [("male:50", "straight"), ("female:5", "straight"), ("male:50", "quarter"), ("male:50", "s-curve")]


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


#: documented in docs/walking.md ("COM over the support"): double support, the COM's floor point
#: inside the hull of both feet; single support, sideways within ML_STEADY x H/H_ref of the stance
#: foot's centre line on the steady steps (less than half the step width: the COM stays on the
#: stance side of the walking line) and ML_ANY on the start and stop steps (onto feet at the
#: standing width); fore and aft no further outside its heel-to-toe span than a symmetric walk
#: at even speed puts it (the COM is midway between the ankles at heel strike):
#: max(0.3·sl − ankle-to-heel, 0.5·sl − ankle-to-toe tip) + AP_MARGIN
ML_STEADY = 0.045
ML_ANY = 0.07
AP_MARGIN = 0.02
DS_TOLERANCE = 0.01


def _foot_axes(pts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Heel point, forward and left unit vectors (top view) of a foot's sole sites."""
    heel, tip = pts[0][[0, 2]], pts[2][[0, 2]]
    fwd = (tip - heel) / np.linalg.norm(tip - heel)
    return heel, fwd, np.array([fwd[1], -fwd[0]])


@pytest.mark.parametrize("human,kind", WALKS[:2])
def test_com_over_support(human, kind):
    from jackpy.locomotion.walk_path import landing_times

    fig, p, steps, postures, targets = baked(human, kind)
    f, sl, n = p.foot, p.step_length, len(steps)
    land = landing_times(steps, p)
    ap_tol = max(0.3 * sl - (f.ankle[2] - f.heel[2]), 0.5 * sl - (f.tip[2] - f.ankle[2])) + AP_MARGIN
    ml_steady = ML_STEADY * p.hip_height / reference_hip_height()
    worst_ds = worst_ap = 0.0
    worst_ml = {True: 0.0, False: 0.0}
    for i, fg in enumerate(_poses(fig, postures)):
        com = fg.centre_of_mass()[[0, 2]]
        support = [s for s in ("left", "right") if targets[i].phase[s] != "swing"]
        if len(support) == 2:
            poly = np.array([q[[0, 2]] for s in support for q in sole(fg, s)])
            worst_ds = max(worst_ds, _support_distance(com, poly))
            continue
        j = max(k for k in range(n) if steps[k].side == support[0] and (land[k] <= i / FPS or k < 2))
        steady = 3 <= j and j + 1 <= n - 3  # stance and the landing swing foot on the walking base
        pts = sole(fg, support[0])
        heel, fwd, left = _foot_axes(pts)
        along = float(np.dot(com - heel, fwd))
        worst_ml[steady] = max(worst_ml[steady], abs(float(np.dot(com - heel, left))))
        worst_ap = max(worst_ap, -along, along - float(np.dot(pts[2][[0, 2]] - heel, fwd)))
    assert worst_ml[True] > 0.0, "the walk has steady single stances"
    assert worst_ds <= DS_TOLERANCE, f"COM {worst_ds * 100:.1f} cm outside the double support"
    assert worst_ml[True] <= ml_steady, f"COM {worst_ml[True] * 100:.1f} cm beside the steady stance foot"
    assert worst_ml[False] <= ML_ANY, f"COM {worst_ml[False] * 100:.1f} cm beside the start/stop stance foot"
    assert worst_ap <= ap_tol, (f"COM {worst_ap * 100:.1f} cm before or behind the stance foot "
                                f"(allowed {ap_tol * 100:.1f})")
