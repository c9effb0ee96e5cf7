"""Forward kinematics, Jacobians, centre of mass and re-rooting on small and human-sized trees."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from jackpy.errors import FigureError
from jackpy.peabody import Dof, Figure, Joint, Segment
from jackpy.peabody.synthetic import human_like_tree
from jackpy.peabody.transforms import rotation, translation


def three_link(mixed: bool = True) -> Figure:
    """Four segments, joints in both directions, a translational DOF and a 3-DOF joint."""
    f = Figure("chain")
    for n in "abcd":
        s = Segment(n, mass=1.0 + ord(n) % 3, com=np.array([0.1, 0.2, 0.0]))
        s.add_site("base")
        s.add_site("tip", translation(0, 0.3, 0.05) @ rotation("z", 0.2))
        f.add_segment(s)
    dofs = [Dof("R", [0, 0, 1]), Dof("R", [1, 0, 0]), Dof("T" if mixed else "R", [0, 1, 0], -1, 1)]
    f.add_joint(Joint("j1", "a", "tip", "b", "base", dofs))
    f.add_joint(Joint("j2", "c", "base", "b", "tip", [Dof("R", [0, 1, 1])]))  # points "up"
    f.add_joint(Joint("j3", "c", "tip", "d", "base", [Dof("R", [1, 0, 0]), Dof("R", [0, 1, 0])]))
    f.root = ("a", "base")
    f.location = translation(1, 2, 3) @ rotation("y", 0.4)
    return f


def naive_world(f: Figure) -> dict[str, np.ndarray]:
    """World transforms by the book's formulas, one joint at a time (reference for the fast FK)."""
    L = lambda s, t: f.site_location(s, t)  # noqa: E731
    W = {"a": f.location @ np.linalg.inv(L("a", "base"))}
    j1, j2, j3 = (f.joints[n] for n in ("j1", "j2", "j3"))
    W["b"] = W["a"] @ L("a", "tip") @ j1.transform() @ np.linalg.inv(L("b", "base"))
    W["c"] = W["b"] @ L("b", "tip") @ np.linalg.inv(j2.transform()) @ np.linalg.inv(L("c", "base"))
    W["d"] = W["c"] @ L("c", "tip") @ j3.transform() @ np.linalg.inv(L("d", "base"))
    return W


def test_joint_type_order_is_peabody_row_product():
    # type = R(z) * R(x): D_row = Rz_row . Rx_row, so D = Rx @ Rz in column form.
    j = Joint("j", "a", "s", "b", "t", [Dof("R", [0, 0, 1]), Dof("R", [1, 0, 0])], np.array([0.3, 0.5]))
    assert np.allclose(j.transform(), rotation("x", 0.5) @ rotation("z", 0.3))


def test_forward_matches_book_formulas():
    f = three_link()
    rng = np.random.default_rng(1)
    for _ in range(20):
        f.q = rng.uniform(-1, 1, f.ndof)
        fast = f.world_transforms()
        ref = naive_world(f)
        for name in "abcd":
            assert np.allclose(fast[name], ref[name], atol=1e-12)


def _numeric_site_jacobian(f, seg, loc, eps=1e-7):
    kin = f.kinematics()
    q0 = f.q
    w0 = kin.forward(q0, f.location).segments[kin.segment_index[seg]] @ loc
    J = np.zeros((6, f.ndof))
    for i in range(f.ndof):
        dq = q0.copy()
        dq[i] += eps
        w = kin.forward(dq, f.location).segments[kin.segment_index[seg]] @ loc
        J[:3, i] = (w[:3, 3] - w0[:3, 3]) / eps
        J[3:, i] = Rotation.from_matrix(w[:3, :3] @ w0[:3, :3].T).as_rotvec() / eps
    return J


@pytest.mark.parametrize("root", [("a", "base"), ("d", "tip"), ("c", "base")])
def test_site_jacobian_matches_finite_differences(root):
    f = three_link()
    f.q = np.random.default_rng(2).uniform(-0.8, 0.8, f.ndof)
    f.reroot(*root)
    kin = f.kinematics()
    fk = kin.forward(f.q, f.location)
    loc = translation(0.05, 0.1, 0.02) @ rotation("x", 0.3)
    for seg in "abcd":
        _, J = kin.site_jacobian(fk, kin.segment_index[seg], loc)
        assert np.allclose(J, _numeric_site_jacobian(f, seg, loc), atol=1e-6)


def test_com_and_its_jacobian():
    f = three_link()
    f.q = np.random.default_rng(3).uniform(-0.8, 0.8, f.ndof)
    W = naive_world(f)
    total = sum(s.mass for s in f.segments.values())
    expect = sum(s.mass * (W[n] @ np.append(s.com, 1))[:3] for n, s in f.segments.items()) / total
    assert np.allclose(f.centre_of_mass(), expect, atol=1e-12)
    kin = f.kinematics()
    q0 = f.q
    Jc = kin.com_jacobian(kin.forward(q0, f.location))
    for i in range(f.ndof):
        dq = q0.copy()
        dq[i] += 1e-7
        num = (kin.centre_of_mass(kin.forward(dq, f.location)) - f.centre_of_mass()) / 1e-7
        assert np.allclose(Jc[:, i], num, atol=1e-6)


def test_rerooting_leaves_every_world_transform_unchanged():
    f = human_like_tree()
    f.q = np.random.default_rng(4).uniform(-0.3, 0.3, f.ndof)
    before = f.world_transforms()
    for seg, site in [("foot_left", "ball"), ("palm_right", "tip"), ("head", "eye_left"), ("pelvis", "base")]:
        joints_before = {n: (j.from_seg, j.from_site, j.to_seg, j.to_site, j.transform()) for n, j in f.joints.items()}
        f.reroot(seg, site)
        after = f.world_transforms()
        for name, w in before.items():
            assert np.abs(after[name] - w).max() <= 1e-12
        for n, j in f.joints.items():  # the user-visible joint definitions never change
            assert joints_before[n][:4] == (j.from_seg, j.from_site, j.to_seg, j.to_site)
            assert np.array_equal(joints_before[n][4], j.transform())


def test_human_like_tree_size_and_fk_of_sites():
    f = human_like_tree()
    assert len(f.segments) == 69 and f.ndof == 136 and len(f.joints) == 68
    w = f.site_world("foot_left", "ball")
    # standing tree: ball of the foot about 1 m below the pelvis, in front of the ankle
    assert w[1, 3] < 0.2 and w[2, 3] > 0.1


def test_validate_names_the_part_at_fault():
    f = three_link()
    f.joints["j3"].displacement = np.array([0.0, 4.0])
    with pytest.raises(FigureError, match="j3.*outside limits"):
        f.validate()
    f = three_link()
    f.add_joint(Joint("loop", "a", "base", "d", "tip", [Dof("R", [1, 0, 0])]))
    with pytest.raises(FigureError, match="loop.*cycle"):
        f.validate()
    f = three_link()
    f.add_joint(Joint("self", "a", "base", "a", "tip", [Dof("R", [1, 0, 0])]))
    with pytest.raises(FigureError, match="self.*itself"):
        f.validate()
    f = three_link()
    f.add_joint(Joint("bad", "a", "nowhere", "b", "base", [Dof("R", [1, 0, 0])]))
    with pytest.raises(FigureError, match="unknown site a.nowhere"):
        f.validate()
    f = three_link()
    f.add_segment(Segment("lonely"))
    with pytest.raises(FigureError, match="lonely.*not joined"):
        f.validate()
