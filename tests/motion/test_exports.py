"""Exports of baked motion: BVH in the figure's own hierarchy (re-imports within 1 mm), glTF
binary with a skin, a joint hierarchy and one animation of the motion's duration, CSV."""

from __future__ import annotations

import csv

import numpy as np
import pygltflib
import pytest

from jackpy.motion import cast
from jackpy.motion.bake import Posture
from jackpy.motion.bvh import read
from jackpy.motion.bvh_export import write_bvh
from jackpy.motion.csv_export import write_csv
from jackpy.motion.gltf_export import write_glb
from jackpy.motion.motion_file import BakedFigure
from jackpy.motion.retarget import import_bvh


@pytest.fixture(scope="module")
def baked_motion():
    """A baked motion of a 5th-percentile woman: a real timeline (COM shift, a step, a reach)."""
    from jackpy.commands.motion import bake_motion_file
    from jackpy.motion.kinds.arm import ArmMotion
    from jackpy.motion.kinds.com import COMMotion
    from jackpy.motion.kinds.foot import FootMotion
    from jackpy.motion.motion_file import MotionFile
    from jackpy.motion.timeline import Timeline

    tl = Timeline([COMMotion(figure="jill", t0=0.0, t1=0.3, x=0.2),
                   FootMotion(figure="jill", side="right", t0=0.3, t1=0.7, displacement=[0, 0, 0.2], height=0.08),
                   ArmMotion(figure="jill", side="left", t0=0.1, t1=0.8, target={"point": [0.25, 1.1, 0.35]})],
                  cast={"jill": {"human": "female:5"}})
    tl.duration = 0.9
    mf, _, _ = bake_motion_file(MotionFile(tl), None, 10.0)
    return mf


def site_positions(fig, posture):
    posture.apply_to(fig)
    w = fig.world_transforms()
    return np.array([(w[seg] @ site.location)[:3, 3] for seg in fig.segments for site in fig.segments[seg].sites.values()])


def test_bvh_export_reimports_within_a_millimetre(baked_motion, tmp_path):
    baked = baked_motion.baked["jill"]
    fig = cast.make_figure("jill", {"human": "female:5"})
    path = tmp_path / "jill.bvh"
    write_bvh(fig, baked, baked_motion.fps, path)
    text = path.read_text()
    assert "ROOT pelvis" in text and "JOINT left_thigh" in text
    assert "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation" in text
    bvh = read(str(path))
    assert bvh.frames.shape[0] == baked.n_frames
    # centimetres: the thigh's offset from the pelvis is some 8-9 cm sideways, not 0.08
    assert 5 < np.linalg.norm(bvh.joints[bvh.index("left_thigh")].offset) < 20
    back = import_bvh(path, "female:5", fps=baked_motion.fps).baked["jill"]
    assert back.n_frames == baked.n_frames
    a, b = cast.make_figure("a", {"human": "female:5"}), cast.make_figure("b", {"human": "female:5"})
    worst = max(np.linalg.norm(site_positions(a, baked.posture(a, i)) - site_positions(b, back.posture(b, i)),
                               axis=1).max() for i in range(baked.n_frames))
    assert worst <= 1e-3
    lo, hi = b.lower, b.upper
    for i in range(back.n_frames):
        assert np.all(back.q[i] >= lo - 1e-12) and np.all(back.q[i] <= hi + 1e-12)


def _node_world(doc, nodes, k, t_index, anim):
    """World matrix of node k at key ``t_index`` from the animation's channels."""
    from scipy.spatial.transform import Rotation

    blob = doc.binary_blob()

    def data(acc_index, width):
        acc = doc.accessors[acc_index]
        view = doc.bufferViews[acc.bufferView]
        return np.frombuffer(blob[view.byteOffset:view.byteOffset + view.byteLength], dtype=np.float32).reshape(
            acc.count, width)

    local = {}
    for ch in anim.channels:
        s = anim.samplers[ch.sampler]
        width = 3 if ch.target.path == "translation" else 4
        local.setdefault(ch.target.node, {})[ch.target.path] = data(s.output, width)[t_index]
    parent = {c: i for i, n in enumerate(nodes) for c in (n.children or [])}
    m = np.eye(4)
    chain = [k]
    while chain[-1] in parent:
        chain.append(parent[chain[-1]])
    for i in reversed(chain):
        t = np.eye(4)
        t[:3, :3] = Rotation.from_quat(local[i]["rotation"]).as_matrix()
        t[:3, 3] = local[i]["translation"]
        m = m @ t
    return m


