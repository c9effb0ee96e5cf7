"""The standard human's continuous skinned torso (jackpy.body.skin), on the CPU."""

import numpy as np
import pytest

from jackpy.body import make_human, rescale_in_place
from jackpy.body.skin import (
    SPINE_SEGMENTS,
    bone_matrices,
    chain_weights,
    deform,
    skin_for,
    skinned_pieces,
    skins_for,
)
from jackpy.peabody.synthetic import human_like_tree
from jackpy.render.skinning import SkinnedMesh


@pytest.fixture(scope="module")
def human():
    return make_human("male", 50)


def bent(fig, flexion=60.0, twist=30.0):
    fig.groups["spine"].set_angles(fig, np.radians([flexion, 0.0, twist]))
    return fig


def test_skin_is_one_closed_outward_surface(human):
    skin = skin_for(human)
    edges = np.sort(skin.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2)  # watertight, manifold: no holes, no seams
    v = skin.vertices[skin.faces]
    assert np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6 > 0.02  # m^3, outward
    assert skin.bones == SPINE_SEGMENTS


def test_weights_blend_two_neighbouring_bones(human):
    skin = skin_for(human)
    assert np.allclose(skin.weights.sum(axis=1), 1.0)
    assert ((skin.weights > 0).sum(axis=1) <= 2).all()
    pairs = skin.joints[:, :2][skin.weights[:, 1] > 0]
    assert np.all(np.abs(pairs[:, 0] - pairs[:, 1]) == 1)  # only neighbours along the spine
    assert np.all(skin.joints[:, 0] == skin.owner)  # the owner is the heaviest bone
    assert len(np.unique(skin.owner)) == len(SPINE_SEGMENTS)


def test_chain_weights_are_a_partition_of_unity():
    h = np.linspace(-0.1, 1.1, 200)
    w = chain_weights(h, np.array([0.3, 0.6]), np.array([0.1, 0.05]))
    assert np.allclose(w.sum(axis=1), 1.0)
    assert np.all(w[h < 0.2] == [1, 0, 0]) and np.all(w[h > 0.65] == [0, 0, 1])
    assert np.all(np.diff(w[:, 2]) >= 0)  # monotone: no bone comes back


def test_rest_pose_reproduces_the_rest_mesh(human):
    skin = skin_for(human)
    zero_pose = {b: np.eye(4) for b in skin.bones}
    for b, o in zip(skin.bones, skin.origins):
        zero_pose[b][:3, 3] = o  # every segment frame at its zero-pose origin, world-parallel
    p, n = deform(skin, bone_matrices(skin, zero_pose))
    assert np.allclose(p, skin.vertices, atol=1e-12)
    assert np.allclose(n, skin.normals, atol=1e-12)
    # the neutral standing posture (straight spine): every vertex moves exactly as its owner's rigid surface
    m = bone_matrices(skin, human.world_transforms())[skin.owner]
    rigid = np.einsum("nij,nj->ni", m[:, :3, :3], skin.vertices) + m[:, :3, 3]
    assert np.allclose(deform(skin, bone_matrices(skin, human.world_transforms()))[0], rigid, atol=1e-9)


def test_skin_has_the_rigid_torso_size(human):
    skin = skin_for(human)
    w = human.world_transforms()
    rigid = np.vstack([human.segment(s).psurf.posed_mesh().transformed(w[s]).vertices for s in SPINE_SEGMENTS])
    p = deform(skin, bone_matrices(skin, w))[0]
    assert np.allclose(p.min(axis=0), rigid.min(axis=0), atol=0.01)
    assert np.allclose(p.max(axis=0), rigid.max(axis=0), atol=0.01)


def test_cpu_skinning_equals_the_renderers(human):
    fig = bent(make_human("male", 50))
    skin = skin_for(fig)
    m = bone_matrices(skin, fig.world_transforms())
    assert np.allclose(SkinnedMesh.of(skin).deform(m), deform(skin, m)[0], atol=1e-5)  # float32 rest data


def test_bent_skin_keeps_its_volume_and_stays_closed():
    fig = bent(make_human("male", 50))
    skin = skin_for(fig)
    p = deform(skin, bone_matrices(skin, fig.world_transforms()))[0]
    v0, v1 = skin.vertices[skin.faces], p[skin.faces]
    vol = [np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6 for v in (v0, v1)]
    assert abs(vol[1] / vol[0] - 1.0) < 0.05  # linear blending over 17 joints loses no visible volume


def test_pieces_reassemble_into_the_skins():
    fig = bent(make_human("female", 5))
    w = fig.world_transforms()
    pieces = skinned_pieces(fig, w)
    skins = skins_for(fig)
    assert set(pieces) == set().union(*(k.covers for k in skins)) >= set(SPINE_SEGMENTS)
    assert sum(len(piece.faces) for piece in pieces.values()) == sum(len(k.faces) for k in skins)
    posed = np.vstack([deform(k, bone_matrices(k, w))[0] for k in skins])
    world = np.vstack([piece.vertices @ w[s][:3, :3].T + w[s][:3, 3] for s, piece in pieces.items()])
    # every piece vertex is a skin vertex (shared boundaries coincide: no seam)
    known = {tuple(p) for p in np.round(posed, 9)}
    assert all(tuple(p) in known for p in np.round(world, 9))
    assert len(world) > len(posed)  # boundary vertices are in both neighbouring pieces


def test_limb_skins_follow_the_rigid_limbs():
    fig = make_human("male", 50)
    skins = skins_for(fig)
    assert [k.bones[-1] for k in skins] == ["t1", "left_upper_arm", "left_thigh", "right_upper_arm", "right_thigh"]
    w = fig.world_transforms()
    for skin in skins[1:]:
        edges = np.sort(skin.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        assert np.all(np.unique(edges, axis=0, return_counts=True)[1] == 2)  # closed
        rigid = np.vstack([fig.segment(b).psurf.posed_mesh().transformed(w[b]).vertices for b in skin.bones])
        p = deform(skin, bone_matrices(skin, w))[0]
        assert np.allclose(p.min(axis=0), rigid.min(axis=0), atol=0.012)  # sized from the rigid surfaces
        assert np.allclose(p.max(axis=0), rigid.max(axis=0), atol=0.012)
        assert ((skin.weights > 0).sum(axis=1) <= 2).all() and np.allclose(skin.weights.sum(axis=1), 1.0)


def test_only_standard_humans_have_a_skin_and_rescale_rebuilds_it():
    assert skin_for(human_like_tree()) is None and skins_for(human_like_tree()) == ()
    fig = make_human("male", 50)
    first = skin_for(fig)
    assert skin_for(fig) is first  # cached
    rescale_in_place(fig, "female", 5)
    smaller = skin_for(fig)
    assert smaller is not first
    assert np.ptp(smaller.vertices[:, 1]) < np.ptp(first.vertices[:, 1])
