"""Walk to a point around the example workplace's desk (issue 13)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from shapely.geometry import Point

from jackpy.analysis.clearance import ClearanceChecker
from jackpy.errors import JackpyError
from jackpy.locomotion import floor_plan, walk_path, walk_solve
from jackpy.locomotion.walk_gait import GaitParams
from jackpy.locomotion.walk_to import visibility_path, walk_to
from jackpy.motion import cast
from jackpy.scene.workplace import load_workplace

SCENE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


def test_walk_to_goes_around_the_desk_with_clearance_on_every_frame():
    wp = load_workplace(SCENE)
    objects = list(wp.objects.values())
    fig = cast.make_figure("w", {"human": "male:50", "position": [0.0, -0.7]})
    p = GaitParams.for_figure(fig)
    steps, path, _ = walk_to(fig, p, (0.0, 1.7), objects)
    # the straight line crosses the desk; the path does not
    desk = floor_plan.footprints([wp.objects["desk"]], 2.0)[0]
    assert desk.intersects(Point(0.0, 0.6))
    assert path.shape[0] > 2
    prints = floor_plan.footprints(objects, 2.0)
    for s in steps:
        assert all(not fp.contains(Point(s.x, s.z)) for fp in prints)
    postures, _ = walk_solve.bake(fig, walk_path.Walk(steps, p), 4.0)
    cc = ClearanceChecker(fig, objects, self_collision=False)
    worst = np.inf
    for po in postures:
        po.apply_to(fig)
        cc.update()
        worst = min(worst, min(cc.clearance(n).distance for n in wp.objects))
    assert worst > 0.0
    end = fig.site_world("pelvis", "centre")[:3, 3]
    assert np.hypot(end[0], end[2] - 1.7) < 0.05


def test_goal_inside_an_obstacle_is_an_error():
    from shapely.geometry import box

    with pytest.raises(JackpyError, match="inside an obstacle"):
        visibility_path((0.0, -2.0), (0.0, 0.0), box(-1, -1, 1, 1))
    assert len(visibility_path((0.0, -2.0), (0.0, 2.0), box(-1, -1, 1, 1))) == 4
