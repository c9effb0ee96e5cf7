"""glTF binary (``.glb``) export of baked motion as a **skinned mesh** with a node hierarchy and one
animation, written with pygltflib (the container library; it reads the file back in the tests).

- one node per segment, in the figure's tree from the pelvis (:func:`.bvh_export.hierarchy`), each
  with its rest (neutral posture) translation and rotation relative to its parent;
- one mesh: every segment's surface at rest in world coordinates, each vertex bound rigidly to its
  segment (JOINTS_0 = that segment's joint index, WEIGHTS_0 = 1), with vertex normals; a standard
  human's torso, arms and legs are its continuous skins (:mod:`jackpy.body.skin`) instead, each
  vertex with its blend of up to four joints, so viewers bend it as the workbench does;
- one skin over all segment nodes; inverse bind matrices are the inverses of the rest world
  transforms;
- one animation ``motion``: per node a translation and a rotation channel (LINEAR), one key per
  baked frame at ``i / fps`` seconds, so its duration equals the motion's ((N - 1) / fps).

Units metres, y up, as glTF wants.
"""

from __future__ import annotations

import os

import numpy as np
import pygltflib as gl
from scipy.spatial.transform import Rotation

from jackpy.body.skin import bone_matrices, deform, skins_for
from jackpy.motion.bvh_export import hierarchy

FLOAT, USHORT, UINT = 5126, 5123, 5125
ARRAY, ELEMENTS = 34962, 34963


class _Buffer:
    """One binary buffer with its views and accessors."""

    def __init__(self, doc: gl.GLTF2) -> None:
        self.doc, self.data = doc, bytearray()

    def add(self, arr: np.ndarray, kind: str, ctype: int, target: int | None = None,
            bounds: bool = False) -> int:
        while len(self.data) % 4:
            self.data.append(0)
        raw = arr.tobytes()
        view = gl.BufferView(buffer=0, byteOffset=len(self.data), byteLength=len(raw))
        if target is not None:
            view.target = target
        self.data += raw
        self.doc.bufferViews.append(view)
        flat = arr.reshape(arr.shape[0], -1)
        acc = gl.Accessor(bufferView=len(self.doc.bufferViews) - 1, componentType=ctype, count=int(arr.shape[0]),
                          type=kind)
        if bounds:
            acc.min = [float(v) for v in flat.min(axis=0)]
            acc.max = [float(v) for v in flat.max(axis=0)]
        self.doc.accessors.append(acc)
        return len(self.doc.accessors) - 1


def _local(world: dict[str, np.ndarray], tree) -> list[np.ndarray]:
    out = []
    for seg, parent, *_ in tree:
        w = world[seg]
        out.append(w if parent < 0 else np.linalg.inv(world[tree[parent][0]]) @ w)
    return out


def _quat(m: np.ndarray) -> np.ndarray:
    """glTF quaternion (x, y, z, w) of a rotation matrix."""
    return Rotation.from_matrix(m).as_quat()


