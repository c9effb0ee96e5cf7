"""Collision and clearance: exact distances, pruning agrees with brute force, self-collision rules."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from jackpy.peabody import Dof, Figure, Joint, Mesh, Psurf, Segment
from jackpy.peabody.transforms import translation
from jackpy.scene.cad import CADObject, ImportSettings

fcl = pytest.importorskip("fcl")
from jackpy.analysis.clearance import ClearanceChecker  # noqa: E402

HALF = 0.03  # half thickness of every link box


def _box(lo, hi) -> Mesh:
    b = trimesh.creation.box(bounds=[lo, hi])
    return Mesh(b.vertices, b.faces)


def boxed_arm() -> Figure:
    """Upper arm 0.30, forearm 0.26, hand 0.09 along +x from a base at the origin; 6 cm thick boxes."""
    X, Z = np.eye(3)[0], np.eye(3)[2]
    f = Figure("arm")
    base = Segment("base", psurf=Psurf("base", mesh=_box([-0.1, -0.1, -0.1], [-0.05, 0.1, 0.1])))
    base.add_site("shoulder")
    f.add_segment(base)
    for name, length in (("upper", 0.30), ("fore", 0.26), ("hand", 0.09)):
        s = Segment(name, psurf=Psurf(name, mesh=_box([0, -HALF, -HALF], [length, HALF, HALF])))
        s.add_site("base")
        s.add_site("tip", translation(length, 0, 0))
        f.add_segment(s)
    f.add_joint(Joint("shoulder", "base", "shoulder", "upper", "base", [Dof("R", X), Dof("R", Z)]))
    f.add_joint(Joint("elbow", "upper", "tip", "fore", "base", [Dof("R", Z)]))
    f.add_joint(Joint("wrist", "fore", "tip", "hand", "base", [Dof("R", Z)]))
    f.root = ("base", "shoulder")
    return f


def slab(name="shelf", y=0.2, triangles_per_side=None) -> CADObject:
    m = trimesh.creation.box(bounds=[[0.1, 0.0, -0.3], [1.0, 0.02, 0.3]])
    if triangles_per_side:
        m = m.subdivide_to_size(triangles_per_side)
    obj = CADObject(name, ImportSettings(f"{name}.stl"), Mesh(m.vertices, m.faces))
    obj.place(np.array([0.0, y, 0.0]))
    return obj


def test_clearance_is_exact_and_names_segment_and_object():
    f = boxed_arm()
    shelf = slab(y=0.2)
    chk = ClearanceChecker(f, [shelf])
    c = chk.clearance("shelf")
    assert c.distance == pytest.approx(0.2 - HALF, abs=1e-9)
    assert c.body == "shelf" and c.segment in {"upper", "fore", "hand"}
    assert c.point_on_body[1] == pytest.approx(0.2) and c.point_on_segment[1] == pytest.approx(HALF)
    assert chk.object_collisions() == [] and chk.colliding_segments() == set()
    # raise the arm into the shelf: the segments that touch are reported
    f.joint("shoulder").displacement = np.array([0.0, 0.6])
    shelf.move(np.array([0.0, 0.05, 0.0]))
    chk.update()
    hits = chk.object_collisions()
    assert hits and {b for _, b in hits} == {"shelf"}
    assert chk.clearance("shelf").distance == 0.0
    assert {s for s, _ in hits} <= chk.colliding_segments()


def test_pruned_clearance_equals_brute_force():
    f = boxed_arm()
    objs = [slab("a", 0.25, 0.05), slab("b", -0.4)]
    objs[1].rotate("x", 0.3)
    chk = ClearanceChecker(f, objs, self_collision=False)
    rng = np.random.default_rng(7)
    req = fcl.DistanceRequest()
    for _ in range(15):
        f.q = rng.uniform(-1.2, 1.2, f.ndof)
        chk.update()
        for name in ("a", "b"):
            got = chk.clearance(name).distance
            k = chk.body_names.index(name)
            brute = min(max(fcl.distance(chk._place(s), chk._body_obj[k], req, fcl.DistanceResult()), 0.0)
                        for s in range(len(chk.segment_names)))
            assert got == pytest.approx(brute, abs=1e-9)


def test_self_collision_skips_adjacent_and_initial_contacts():
    f = boxed_arm()
    chk = ClearanceChecker(f, [])
    assert chk.self_collisions() == []  # upper/fore and fore/hand overlap at joints: adjacent
    f.joint("elbow").displacement = np.array([-3.0])  # fold the forearm back: the hand meets upper arm and base
    chk.update()
    folded = [("base", "hand"), ("upper", "hand")]
    assert chk.self_collisions() == folded
    assert chk.colliding_segments() == {"base", "upper", "hand"}
    # a checker built in the folded posture allows those contacts
    assert ClearanceChecker(f, []).self_collisions() == []
    assert ClearanceChecker(f, [], ignore_initial=False).self_collisions() == folded


def test_unknown_object_is_a_clear_error():
    from jackpy.errors import JackpyError

    chk = ClearanceChecker(boxed_arm(), [slab()])
    with pytest.raises(JackpyError, match="no object 'desk'"):
        chk.clearance("desk")


def _ball(name="ball", centre=(0.35, 0.3, 0.0), radius=0.12, count=40) -> CADObject:
    m = trimesh.creation.uv_sphere(radius=radius, count=[count, count])
    obj = CADObject(name, ImportSettings(f"{name}.ply"), Mesh(m.vertices, m.faces))
    obj.place(np.array(centre))
    return obj


def _point_distance(mesh: Mesh, points: np.ndarray) -> np.ndarray:
    """Exact point-to-surface distance by fcl (a point as a sphere of radius 0)."""
    bvh = fcl.BVHModel()
    bvh.beginModel(len(mesh.vertices), len(mesh.faces))
    bvh.addSubModel(np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int32))
    bvh.endModel()
    target = fcl.CollisionObject(bvh, fcl.Transform())
    out = []
    for p in points:
        d = fcl.distance(fcl.CollisionObject(fcl.Sphere(0.0), fcl.Transform(p)), target, fcl.DistanceRequest(),
                         fcl.DistanceResult())
        out.append(max(d, 0.0))
    return np.array(out)


@pytest.mark.parametrize("shape", ["ball", "slab"])
def test_distance_grid_bounds_are_sound(shape):
    from jackpy.analysis.distance_field import DistanceGrid

    m = (trimesh.creation.uv_sphere(radius=0.2, count=[30, 30]) if shape == "ball"
         else trimesh.creation.box(bounds=[[0, 0, 0], [1.2, 0.02, 0.5]]))
    mesh = Mesh(m.vertices, m.faces)
    grid = DistanceGrid(mesh, budget=20_000)
    rng = np.random.default_rng(3)
    pts = rng.uniform(grid.box[0] - 0.6, grid.box[1] + 0.6, (400, 3))
    near = m.sample(200, seed=4) + rng.normal(0, 0.02, (200, 3))  # points near the surface
    pts = np.vstack([pts, near])
    lower, upper = grid.bounds(pts)
    exact = _point_distance(mesh, pts)
    assert np.all(lower <= exact + 1e-9)
    assert np.all(upper >= exact - 1e-9)
    assert np.median((exact - lower)[-200:]) < 0.02 and np.median((upper - exact)[-200:]) < 0.03  # and tight


def test_segment_lower_bounds_never_exceed_true_distance():
    f = boxed_arm()
    objs = [_ball(), slab("shelf", 0.25, 0.05)]
    chk = ClearanceChecker(f, objs, self_collision=False, grid_budget=30_000)
    rng = np.random.default_rng(11)
    req = fcl.DistanceRequest()
    for _ in range(25):
        f.q = rng.uniform(-1.5, 1.5, f.ndof)
        chk.update()
        for name in ("ball", "shelf"):
            lower, upper = chk.segment_bounds(name)
            k = chk.body_names.index(name)
            for s in range(len(chk.segment_names)):
                true = fcl.distance(chk._place(s), chk._body_obj[k], req, fcl.DistanceResult())
                if true <= 0.0:  # touching: fcl reports no distance
                    assert lower[s] <= 1e-9
                    continue
                assert lower[s] <= true + 1e-9
                assert upper[s] >= true - 1e-9


def test_pruned_clearance_equals_brute_force_near_a_curved_object():
    f = boxed_arm()
    ball = _ball()
    chk = ClearanceChecker(f, [ball], self_collision=False, grid_budget=30_000)
    rng = np.random.default_rng(5)
    req = fcl.DistanceRequest()
    q = np.zeros(f.ndof)
    for step in range(40):  # a smooth path (frame coherence and the bound caches) with jumps
        q = rng.uniform(-1.5, 1.5, f.ndof) if step % 10 == 0 else q + rng.normal(0, 0.05, f.ndof)
        f.q = q
        chk.update()
        c = chk.clearance("ball")
        brute = min(max(fcl.distance(chk._place(s), chk._body_obj[0], req, fcl.DistanceResult()), 0.0)
                    for s in range(len(chk.segment_names)))
        assert c.distance == pytest.approx(brute, abs=1e-9)
        if c.distance > 0:
            assert np.linalg.norm(c.point_on_segment - c.point_on_body) == pytest.approx(c.distance, abs=1e-6)
