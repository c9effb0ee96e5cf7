"""Sidecars and the knowledge base: name folding, the book's name map, references that follow a
moved object, on/in resolution and its failure reasons, trimesh suggestions."""

import json

import numpy as np
import pytest

from jackpy.errors import ParseError
from jackpy.scene.workplace import load_workplace
from jackpy.tasks import placement, semantics
from jackpy.tasks.kb import KnowledgeBase
from jackpy.tasks.semantics import TaskError


@pytest.fixture()
def panel_kb(panel_scene):
    env = load_workplace(panel_scene).env
    return KnowledgeBase.for_scene(env, panel_scene.parent)


@pytest.fixture()
def put_kb(put_scene):
    env = load_workplace(put_scene).env
    return KnowledgeBase.for_scene(env, put_scene.parent)


def test_names_fold_and_follow_the_object(panel_kb):
    refs = {panel_kb.resolve(n) for n in ("twf-1", "twF-1", "twf_1", "ctrlpanel.panel.twf_1", "ctrlpanel.twf_1")}
    assert len(refs) == 1
    ref = refs.pop()
    assert np.allclose(panel_kb.world(ref), [0.1325, 1.6302, 0.8086])
    panel_kb.move_object("ctrlpanel", np.array([[1, 0, 0, 0.5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]]))
    assert np.allclose(panel_kb.world(ref), [0.6325, 1.6302, 0.8086])
    with pytest.raises(TaskError, match="nothing in the scene is called 'twf-9'"):
        panel_kb.resolve("twf-9")
    ref, ctl = panel_kb.control("tglJ-1")
    assert ctl.kind == "toggle" and ctl.state == "off" and ctl.value_of("on") == 20


def test_sidecar_errors(tmp_path):
    p = tmp_path / "x.semantics.json"
    p.write_text('{"jackpy_semantics": 1,\n "sites": {"a": {"position": [1, 2]}}}')
    with pytest.raises(ParseError, match=r"x.semantics.json: sites.a.position: expected 3 finite numbers"):
        semantics.load(p)
    p.write_text('{"jackpy_semantics": 1,\n "sites": [}')
    with pytest.raises(ParseError, match=r"x.semantics.json:2:12: expected JSON"):
        semantics.load(p)
    p.write_text(json.dumps({"jackpy_semantics": 1, "sites": {"a": {"position": [0, 0, 0]}},
                             "controls": {"a": {"states": {"on": 20, "off": -20}, "limits": [0, 30]}}}))
    with pytest.raises(ParseError, match="outside the limits"):
        semantics.load(p)


def test_on_resting_pose_face_down_inside_and_free(put_kb):
    T, face = placement.resting_pose(put_kb, "block", "table")
    verts = put_kb.env.figures["block"].mesh().vertices @ T[:3, :3].T + T[:3, 3]
    assert verts[:, 1].min() == pytest.approx(0.75, abs=1e-9)
    assert face == "side_1"  # already face down: the least rotation
    put_kb.env.figures["block"].location = T
    put_kb.rest_on("block", "table")
    put_kb.env.figures["crate"].location = T.copy()  # pretend a second object stands there
    put_kb.rest_on("crate", "table")
    with pytest.raises(TaskError, match="not free"):
        placement.resting_pose(put_kb, "block", "table", at=T[:3, 3])
    with pytest.raises(TaskError, match="does not fit on 'table'"):
        placement.resting_pose(put_kb, "block", "table", at=np.array([5.0, 0.75, 0.0]))


def test_in_checks(put_kb):
    with pytest.raises(TaskError, match="'block' does not fit in 'smallbox'"):
        placement.container_pose(put_kb, "block", "smallbox")
    with pytest.raises(TaskError, match="'table' is not a container"):
        placement.container_pose(put_kb, "block", "table")
    box = put_kb.env.figures["smallbox"]
    box.location = box.location @ np.diag([1.0, -1.0, -1.0, 1.0])  # upside down
    with pytest.raises(TaskError, match="not normally oriented"):
        placement.container_pose(put_kb, "block", "smallbox")


def test_suggest_block(put_kb):
    m = put_kb.env.figures["block"].mesh()
    s = semantics.suggest(m.vertices, m.faces)
    normals = {tuple(np.round(f["normal"]).astype(int)) for f in s["self_supporting_faces"]}
    assert len(normals) == 6 and (0, -1, 0) in normals
    assert np.allclose(s["support_surfaces"][0]["normal"], [0, 1, 0])
    t = put_kb.env.figures["table"].mesh()
    assert abs(semantics.suggest(t.vertices, t.faces)["longitudinal_axis"][0]) == pytest.approx(1.0)