def test_glb_has_a_skin_a_hierarchy_and_one_animation_of_the_motions_length(baked_motion, tmp_path):
    baked = baked_motion.baked["jill"]
    fig = cast.make_figure("jill", {"human": "female:5"})
    path = tmp_path / "jill.glb"
    write_glb(fig, baked, baked_motion.fps, path)
    doc = pygltflib.GLTF2().load(str(path))
    assert len(doc.skins) == 1 and len(doc.skins[0].joints) == len(fig.segments)
    assert len(doc.animations) == 1
    anim = doc.animations[0]
    times = doc.accessors[anim.samplers[0].input]
    assert times.count == baked.n_frames  # the same number of frames
    assert times.max[0] == pytest.approx(baked_motion.duration, abs=1e-6)
    root = doc.nodes[doc.skins[0].joints[0]]
    assert root.name == "pelvis" and root.children  # a joint hierarchy, not flat nodes
    mesh_node = next(n for n in doc.nodes if n.mesh is not None)
    assert mesh_node.skin == 0
    # skinning reproduces jackpy's posed surface: a vertex of the left foot at the last frame
    from scipy.spatial.transform import Rotation  # noqa: F401

    k = doc.skins[0].joints.index(next(i for i, n in enumerate(doc.nodes) if n.name == "left_foot"))
    blob = doc.binary_blob()
    acc = doc.accessors[doc.skins[0].inverseBindMatrices]
    view = doc.bufferViews[acc.bufferView]
    ibm = np.frombuffer(blob[view.byteOffset:view.byteOffset + view.byteLength], dtype=np.float32).reshape(-1, 4, 4)
    inv_bind = ibm[k].T.astype(float)
    last = baked.n_frames - 1
    world = _node_world(doc, doc.nodes, k, last, anim)
    mesh = fig.segment("left_foot").psurf.posed_mesh()
    from jackpy.body.human import set_neutral_posture

    set_neutral_posture(fig)
    rest = fig.world_transforms()["left_foot"]
    v_local = mesh.vertices[0]
    v_rest = rest[:3, :3] @ v_local + rest[:3, 3]
    skinned = (world @ inv_bind @ np.append(v_rest, 1.0))[:3]
    baked.posture(fig, last).apply_to(fig)
    now = fig.world_transforms()["left_foot"]
    assert np.linalg.norm(skinned - (now[:3, :3] @ v_local + now[:3, 3])) < 1e-4
    # and trimesh, a second reader, loads it
    import trimesh

    assert len(trimesh.load(str(path)).geometry) == 1


def test_csv_has_one_row_per_frame(baked_motion, tmp_path):
    baked = baked_motion.baked["jill"]
    fig = cast.make_figure("jill", {"human": "female:5"})
    path = tmp_path / "jill.csv"
    write_csv(fig, baked, baked_motion.fps, path)
    rows = list(csv.reader(path.open()))
    assert rows[0][:3] == ["time_s", "root", "x_m"] and len(rows) == baked.n_frames + 1
    assert float(rows[-1][0]) == pytest.approx(baked_motion.duration)
    assert np.array_equal(np.array(rows[5][9:], dtype=float), baked.q[4])


def test_posture_of_round_trips():
    fig = cast.make_figure("x")
    p = Posture.of(fig)
    b = BakedFigure.from_postures(fig, [p, p])
    assert b.posture(fig, 1).same(p)
