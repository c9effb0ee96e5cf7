"""Ray-cast visibility: a box hidden behind a wall, half hidden, and seen; sites; both against the
GPU-free analytic geometry of boxes."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from jackpy.peabody.geometry import Mesh
from jackpy.population.sightline import Sightlines
from jackpy.scene.cad import CADObject, ImportSettings


def _box(name: str, lo, hi) -> CADObject:
    tm = trimesh.creation.box(bounds=[lo, hi])
    obj = CADObject(name, ImportSettings(source=f"{name}.stl"), Mesh(np.asarray(tm.vertices), np.asarray(tm.faces)))
    return obj


def test_target_behind_a_wall_is_hidden_half_wall_hides_half() -> None:
    eye = np.array([0.0, 0.0, 0.0])
    target = _box("target", [-0.1, -0.1, 2.0], [0.1, 0.1, 2.02])  # faces the eye at z = 2
    wall = _box("wall", [-1.0, -1.0, 1.0], [1.0, 1.0, 1.01])
    half = _box("half", [-1.0, -1.0, 1.0], [0.0, 1.0, 1.01])  # covers x < 0
    assert Sightlines({"target": target}).object_fraction(eye, "target") == 1.0
    assert Sightlines({"target": target, "wall": wall}).object_fraction(eye, "target") == 0.0
    f = Sightlines({"target": target, "half": half}).object_fraction(eye, "target")
    assert f == pytest.approx(0.5, abs=0.08)


def test_sites_and_back_facing() -> None:
    eye = np.zeros(3)
    s = Sightlines({"wall": _box("wall", [-1.0, -1.0, 1.0], [1.0, 1.0, 1.01])})
    assert s.site_visible(eye, [0.0, 0.0, 0.5])
    assert not s.site_visible(eye, [0.0, 0.0, 2.0])
    assert s.site_visible(eye, [0.0, 0.0, 1.0])  # a site on the wall's own face is seen
    assert s.object_fraction(np.array([0.0, 0.0, 5.0]), "wall") == 1.0
