"""The creature editor's model (Sims Ch. 4, App. A): editing, network analysis, the 3-D build, and
the headless acceptance: draw a 6-legged insect, build it, it walks on flat ground unaided."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings, strategies as st

from jackpy.errors import FigureError, ParseError
from jackpy.locomotion.creature_editor import (SNAP, Drawing, Editor, analyse, build, inside_lasso,
                                               save_figure)
from jackpy.locomotion.legs import find_legs
from jackpy.peabody.reader import load


def draw_insect() -> Editor:
    """An insect drawn the way a user would: a body line, one left leg, copied twice down the
    body, then the left legs mirror-copied to the right."""
    ed = Editor()
    head = ed.add_node(0.3, -20)  # snaps onto the axis
    mid = ed.add_node(0, 0, connect_from=head)
    tail = ed.add_node(0, 20, connect_from=mid)
    knee = ed.add_node(-14, -20, connect_from=head)
    ed.add_node(-32, -20, connect_from=knee)
    ed.selection = {3, 4}
    ed.translate(0, 20, copy_=True)  # copy the leg down to the middle node
    ed.connect(mid, min(ed.selection))
    ed.selection = {3, 4}
    ed.translate(0, 40, copy_=True)
    ed.connect(tail, min(ed.selection))
    ed.selection = {i for i, (x, _) in enumerate(ed.drawing.nodes) if x < 0}
    before = len(ed.drawing.nodes)
    ed.mirror_x(copy_=True)
    for i in range(3):  # join the mirrored knees to the body
        knee_l = 3 + 2 * i
        x, y = ed.drawing.nodes[knee_l]
        ed.connect({-20: head, 0: mid, 20: tail}[int(y)], ed.node_at(-x, y))
    assert len(ed.drawing.nodes) == before + 6
    return ed


def test_draw_build_and_walk_an_insect_headless(tmp_path):
    from jackpy.locomotion.config import WalkConfig
    from jackpy.locomotion.creature_walk import walk
    from jackpy.locomotion.terrain import Terrain

    ed = draw_insect()
    an = analyse(ed.drawing)
    assert len(an.legs) == 6 and not an.of("head") and not an.of("tail")
    save_figure(build(ed.drawing), tmp_path / "insect.fig")
    fig = load(tmp_path / "insect.fig").figures["creature"]
    flat = Terrain.flat(6.0, 0.25)
    r = walk(fig, flat, (0.0, 1.0), config=WalkConfig(fps=10.0))
    assert len(r.legs) == 6 and r.gait.name == "wave"
    assert np.hypot(*(r.body_xz(-1) - r.goal)) < 0.2
    gap = np.abs(r.feet[..., 1])
    assert gap[r.stance].max() < 0.005


def test_network_analysis_of_a_spider_with_a_stray_node():
    d = Drawing(nodes=[[0, -10], [0, 10]], links=[(0, 1)])
    for body in (0, 1):
        for side in (-1, 1):
            for dy in (-6, 6):
                a = len(d.nodes)
                y = d.nodes[body][1]
                d.nodes += [[side * 15, y + dy], [side * 30, y + 2 * dy]]
                d.links += [(body, a), (a, a + 1)]
    d.nodes.append([50, 50])  # stray
    an = analyse(d)
    assert len(an.legs) == 8
    assert an.body == [0, 1]
    assert all(len(a.nodes) == 3 for a in an.legs)
    assert len(d.nodes) - 1 not in {n for a in an.appendages for n in a.nodes}


def test_head_and_tail_are_found():
    d = Drawing.load(_example("quadruped"))
    an = analyse(d)
    assert len(an.legs) == 4 and len(an.of("head")) == 1 and len(an.of("tail")) == 1
    head = an.of("head")[0]
    assert d.nodes[head.nodes[-1]][1] < d.nodes[head.nodes[0]][1]


def _example(name):
    from pathlib import Path

    return Path(__file__).resolve().parents[2] / "examples" / "creatures" / f"{name}.drawing.json"


def test_mapping_and_mirror_symmetry():
    d = Drawing.load(_example("hexapod"))
    fig = build(d)
    legs = find_legs(fig)
    left = sorted((g for g in legs if g.side > 0), key=lambda g: g.order)
    right = sorted((g for g in legs if g.side < 0), key=lambda g: g.order)
    for a, b in zip(left, right):
        assert np.allclose(a.hip_body * [-1, 1, 1], b.hip_body)
        assert np.allclose(a.neutral_body * [-1, 1, 1], b.neutral_body)
    # drawing (x, y) -> world (-x, 0, -y) cm: the drawn front leg (y = -20) is at +z, the screen's
    # left (x < 0) is the creature's left (+x)
    assert left[0].hip_body[2] == pytest.approx(0.2) and left[0].neutral_body[0] > 0


def test_axis_styles_and_ball_joints():
    ins = build(Drawing.load(_example("hexapod")))
    mam = build(Drawing.load(_example("quadruped")))
    for fig, style in ((ins, "insect"), (mam, "mammal")):
        for jn, j in fig.joints.items():
            if not jn.startswith("leg_"):
                continue
            base = jn.endswith("_1")
            assert j.ndof == (2 if base else 1)  # a ball joint (two axes) at each leg base
            seg = fig.segments[j.to_seg]
            d = seg.sites[[s for s in seg.sites if s != "proximal"][0]].location[:3, 3]
            d = d / np.linalg.norm(d)
            axes = [dof.axis for dof in j.dofs]
            if style == "insect":  # horizontal, perpendicular to the leg; the base's outer axis vertical
                assert abs(axes[0][1]) < 1e-12 and abs(axes[0] @ d) < 1e-12
                if base:
                    assert np.allclose(np.abs(axes[1]), [0, 1, 0])
            else:  # vertical in the creation pose; the base's outer axis folds the leg (horizontal)
                assert np.allclose(np.abs(axes[0]), [0, 1, 0])
                if base:
                    assert abs(axes[1][1]) < 1e-12


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.floats(-10, 10), st.floats(-10, 10)), min_size=3, max_size=12),
       st.tuples(st.floats(-10, 10), st.floats(-10, 10)))
def test_lasso_agrees_with_shapely(poly, p):
    ring = shapely.Polygon(poly)
    if not ring.is_valid or ring.area < 1e-3:
        return
    if ring.exterior.distance(shapely.Point(p)) < 1e-6:
        return
    assert inside_lasso(p, poly) == ring.contains(shapely.Point(p))
    assert inside_lasso(p, poly[::-1]) == ring.contains(shapely.Point(p))


def test_snapping_undo_delete_undelete():
    ed = Editor()
    a = ed.add_node(SNAP * 0.5, 7.0)
    assert ed.drawing.nodes[a] == [0.0, 7.0]
    b = ed.add_node(5.0, 5.0, connect_from=a)
    ed.delete([a])
    assert len(ed.drawing.nodes) == 1 and ed.drawing.links == []
    assert ed.undelete() and len(ed.drawing.nodes) == 2 and ed.drawing.links == [(a, b)]
    ed.select_lasso([[4, 4], [6, 4], [6, 6], [4, 6]])
    assert ed.selection == {b}
    ed.scale(2.0)
    assert ed.drawing.nodes[b] == [10.0, 10.0]
    ed.undo()
    assert ed.drawing.nodes[b] == [5.0, 5.0]
    ed.rotate(math.pi / 2)
    assert np.allclose(ed.drawing.nodes[b], [-5.0, 5.0])


def test_bad_drawings(tmp_path):
    (tmp_path / "d.json").write_text('{"nodes": [[0, 0], [1, 1]],\n "links": [[0, 0]]}')
    with pytest.raises(ParseError, match="links\\[0\\]"):
        Drawing.load(tmp_path / "d.json")
    with pytest.raises(FigureError):
        build(Drawing(nodes=[[0, 0], [1, 0], [2, 0]], links=[(0, 1), (1, 2)]))  # a chain has no body


def test_drawing_round_trip(tmp_path):
    d = draw_insect().drawing
    d.save(tmp_path / "i.json")
    assert Drawing.load(tmp_path / "i.json").to_dict() == d.to_dict()


_json = st.recursive(st.none() | st.booleans() | st.integers(-5, 40) | st.floats(allow_nan=False) | st.text(max_size=5),
                     lambda c: st.lists(c, max_size=4) | st.dictionaries(st.sampled_from(
                         ["nodes", "links", "style", "units", "name", "thickness", "body_thickness"]), c, max_size=5),
                     max_leaves=20)


@settings(max_examples=150, deadline=None)
@given(_json)
def test_fuzzed_drawings_parse_or_fail_cleanly(data):
    try:
        d = Drawing.from_dict(data, "fuzz.json")
    except ParseError as exc:
        assert str(exc).startswith("fuzz.json: ")
        return
    try:
        build(d)
    except FigureError:
        pass
