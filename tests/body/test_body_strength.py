"""Strength table: every DOF, two directions, sex and percentile order."""

import pytest

from jackpy.body.strength import strength_table, torque


def test_every_dof_has_two_strengths(male50):
    t = strength_table(male50)
    assert list(t) == male50.dof_names()
    assert all(lo > 0 and hi > 0 for lo, hi in t.values())
    assert t["left_elbow[0]"] == (45.0, 70.0)


def test_sex_and_percentile_order(female5, male95):
    f, m = strength_table(female5), strength_table(male95)
    assert all(f[k][0] < m[k][0] for k in f if not k.endswith("eye[0]") and "eye" not in k)
    assert torque("knee", "flexion", "male", 5)[0] < torque("knee", "flexion", "male", 50)[0] \
        < torque("knee", "flexion", "male", 95)[0]
    assert torque("elbow", "flexion", "female", 50)[1] == pytest.approx(0.56 * 70.0)
