"""Reading Peabody .fig/.env text: the book's table, units, product rule, groups, errors."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from jackpy.errors import FigureError, ParseError
from jackpy.peabody.model import Figure
from jackpy.peabody.reader import load, parse_environment, parse_figures, read_environment, read_figures
from jackpy.peabody.transforms import rotation, translation

FIGURES = Path(__file__).resolve().parents[2] / "figures"
SPEC = Path("/work/shared/spec/body-model.md")


def one(text: str) -> Figure:
    return parse_figures(text, "t.fig")[0]


def seg(body: str, name: str = "a") -> str:
    return f"segment {name} {{ {body} }}\n"


TWO = ("figure f {\n" + seg("site s->location = trans(0cm,0cm,0cm);")
       + seg("site s->location = trans(0cm,0cm,0cm);", "b"))


def test_table_leg_bases_land_as_in_the_book() -> None:
    fig = read_figures(FIGURES / "table.fig")[0]
    world = fig.world_transforms()
    expected = {"leg": (90, 0, 0), "leg0": (0, 0, 0), "leg1": (90, 0, 190), "leg2": (0, 0, 190), "top": (0, 75, 0)}
    for name, xyz in expected.items():
        np.testing.assert_allclose(world[name][:3, 3], np.array(xyz) / 100, atol=1e-12)
    assert fig.root == ("top", "base") and fig.ndof == 4
    top = fig.segment("top").psurf
    assert top.source == "cube.pss" and top.mesh is not None
    np.testing.assert_allclose(top.posed_mesh().bounds(), [[0, 0, 0], [1.0, 0.1, 2.0]], atol=1e-12)


def test_book_listing_from_the_spec_parses_like_the_shipped_file() -> None:
    if not SPEC.exists():
        pytest.skip("spec digest not available")
    listing = re.search(r"```\n(figure table \{.*?\n\})\n```", SPEC.read_text(), re.S).group(1)
    a = parse_figures(listing, "book.fig")[0]
    b = read_figures(FIGURES / "table.fig", require_geometry=False)[0]
    from jackpy.peabody.compare import figure_differences

    assert figure_differences(a, b) == []


def test_row_vector_product_rule_for_locations() -> None:
    fig = one("figure f {\nlocation = trans(10cm,0cm,0cm) * rotz(90);\n" + seg("") + "}")
    # translate first, then rotate about the fixed z axis: column form R @ T
    np.testing.assert_allclose(fig.location, rotation("z", np.pi / 2) @ translation(0.1, 0, 0), atol=1e-15)
    np.testing.assert_allclose(fig.location[:3, 3], [0, 0.1, 0], atol=1e-15)


def test_units_lengths_and_angles() -> None:
    text = ("figure f {\n" + seg("site s->location = trans(10mm, 0.5m, 1in) * rot(0,0,2, 1.5707963267948966rad);")
            + "}")
    loc = one(text).segment("a").site("s").location
    np.testing.assert_allclose(loc, rotation("z", np.pi / 2) @ translation(0.01, 0.5, 0.0254), atol=1e-15)


def test_psurf_transform_product_and_scale_text() -> None:
    fig = one("figure f {\n" + seg('psurf = "x.pss" * scale(2,1,1) * trans(1cm,0cm,0cm);') + "}")
    ps = fig.segment("a").psurf
    np.testing.assert_allclose(ps.transform, translation(0.01, 0, 0) @ np.diag([2.0, 1, 1, 1]))
    assert ps.scale_text == [("scale", (2.0, 1.0, 1.0)), ("trans", (1.0, 0.0, 0.0))]
    assert ps.mesh is None  # parse_figures never touches files


def test_joint_type_order_limits_displacement_and_translation_dofs() -> None:
    text = TWO + """joint j { connect a.s to b.s; type = R(x) * T(y) * R(1,1,0);
        lower = (-90, -5cm, -1rad); upper = (90deg, 50mm, 1); displacement = (30, 2, 0.5deg); }}"""
    j = one(text).joint("j")
    assert [d.kind for d in j.dofs] == ["R", "T", "R"]
    np.testing.assert_allclose(j.dofs[2].axis, np.array([1, 1, 0]) / np.sqrt(2))
    np.testing.assert_allclose(j.lower, [-np.pi / 2, -0.05, -1.0])
    np.testing.assert_allclose(j.upper, [np.pi / 2, 0.05, np.radians(1)])
    np.testing.assert_allclose(j.displacement, [np.radians(30), 0.02, np.radians(0.5)])
    a, t, b = (d.transform(v) for d, v in zip(j.dofs, j.displacement))
    np.testing.assert_allclose(j.transform(), b @ t @ a)  # type A * B * C is C @ B @ A


def test_default_limits_and_clamped_default_displacement() -> None:
    j = one(TWO + "joint j { connect a.s to b.s; type = R(z) * T(x); lower = (10, -1); upper = (20, 1); }}").joint("j")
    np.testing.assert_allclose(j.displacement, [np.radians(10), 0.0])
    k = one(TWO + "joint k { connect a.s to b.s; type = R(y) * T(z); }}").joint("k")
    np.testing.assert_allclose(k.lower, [-np.pi, -10.0])
    np.testing.assert_allclose(k.upper, [np.pi, 10.0])


def test_mass_com_inertia_and_attributes() -> None:
    body = ('mass = 2.5kg; com = (1, 2, 3)cm; inertia = (100, 200, 300, 1, 2, 3); attribute = "light blue";'
            "site s->location = trans(0cm,0cm,0cm);")
    s = one("figure f {\n" + seg(body) + "}").segment("a")
    assert s.mass == 2.5 and s.attribute == "light blue"
    np.testing.assert_allclose(s.com, [0.01, 0.02, 0.03])
    np.testing.assert_allclose(s.inertia, np.array([[100, 1, 2], [1, 200, 3], [2, 3, 300]]) * 1e-4)


def test_comments_of_every_kind() -> None:
    text = "# hash\n// slashes\n/* block\n over lines */ figure f { /* inline */ segment a { } } // end"
    assert one(text).name == "f"


def test_finger_group_drives_its_joints() -> None:
    fig = read_figures(FIGURES / "finger.fig")[0]
    g = fig.groups["curl"]
    assert g.joints == ["mcp", "pip", "dip"] and g.angle_names == ["curl"]
    np.testing.assert_allclose(g.angles, [np.radians(30)])
    np.testing.assert_allclose(fig.q, np.radians([27, 33, 24]))
    np.testing.assert_allclose(g.A, [[1.1]])
    np.testing.assert_allclose(g.b, [np.radians(99)])
    assert not g.is_feasible(np.radians([92.0]))  # inside the box, outside the linear limit


def test_group_limit_expression_signs_and_translation_members() -> None:
    text = TWO + """joint j { connect a.s to b.s; type = R(x) * T(y); }
      group g { joints = j; angles = p, q; driver = matrix((1, 0), (0, 2)); offset = (5, 1cm);
                limit p - 0.5*q >= -10; limit -q + p <= 20deg; displacement = (1, 2); }}"""
    fig = one(text)
    g = fig.groups["g"]
    np.testing.assert_allclose(g.A, [[-1, 0.5], [1, -1]])
    np.testing.assert_allclose(g.b, np.radians([10, 20]))
    # T member: 2 cm per degree is 0.02 m per (pi/180) rad
    np.testing.assert_allclose(g.driver.matrix, [[1, 0], [0, 0.02 / np.radians(1)]])
    np.testing.assert_allclose(fig.joint("j").displacement, [np.radians(6), 0.05])


def test_environment_includes_places_and_inline_figures() -> None:
    env = read_environment(FIGURES / "workplace.env")
    assert list(env.figures) == ["worktable", "chair", "arm7", "crate"]
    assert env.includes == ["worktable.fig", "chair.fig", "arm7.fig"]
    np.testing.assert_allclose(env.figures["chair"].location,
                               translation(0, 0, 0.55) @ rotation("y", np.pi), atol=1e-15)
    assert all(s.psurf.mesh is not None for f in env.figures.values() for s in f.segments.values() if s.psurf)


def test_environment_rebases_psurf_names_of_included_files(tmp_path: Path) -> None:
    (tmp_path / "props").mkdir()
    (tmp_path / "props" / "box.pss").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (tmp_path / "props" / "box.fig").write_text('figure box { segment b { psurf = "box.pss"; } }')
    (tmp_path / "w.env").write_text('include "props/box.fig";\nplace box at trans(1cm,2cm,3cm);\n')
    env = read_environment(tmp_path / "w.env")
    ps = env.figures["box"].segment("b").psurf
    assert ps.source == "props/box.pss" and ps.mesh is not None and len(ps.mesh.faces) == 1
    np.testing.assert_allclose(env.figures["box"].location[:3, 3], [0.01, 0.02, 0.03])


def test_load_dispatches_on_extension(tmp_path: Path) -> None:
    assert list(load(FIGURES / "table.fig").figures) == ["table"]
    assert "crate" in load(FIGURES / "workplace.env").figures
    (tmp_path / "x.txt").write_text("")
    with pytest.raises(FigureError, match="unknown Peabody file type"):
        load(tmp_path / "x.txt")


def test_missing_geometry_names_file_and_segment(tmp_path: Path) -> None:
    p = tmp_path / "m.fig"
    p.write_text('figure m { segment body { psurf = "nowhere.pss"; } }')
    with pytest.raises(FigureError, match=r"m\.fig:1:35: figure 'm' segment 'body': geometry file 'nowhere\.pss' not found"):
        read_figures(p)
    fig = read_figures(p, require_geometry=False)[0]
    assert fig.segment("body").psurf.mesh is None


# ----- syntax errors: exact file:line:column ----------------------------------------------------
@pytest.mark.parametrize("text, where, message", [
    ("figure f {\n  segment a {\n    site s->location = trans(1cm,2cm,3cm)\n  }\n}", "4:3",
     "expected ';', found '}'"),
    ("figure f {\n  segment a { site s->location = tran(1cm,2cm,3cm); }\n}", "2:34",
     "expected a transform (trans, scale, rotx, roty, rotz, rot, matrix), found 'tran'"),
    ('figure f {\n  segment a { psurf = "x.pss; }\n}', "2:23", "unterminated string"),
    ("figure f { /* never closed\n", "1:12", "unterminated comment"),
    ("figure f {\n  segment a @ { }\n}", "2:13", "unexpected character '@'"),
    ("figure f {\n  segment a { site s->location = trans(1furlong,0,0); }\n}", "2:41",
     "expected a unit (cm, mm, m, in, deg, rad), found 'furlong'"),
    ("figure f {\n  segment a { }\n", "3:1", "expected 'segment', 'joint', 'group', 'root', 'location', 'human' or '}', "
     "found end of file"),
    ("figure f {\n  joint j { type = Q(z); }\n}", "2:20", "expected a DOF R(axis) or T(axis), found 'Q'"),
    ("figure f {\n  segment a { site s->location = trans(1cm,2cm); }\n}", "2:47", "expected ',', found ')'"),
    ("figure f {\n  root = a;\n}", "2:11", "expected '.' in SEGMENT.SITE, found ';'"),
    ("segment a { }", "1:1", "expected 'figure', found 'segment'"),
])
def test_syntax_errors_report_file_line_column(text: str, where: str, message: str) -> None:
    with pytest.raises(ParseError) as info:
        parse_figures(text, "bad.fig")
    assert str(info.value).startswith(f"bad.fig:{where}: ")
    assert message in str(info.value)


# ----- semantic errors name the part at fault ---------------------------------------------------
@pytest.mark.parametrize("joint, message", [
    ("joint j { connect a.s to b.nope; type = R(z); }", "joint 'j' names unknown site b.nope"),
    ("joint j { connect a.s to a.s; type = R(z); }", "joint 'j' connects segment 'a' to itself"),
    ("joint j { connect a.s to b.s; type = R(z); } joint k { connect b.s to a.s; type = R(x); }",
     "joint 'k' closes a cycle"),
    ("joint j { connect a.s to b.s; type = R(z); lower = (-10); upper = (10); displacement = (20); }",
     "joint 'j' DOF 0: displacement 20 deg outside limits [-10, 10] deg"),
    ("joint j { connect a.s to b.s; type = R(z) * R(x); displacement = (1); }",
     "joint 'j': displacement has 1 values for 2 DOFs"),
    ("joint j { connect a.s to b.s; type = R(z); displacement = (3cm); }",
     "joint 'j' DOF 0 (rotation): expected a unit among deg, rad, found 'cm'"),
    ("joint j { type = R(z); }", "joint 'j': no 'connect"),
    ("joint j { connect a.s to b.s; type = R(0,0,0); }", "DOF axis has no direction"),
    ("group g { joints = nope; angles = t; driver = matrix((1)); }", "group 'g': unknown joint 'nope'"),
    ("joint j { connect a.s to b.s; type = R(z); } group g { joints = j; angles = t; driver = matrix((1, 2)); }",
     "driver matrix must have 1 rows (member DOFs) of 1 values"),
    ("joint j { connect a.s to b.s; type = R(z); } group g { joints = j; angles = t; driver = matrix((1));"
     " limit u <= 3; }", "limit names unknown group angle 'u'"),
])
def test_semantic_errors_name_the_joint(joint: str, message: str) -> None:
    with pytest.raises(FigureError) as info:
        parse_figures(TWO + joint + "}", "sem.fig")
    assert str(info.value).startswith("sem.fig:")
    assert message in str(info.value)


@pytest.mark.parametrize("text, message", [
    ("figure f { segment a { } segment a { } }", "sem.fig:1:34: figure 'f': duplicate segment 'a'"),
    ("figure f { segment a { site s->location = scale(2,2,2); } }", "a location must be rigid"),
    ("figure f { segment a { site s->location = trans(0cm,0cm,0cm); site s->location = trans(0cm,0cm,0cm); } }",
     "segment 'a': duplicate site 's'"),
    ("figure f { segment a { mass = -1; } }", "mass must not be negative"),
    ("figure f { segment a { } root = a.x; }", "root names unknown site a.x"),
    ("figure f { segment a { } } figure f { segment b { } }", "duplicate figure 'f'"),
])
def test_other_semantic_errors(text: str, message: str) -> None:
    with pytest.raises(FigureError, match=re.escape(message)):
        parse_figures(text, "sem.fig")


def test_environment_errors(tmp_path: Path) -> None:
    with pytest.raises(FigureError, match=r"e\.env:2:7: place: environment has no figure 'ghost'"):
        parse_environment("figure a { segment s { } }\nplace ghost at trans(0cm,0cm,0cm);", "e.env", tmp_path)
    with pytest.raises(FigureError, match=r"e\.env:1:9: cannot read included file 'missing\.fig'"):
        parse_environment('include "missing.fig";', "e.env", tmp_path)
    with pytest.raises(ParseError, match=r"e\.env:1:1: expected 'include', 'place' or 'figure', found 'segment'"):
        parse_environment("segment s { }", "e.env", tmp_path)


def test_non_utf8_file_is_a_parse_error(tmp_path: Path) -> None:
    p = tmp_path / "b.fig"
    p.write_bytes(b"figure f {\n  \xff }")
    with pytest.raises(ParseError, match=r"b\.fig:2:3: expected UTF-8 text"):
        read_figures(p)
