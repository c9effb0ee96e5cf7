"""Acceptance: counts, stature and eye height, mass, COM over the feet, limits, percentile order."""

import numpy as np
import pytest

from jackpy.body.anthropometry import PERCENTILES, data_rows, load_population
from jackpy.body.human import SUPPORT_SITES, make_human
from jackpy.body.sass import STATURE_PATH


@pytest.mark.parametrize("sex,p", [("female", 5), ("female", 50), ("male", 50), ("male", 95), ("female", 99)])
def test_stature_and_eye_height_match_population(sex, p):
    fig = make_human(sex, p)
    pop = load_population("ansur2")
    top = fig.site_world("head", "top")[1, 3]
    assert abs(top - pop.value(sex, "stature", p)) <= 0.01 * pop.value(sex, "stature", p)
    assert abs(fig.site_world("head", "view")[1, 3] - pop.value(sex, "eye_height", p)) <= 0.02
    assert min(fig.site_world(*s)[1, 3] for s in SUPPORT_SITES) == pytest.approx(0.0, abs=1e-9)
    # the surface reaches the top of the head too
    head = fig.segment("head").psurf.posed_mesh()
    w = fig.world_transforms()["head"]
    assert (head.vertices @ w[:3, :3].T + w[:3, 3])[:, 1].max() == pytest.approx(top, abs=0.01)


def test_counts_and_structure(male50):
    fig = male50
    fig.validate()
    assert (len(fig.segments), len(fig.joints), fig.ndof) == (74, 73, 137)
    assert len([s for s in fig.segments.values() if s.psurf is not None]) == 72
    hand = [n for n in fig.segments if n.startswith("left_") and
            (n == "left_palm" or n.split("_")[1] in ("thumb", "index", "middle", "ring", "little"))]
    assert len(hand) == 16
    assert len(fig.groups["spine"].joints) == 18
    assert all(len(fig.joint(j).dofs) == 3 for j in fig.groups["spine"].joints)


def test_named_sites_exist(male50):
    names = dict(male50.iter_sites())
    for side in ("left", "right"):
        for s in ("palm.palm_centre", "palm.grip", "foot.heel", "foot.ball", "foot.toe", "toes.tip",
                  "thumb_3.tip", "index_3.tip", "middle_3.tip", "ring_3.tip", "little_3.tip", "eye.gaze",
                  "clavicle.shoulder", "upper_arm.base", "thigh.base"):
            assert f"{side}_{s}" in names
        assert f"pelvis.{side}_hip" in names
    for s in ("head.view", "head.top", "pelvis.centre", "neck.base", "l3.waist"):
        assert s in names


def test_frames_face_plus_z_left_plus_x(male50):
    f = male50
    assert f.site_world("left_foot", "toe")[2, 3] > f.site_world("left_foot", "heel")[2, 3]
    assert f.site_world("pelvis", "left_hip")[0, 3] > 0 > f.site_world("pelvis", "right_hip")[0, 3]
    assert f.site_world("head", "view")[2, 3] > f.site_world("head", "base")[2, 3]


def test_masses_sum_and_com_over_support(female5, male95):
    for fig in (female5, male95):
        assert fig.total_mass == pytest.approx(fig.body_spec.mass, rel=1e-12)
        assert all(s.mass >= 0 for s in fig.segments.values())
        com = fig.centre_of_mass()
        feet = np.array([fig.site_world(*s)[:3, 3] for s in SUPPORT_SITES])
        assert feet[:, 0].min() < com[0] < feet[:, 0].max()
        assert feet[:, 2].min() < com[2] < feet[:, 2].max()
        assert 0.5 < com[1] / fig.body_spec.stature < 0.6


def test_every_dof_limited_and_neutral_inside(male50):
    f = male50
    lo, hi = f.lower, f.upper
    assert np.all(np.isfinite(lo)) and np.all(np.isfinite(hi)) and np.all(lo < hi)
    assert not np.any(np.isclose(lo, -np.pi) & np.isclose(hi, np.pi))  # a published range, not the default
    q = f.q
    assert np.all(q >= lo - 1e-12) and np.all(q <= hi + 1e-12)
    for g in f.groups.values():
        assert g.is_feasible(g.angles)


def test_percentile_order_every_dimension():
    pop = load_population("ansur2")
    for sex in ("female", "male"):
        for name in pop.names(sex):
            v = [pop.value(sex, name, p) for p in (5, 50, 95)]
            assert v[0] < v[1] < v[2], name
            assert np.all(np.diff(pop.dimension(sex, name).values) > 0)
    assert list(PERCENTILES) == [1, 5, 25, 50, 75, 95, 99]
    # figures take the regression on stature and weight: every dimension that grows with body size
    # (correlation with stature or weight above 0.3, ANSUR II) is larger at P95; head height,
    # interpupillary breadth and the offsets acromion.drop and seat.hip_height hardly correlate
    # with either and may go either way
    f5, f95 = make_human("male", 5).body_spec, make_human("male", 95).body_spec
    rows = {r["dimension"]: r for r in data_rows("population_ansur2.csv") if r["sex"] == "male"}
    grows = [n for n in f5.dims if max(float(rows[n]["r_stature"]), float(rows[n]["r_weight"])) > 0.3]
    assert len(grows) >= len(f5.dims) - 4
    for name in grows:
        assert f5.dims[name] < f95.dims[name], name
    assert set(STATURE_PATH) <= set(f5.dims)