def build_gltf(figure, baked, fps: float) -> gl.GLTF2:
    """The glTF document of ``baked`` frames of ``figure`` (see the module docstring)."""
    from jackpy.body.human import set_neutral_posture

    try:
        set_neutral_posture(figure)
    except Exception:
        pass
    tree = hierarchy(figure)
    rest = figure.world_transforms()
    doc = gl.GLTF2(asset=gl.Asset(version="2.0", generator="jackpy"))
    buf = _Buffer(doc)
    # nodes: one per segment (rest pose), then the mesh node
    locals_rest = _local(rest, tree)
    children: dict[int, list[int]] = {}
    for k, (_, parent, *_r) in enumerate(tree):
        children.setdefault(parent, []).append(k)
    for k, (seg, parent, *_r) in enumerate(tree):
        m = locals_rest[k]
        node = gl.Node(name=seg, translation=[float(v) for v in m[:3, 3]],
                       rotation=[float(v) for v in _quat(m[:3, :3])])
        if children.get(k):
            node.children = children[k]
        doc.nodes.append(node)
    # mesh: rest surfaces in world, rigidly bound
    pos, nrm, joints, weights, faces = [], [], [], [], []
    base = 0
    node = {seg: k for k, (seg, *_r) in enumerate(tree)}
    covered: set[str] = set()
    for skin in skins_for(figure):  # the continuous torso and limbs, blended
        if not skin.covers <= node.keys():
            continue
        p, n = deform(skin, bone_matrices(skin, rest))
        pos.append(p)
        nrm.append(n)
        joints.append(np.array([node[b] for b in skin.bones])[skin.joints])
        weights.append(skin.weights)
        faces.append(skin.faces + base)
        base += len(p)
        covered |= skin.covers
    for k, (seg, *_r) in enumerate(tree):
        if seg in covered:
            continue
        ps = figure.segment(seg).psurf
        mesh = ps.posed_mesh() if ps is not None else None
        if mesh is None or len(mesh.faces) == 0:
            continue
        w = rest[seg]
        pos.append(mesh.vertices @ w[:3, :3].T + w[:3, 3])
        nrm.append(mesh.vertex_normals() @ w[:3, :3].T)
        rigid = np.zeros((len(mesh.vertices), 4))
        rigid[:, 0] = 1.0
        joints.append(np.column_stack([np.full(len(mesh.vertices), k), np.zeros((len(mesh.vertices), 3), int)]))
        weights.append(rigid)
        faces.append(mesh.faces + base)
        base += len(mesh.vertices)
    pos = np.vstack(pos).astype(np.float32)
    nrm = np.vstack(nrm)
    nrm = (nrm / np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-12)).astype(np.float32)
    j4 = np.vstack(joints).astype(np.uint16)
    w4 = np.vstack(weights).astype(np.float32)
    idx = np.concatenate(faces).astype(np.uint32).reshape(-1)
    attrs = gl.Attributes(POSITION=buf.add(pos, "VEC3", FLOAT, ARRAY, bounds=True),
                          NORMAL=buf.add(nrm, "VEC3", FLOAT, ARRAY),
                          JOINTS_0=buf.add(j4, "VEC4", USHORT, ARRAY),
                          WEIGHTS_0=buf.add(w4, "VEC4", FLOAT, ARRAY))
    prim = gl.Primitive(attributes=attrs, indices=buf.add(idx, "SCALAR", UINT, ELEMENTS))
    doc.meshes.append(gl.Mesh(name=figure.name, primitives=[prim]))
    ibm = np.stack([np.linalg.inv(rest[seg]).T for seg, *_r in tree]).astype(np.float32)  # column-major
    doc.skins.append(gl.Skin(name=figure.name, joints=list(range(len(tree))), skeleton=0,
                             inverseBindMatrices=buf.add(ibm, "MAT4", FLOAT)))
    doc.nodes.append(gl.Node(name=f"{figure.name} mesh", mesh=0, skin=0))
    doc.scenes.append(gl.Scene(nodes=[0, len(doc.nodes) - 1]))
    doc.scene = 0
    # the animation
    n = baked.n_frames
    times = (np.arange(n) / fps).astype(np.float32)
    trans = np.empty((len(tree), n, 3), dtype=np.float32)
    rots = np.empty((len(tree), n, 4), dtype=np.float32)
    for i in range(n):
        baked.posture(figure, i).apply_to(figure)
        loc = _local(figure.world_transforms(), tree)
        for k, m in enumerate(loc):
            trans[k, i] = m[:3, 3]
            rots[k, i] = _quat(m[:3, :3])
    for k in range(len(tree)):  # quaternion signs continuous over time
        q = rots[k].astype(float)
        flip = np.cumsum(np.r_[0, (np.sum(q[1:] * q[:-1], axis=1) < 0)]) % 2 == 1
        q[flip] *= -1
        rots[k] = q.astype(np.float32)
    t_acc = buf.add(times.reshape(-1, 1), "SCALAR", FLOAT, bounds=True)
    anim = gl.Animation(name="motion", samplers=[], channels=[])
    for k in range(len(tree)):
        for path, data, kind in (("translation", trans[k], "VEC3"), ("rotation", rots[k], "VEC4")):
            anim.samplers.append(gl.AnimationSampler(input=t_acc, output=buf.add(data, kind, FLOAT),
                                                     interpolation="LINEAR"))
            anim.channels.append(gl.AnimationChannel(sampler=len(anim.samplers) - 1,
                                                     target=gl.AnimationChannelTarget(node=k, path=path)))
    doc.animations.append(anim)
    doc.buffers.append(gl.Buffer(byteLength=len(buf.data)))
    doc.set_binary_blob(bytes(buf.data))
    return doc


def write_glb(figure, baked, fps: float, path: str | os.PathLike) -> None:
    """Write ``baked`` frames of ``figure`` as a binary glTF file, atomically."""
    from jackpy.atomic import atomic_write_bytes

    doc = build_gltf(figure, baked, fps)
    atomic_write_bytes(path, b"".join(doc.save_to_bytes()))
