"""Reachable workspace: sampling matches FK, volume converges to the analytic shell, surface, sites."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from jackpy.analysis.surface import mesh_volume, surface_nets
from jackpy.analysis.workspace import Chain, reachable_workspace
from jackpy.errors import FigureError
from jackpy.peabody import Dof, Figure, Joint, Segment
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import translation

L1, L2 = 0.3, 0.2
SHELL = 4 / 3 * np.pi * ((L1 + L2) ** 3 - (L1 - L2) ** 3)


def two_link_arm() -> Figure:
    """Shoulder at (0, 1, 0): yaw R(y) +-180 deg, pitch R(z) +-90, roll R(x) +-180; elbow R(z) 0..180."""
    f = Figure("arm2")
    base = Segment("base")
    base.add_site("shoulder")
    f.add_segment(base)
    for name, length in (("upper", L1), ("fore", L2)):
        s = Segment(name)
        s.add_site("base")
        s.add_site("tip", translation(length, 0, 0))
        f.add_segment(s)
    X, Y, Z = np.eye(3)
    f.add_joint(Joint("shoulder", "base", "shoulder", "upper", "base",
                      [Dof("R", X), Dof("R", Z, -np.pi / 2, np.pi / 2), Dof("R", Y)]))
    f.add_joint(Joint("elbow", "upper", "tip", "fore", "base", [Dof("R", Z, 0.0, np.pi)]))
    f.root = ("base", "shoulder")
    f.location = translation(0, 1, 0)
    return f


@pytest.mark.parametrize("root", [("pelvis", "base"), ("palm_right", "tip")])
def test_sampled_points_match_forward_kinematics(root):
    f = human_like_tree()
    f.reroot(*root)
    rng = np.random.default_rng(1)
    f.q = rng.uniform(f.lower, f.upper) * 0.3
    start, end = ("clavicle_right", "palm_right") if root[0] == "pelvis" else ("elbow_right", "clavicle_left")
    chain = Chain(f, start, end, np.array([0.01, 0.02, 0.03]))
    kin = f.kinematics()
    vals = rng.uniform(chain.lower, chain.upper, size=(20, len(chain.dofs)))
    pts = chain.points(vals)
    for v, p in zip(vals, pts):
        q = f.q
        q[chain.dofs] = v
        w = kin.forward(q, f.location).segments[kin.segment_index[end]]
        np.testing.assert_allclose(p, w[:3, :3] @ chain.point + w[:3, 3], atol=1e-12)


def test_chain_must_move_the_end_segment():
    with pytest.raises(FigureError):
        Chain(human_like_tree(), "elbow_left", "palm_right", np.zeros(3))


def test_volume_converges_to_the_analytic_shell_as_resolution_grows():
    chain = Chain.to_site(two_link_arm(), "shoulder", "fore", "tip")
    errors = []
    for res in (16, 32, 64):
        ws = reachable_workspace(chain, res, max_samples=1_500_000, tol=1e-3)
        errors.append(abs(ws.volume() - SHELL) / SHELL)
    assert errors[0] > errors[1] > errors[2]
    assert errors[2] < 0.07
    # the surface encloses the marked voxels' volume to within 5 % (spec test 32), and is closed
    surf = ws.surface()
    assert abs(mesh_volume(surf) - ws.volume()) / ws.volume() < 0.05
    assert trimesh.Trimesh(surf.vertices, surf.faces).is_watertight


def test_sites_classified_inside_and_outside_with_distance():
    chain = Chain.to_site(two_link_arm(), "shoulder", "fore", "tip")
    ws = reachable_workspace(chain, 32, max_samples=600_000)
    c = np.array([0.0, 1.0, 0.0])
    out = ws.classify({"mid": c + [0.3, 0.0, 0.0], "far": c + [0.0, 0.0, 0.7], "core": c + [0.0, 0.02, 0.0]})
    assert out["mid"] == (True, 0.0)
    assert not out["far"][0] and out["far"][1] == pytest.approx(0.2, abs=1.5 * ws.cell)
    assert not out["core"][0]  # the unreachable core of radius L1 - L2 around the shoulder


def test_progress_is_reported_and_cancel_stops_early():
    chain = Chain.to_site(two_link_arm(), "shoulder", "fore", "tip")
    seen = []

    def progress(p):
        seen.append(p)
        return len(seen) < 3

    ws = reachable_workspace(chain, 24, max_samples=10_000_000, batch=8192, tol=0.0, fill_gaps=0,
                             progress=progress)
    assert ws.cancelled and not ws.converged and ws.samples == 3 * 8192
    assert [p.samples for p in seen] == [8192, 16384, 24576] and seen[-1].marked == ws.occupied.sum()


def test_surface_nets_sphere():
    x = np.linspace(-1, 1, 30)
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    m = surface_nets(0.6 - np.sqrt(X ** 2 + Y ** 2 + Z ** 2), 0.0, x[1] - x[0], np.full(3, -1.0))
    r = np.linalg.norm(m.vertices, axis=1)
    assert np.all(np.abs(r - 0.6) < 0.01)
    assert mesh_volume(m) == pytest.approx(4 / 3 * np.pi * 0.6 ** 3, rel=0.02)
