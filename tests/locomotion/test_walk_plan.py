"""Walk plans as data (the step and path editors' plan in a document): round trip, bad data,
moves; path points optional (old plans have none), added, moved and deleted."""

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from jackpy.locomotion import footsteps, walk_plan
from jackpy.locomotion.walk_plan import PlanError
from tests.locomotion.walk_cases import figure_and_params


def test_round_trip_through_json():
    _, p = figure_and_params("male:50")
    steps = footsteps.from_path(p, [(0.0, 0.0), (1.0, 1.0), (2.0, 1.0)])
    again = walk_plan.from_data(json.loads(json.dumps(walk_plan.to_data(steps))))
    assert again == steps
    path = [(0.0, 0.0), (1.0, 1.0), (2.0, 1.0)]
    data = json.loads(json.dumps(walk_plan.to_data(steps, path)))
    assert walk_plan.from_data(data) == steps and walk_plan.path_from_data(data) == path
    assert walk_plan.path_from_data(walk_plan.to_data(steps)) is None  # a plan saved before paths


@pytest.mark.parametrize("data,message", [
    ([], "needs"),
    ({"steps": [[0, 0, 0, "left"]]}, "two standing footsteps"),
    ({"steps": [[0, 0, 0, "left"], [0, 0, 0, "left"]]}, "two standing footsteps"),
    ({"steps": [[0, 0, 0, "left"], [0, 0, 0, "right"], [1, 0, 0, "right"]]}, "footstep 2 is on the same side"),
    ({"steps": [[0, 0, 0, "left"], [0, "a", 0, "right"]]}, "footstep 1 is not"),
    ({"steps": [[0, 0, 0, "left"], [0, float("nan"), 0, "right"]]}, "footstep 1 is not"),
    ({"steps": [[0, 0, 0, "middle"], [0, 0, 0, "right"]]}, "footstep 0 is not"),
    ({"steps": [[0, 0, 0, "left"], [0, 0, 0, "right"]], "path": [[0, 0]]}, "two or more"),
    ({"steps": [[0, 0, 0, "left"], [0, 0, 0, "right"]], "path": "0,0 1,1"}, "two or more"),
    ({"steps": [[0, 0, 0, "left"], [0, 0, 0, "right"]], "path": [[0, 0], [1, True]]}, "path point 1 is not"),
    ({"steps": [[0, 0, 0, "left"], [0, 0, 0, "right"]], "path": [[0, 0], [1, 2, 3]]}, "path point 1 is not"),
    ({"steps": [[0, 0, 0, "left"], [0, 0, 0, "right"]], "path": [[0, 0], [float("inf"), 0]]}, "path point 1"),
])
def test_bad_plans_are_one_line(data, message):
    with pytest.raises(PlanError, match=message) as e:
        walk_plan.from_data(data, "scene.env: walk plan of jack")
    assert "\n" not in str(e.value) and str(e.value).startswith("scene.env: walk plan of jack")


@settings(max_examples=200, deadline=None)
@given(st.recursive(st.none() | st.booleans() | st.floats() | st.text(max_size=5) | st.integers(),
                    lambda kids: st.lists(kids, max_size=5)
                    | st.dictionaries(st.sampled_from(["steps", "path"]), kids, max_size=2),
                    max_leaves=20))
def test_fuzz_only_plan_errors(data):
    try:
        steps = walk_plan.from_data(data)
        path = walk_plan.path_from_data(data)
    except PlanError:
        return
    assert len(steps) >= 2 and all(np.isfinite([s.x, s.z, s.psi]).all() for s in steps)
    assert path is None or (len(path) >= 2 and np.isfinite(path).all())


def test_path_points_added_moved_deleted_as_copies():
    path = [(0.0, 0.0), (0.0, 2.0)]
    more = walk_plan.with_point_added(path, 1, 1.0, 1.0)
    assert more == [(0.0, 0.0), (1.0, 1.0), (0.0, 2.0)] and path == [(0.0, 0.0), (0.0, 2.0)]
    assert walk_plan.with_point_added(path, 2, 3.0, 3.0)[-1] == (3.0, 3.0)
    assert walk_plan.with_point_moved(more, 2, 0.5, 2.5) == [(0.0, 0.0), (1.0, 1.0), (0.5, 2.5)]
    assert walk_plan.with_point_deleted(more, 1) == path
    for bad in (lambda: walk_plan.with_point_added(path, 0, 1.0, 1.0),
                lambda: walk_plan.with_point_added(path, 3, 1.0, 1.0),
                lambda: walk_plan.with_point_moved(path, 0, 1.0, 1.0),
                lambda: walk_plan.with_point_deleted(more, 0)):
        with pytest.raises(PlanError, match="where the figure stands"):
            bad()
    with pytest.raises(PlanError, match="two points"):
        walk_plan.with_point_deleted(path, 1)


def test_moved_copies_and_keeps_the_standing_feet():
    _, p = figure_and_params("male:50")
    steps = footsteps.straight(p, 2.0)
    out = walk_plan.moved(steps, 3, 0.5, 1.0, 0.2)
    assert (out[3].x, out[3].z, out[3].psi, out[3].side) == (0.5, 1.0, 0.2, steps[3].side)
    assert steps[3].x != 0.5  # the original is untouched
    for j in (0, 1, len(steps)):
        with pytest.raises(PlanError):
            walk_plan.moved(steps, j, 0.0, 0.0, 0.0)


def test_a_stride_added_then_deleted_is_the_plan_again():
    _, p = figure_and_params("male:50")
    steps = footsteps.straight(p, 3.0)
    for j in range(2, len(steps) - 2):
        more = walk_plan.with_stride_added(steps, j)
        assert [s.side for s in more[j + 1:j + 3]] == [steps[j + 1].side, steps[j].side]
        assert more[j + 1].z == pytest.approx(0.5 * (steps[j - 1].z + steps[j + 1].z))
        assert walk_plan.with_stride_deleted(more, j + 1) == steps
        walk_plan.from_data(walk_plan.to_data(more))  # still a walk
    with pytest.raises(PlanError):
        walk_plan.with_stride_added(steps, len(steps) - 2)
    with pytest.raises(PlanError):
        walk_plan.with_stride_deleted(steps, 1)
