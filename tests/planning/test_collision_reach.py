"""Collision-aware reach in the shipped example workplace (issue 16 acceptance): no posture
reported as reaching passes into a CAD object deeper than the contact tolerance (checked with a
clearance checker of its own), and the far corner behind the partition is blocked, by the
partition, for the 5th-percentile woman and the 95th-percentile man."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest

from jackpy.analysis.clearance import ClearanceChecker, eroded
from jackpy.analysis.parts import figure_parts
from jackpy.analysis.reach import point_reach
from jackpy.body.human import make_human
from jackpy.peabody.geometry import Mesh
from jackpy.planning.collision_reach import CONTACT_TOLERANCE, WorkplaceJudge
from jackpy.scene.workplace import load_workplace, resolve_target, stand_figure

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


@pytest.fixture(scope="module")
def workplace():
    return load_workplace(EXAMPLE)


@pytest.fixture(scope="module", params=[("female", 5), ("male", 95)], ids=["female5", "male95"])
def reaches(request, workplace):
    f = make_human(*request.param)
    stand_figure(f, workplace.stand)
    objs = list(workplace.objects.values())
    out = {}
    for ref in workplace.plan.reach:
        obj, p = resolve_target(workplace.env, ref)
        out[ref] = (obj.name, point_reach(f, p, "right", obstacles=objs, target_object=obj.name))
    return f, out


def _deep_contacts(figure, posture, objects) -> list[tuple[str, str]]:
    """Segments more than the tolerance into an object, by a checker built here (eroded meshes)."""
    c = copy.deepcopy(figure)
    posture.apply(c, root=tuple(figure.root))
    return ClearanceChecker(c, objects, self_collision=False, erode=CONTACT_TOLERANCE).object_collisions()


def test_no_reaching_posture_passes_into_the_workplace(reaches, workplace):
    figure, out = reaches
    palm = figure_parts(figure).hands["right"].segment
    objs = list(workplace.objects.values())
    reached = [ref for ref, (_, r) in out.items() if r.reached]
    assert "desk.button" in reached  # both sizes press the button without the arm in the desk
    for ref in reached:
        own, r = out[ref]
        deep = [(s, b) for s, b in _deep_contacts(figure, r.posture, objs) if not (s == palm and b == own)]
        assert deep == [], f"{ref}: {deep}"
        assert r.shortfall <= 0.005


def test_far_corner_is_blocked_by_the_partition(reaches):
    _, out = reaches
    _, r = out["desk.far_corner"]
    assert not r.reached and r.verdict.kind == "blocked" and r.verdict.blocked_by == "partition"
    assert r.describe().startswith("blocked by partition (short by ~")


def test_ignoring_the_workplace_the_button_is_reached_inside_the_desk(workplace):
    """The measured problem: the plain IK puts the fingers or forearm into the desk."""
    f = make_human("male", 95)
    stand_figure(f, workplace.stand)
    _, p = resolve_target(workplace.env, "desk.button")
    r = point_reach(f, p, "right")
    assert r.reached
    judge = WorkplaceJudge(f, list(workplace.objects.values()))
    assert any(b == "desk" for _, b in judge.penetrations(r.posture))


def test_eroded_cube_shrinks_by_the_depth():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float) * 0.1
    faces = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                      [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    for f in (faces, faces[:, ::-1]):  # either winding
        m = eroded(Mesh(v, f), 0.01)
        lo, hi = m.bounds()
        assert np.all(lo > 0.004) and np.all(hi < 0.096)  # corners move along the diagonal normal
        assert np.all(lo < 0.01) and np.all(hi > 0.09)
    thin = eroded(Mesh(v * [1, 1, 0.05], faces), 0.01)  # 5 mm thick: at most 45 % of its half-extent
    lo, hi = thin.bounds()
    assert hi[2] > lo[2]
