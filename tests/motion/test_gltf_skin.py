"""glTF export of a standard human: torso, arms and legs are continuous skins, blended over their joints,
and a glTF viewer's skinning of the exported animation gives the workbench's surface."""

import numpy as np
import pygltflib as gl
from scipy.spatial.transform import Rotation

from jackpy.body import make_human, set_neutral_posture
from jackpy.body.skin import SPINE_SEGMENTS, bone_matrices, deform, skins_for
from jackpy.motion.bake import Posture
from jackpy.motion.gltf_export import build_gltf
from jackpy.motion.motion_file import BakedFigure

COMPONENTS = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}
DTYPES = {5126: np.float32, 5123: np.uint16, 5125: np.uint32}


def accessor(doc: gl.GLTF2, blob: bytes, index: int) -> np.ndarray:
    acc = doc.accessors[index]
    view = doc.bufferViews[acc.bufferView]
    data = np.frombuffer(blob, DTYPES[acc.componentType], acc.count * COMPONENTS[acc.type], view.byteOffset)
    return data.reshape(acc.count, -1)


def trs(t, q) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = Rotation.from_quat(q).as_matrix()
    m[:3, 3] = t
    return m


def test_the_exported_body_is_the_blended_skin():
    fig = make_human("male", 50)
    set_neutral_posture(fig)
    frames = [Posture.of(fig)]
    fig.groups["spine"].set_angles(fig, np.radians([60.0, 0.0, 30.0]))
    frames.append(Posture.of(fig))
    bent_world = fig.world_transforms()
    doc = build_gltf(fig, BakedFigure.from_postures(fig, frames), fps=10.0)
    doc = gl.GLTF2.load_from_bytes(b"".join(doc.save_to_bytes()))  # as a reader sees it
    blob = doc.binary_blob()
    attrs = doc.meshes[0].primitives[0].attributes
    pos, joints, weights = (accessor(doc, blob, a) for a in (attrs.POSITION, attrs.JOINTS_0, attrs.WEIGHTS_0))
    assert np.allclose(weights.sum(axis=1), 1.0, atol=1e-6)
    names = [n.name for n in doc.nodes]
    blended = weights[:, 1] > 0
    assert blended.sum() > 1000
    blended_nodes = {names[j] for j in np.unique(joints[blended][:, :2])}
    assert set(SPINE_SEGMENTS) | {"left_forearm", "right_shank"} <= blended_nodes  # spine, elbows, knees...
    assert not blended_nodes & {"head", "left_palm", "right_foot"}  # ...not the rigid parts

    # a viewer's skinning at the second key: node worlds from the animation, then LBS with the IBMs
    anim = doc.animations[0]
    local = {}
    for ch in anim.channels:
        out = accessor(doc, blob, anim.samplers[ch.sampler].output)[1]
        local.setdefault(ch.target.node, {})[ch.target.path] = out
    skin = doc.skins[0]
    parent = {c: k for k, n in enumerate(doc.nodes) for c in (n.children or [])}
    world = {}

    def node_world(k):
        if k not in world:
            m = trs(local[k]["translation"], local[k]["rotation"])
            world[k] = m if k not in parent else node_world(parent[k]) @ m
        return world[k]

    ibm = accessor(doc, blob, skin.inverseBindMatrices).reshape(-1, 4, 4).transpose(0, 2, 1)
    joint_m = np.stack([node_world(j) @ ibm[i] for i, j in enumerate(skin.joints)])
    m = np.einsum("nk,nkij->nij", weights.astype(float), joint_m[joints])
    viewer = np.einsum("nij,nj->ni", m[:, :3, :3], pos.astype(float)) + m[:, :3, 3]

    expected = np.vstack([deform(k, bone_matrices(k, bent_world))[0] for k in skins_for(fig)])
    n = len(expected)  # the skins come first in the exported mesh
    assert np.abs(viewer[:n] - expected).max() < 2e-4  # float32 file data
