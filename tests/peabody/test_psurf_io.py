"""Psurf (.pss) text and the trimesh-backed mesh formats."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import trimesh

from jackpy.errors import ImportCADError, ParseError
from jackpy.peabody.geometry import Mesh
from jackpy.peabody.psurf_io import load_mesh, parse_psurf, psurf_to_text, read_psurf, write_psurf

FIGURES = Path(__file__).resolve().parents[2] / "figures"


def test_quads_are_triangulated_and_centimetres_become_metres() -> None:
    text = "# a unit square, 10 cm\nv 0 0 0\nv 10 0 0 // comment\nv 10 10 0\nv 0 10 0\n\nf 1 2 3 4\n"
    mesh = parse_psurf(text)
    np.testing.assert_allclose(mesh.vertices[2], [0.1, 0.1, 0.0])
    assert mesh.faces.tolist() == [[0, 1, 2], [0, 2, 3]]


def test_shipped_psurfs_are_closed_and_outward() -> None:
    for p in sorted(FIGURES.glob("*.pss")):
        m = read_psurf(p)
        tm = trimesh.Trimesh(m.vertices, m.faces, process=False)
        assert tm.is_winding_consistent and tm.volume > 0, p.name
    np.testing.assert_allclose(read_psurf(FIGURES / "cube.pss").bounds(), [[0, 0, 0], [1, 1, 1]])
    np.testing.assert_allclose(read_psurf(FIGURES / "leg.pss").bounds(), [[0, 0, 0], [0.1, 0.75, 0.1]])


def test_write_read_round_trip(tmp_path: Path) -> None:
    rng = np.random.default_rng(3)
    mesh = Mesh(rng.normal(size=(20, 3)), rng.integers(0, 20, size=(30, 3)))
    write_psurf(tmp_path / "r.pss", mesh, comment="random\nmesh")
    back = read_psurf(tmp_path / "r.pss")
    np.testing.assert_allclose(back.vertices, mesh.vertices, atol=0.5e-6)  # 1e-4 cm rounding
    assert np.array_equal(back.faces, mesh.faces)
    assert psurf_to_text(mesh).count("\n") == 50


@pytest.mark.parametrize("text, where, message", [
    ("v 0 0\n", "1:6", "expected three coordinates (cm) after 'v'"),
    ("v 0 0 0 0\n", "1:9", "expected end of line after 'v'"),
    ("v 0 zero 0\n", "1:5", "expected a coordinate (cm), found 'zero'"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "4:7", "expected a vertex index in 1..3, found '4'"),
    ("v 0 0 0\nf 1 1\n", "2:6", "expected at least 3 vertex indices after 'f'"),
    ("\n  vt 0 0\n", "2:3", "expected 'v' or 'f', found 'vt'"),
])
def test_malformed_psurf_reports_line_and_column(text: str, where: str, message: str) -> None:
    with pytest.raises(ParseError) as info:
        parse_psurf(text, "bad.pss")
    assert str(info.value) == f"bad.pss:{where}: {message}"


@pytest.mark.parametrize("ext, unit", [(".obj", 0.01), (".stl", 0.01), (".ply", 0.01), (".glb", 1.0)])
def test_trimesh_formats_load_in_metres(tmp_path: Path, ext: str, unit: float) -> None:
    box = trimesh.creation.box(extents=(10.0, 20.0, 30.0))
    path = tmp_path / f"box{ext}"
    box.export(path)
    mesh = load_mesh(path)
    np.testing.assert_allclose(mesh.bounds(), box.bounds * unit, atol=1e-6)
    assert len(mesh.faces) == 12


def test_unknown_and_broken_mesh_files(tmp_path: Path) -> None:
    (tmp_path / "a.dwg").write_text("x")
    with pytest.raises(ImportCADError, match="unknown geometry format '.dwg'"):
        load_mesh(tmp_path / "a.dwg")
    (tmp_path / "b.glb").write_bytes(b"not a glb file")
    with pytest.raises(ImportCADError, match="b.glb"):
        load_mesh(tmp_path / "b.glb")
    with pytest.raises(FileNotFoundError):
        load_mesh(tmp_path / "c.stl")


# ----- issue 22 item 8: silent bad geometry is refused with file:line ---------------------------
@pytest.mark.parametrize("text, where, message", [
    ("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "2:3", "not a finite number"),
    ("v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n", "2:3", "not a finite number of at most 1e12"),
    ("v 0 0 0\nv 1 0 0\nv 0 -1e308 0\nf 1 2 3\n", "3:5", "not a finite number"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "4:3", "face refers to vertex '0'"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "4:7", "face refers to vertex '4'"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 -4/3\n", "4:11", "face refers to vertex '-4'"),
])
def test_obj_psurf_with_bad_vertices_or_faces_is_refused_at_its_line(tmp_path: Path, text: str, where: str,
                                                                     message: str) -> None:
    path = tmp_path / "part.obj"
    path.write_text(text)
    with pytest.raises(ParseError) as info:
        load_mesh(path)
    assert str(info.value).startswith(f"{path}:{where}: ") and message in str(info.value)


def test_pss_with_huge_coordinates_is_refused(tmp_path: Path) -> None:
    with pytest.raises(ParseError, match=r"p\.pss:2:3: coordinate 1e308 out of range"):
        parse_psurf("v 0 0 0\nv 1e308 0 0\n", "p.pss")
    ok = tmp_path / "ok.obj"
    ok.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n")
    np.testing.assert_allclose(load_mesh(ok).vertices[1], [0.01, 0, 0])  # (OBJ psurfs are cm)


def test_a_mesh_changed_in_place_is_written_anew_not_from_the_text_cache():
    mesh = Mesh(np.array([[0.0, 0, 0], [0.01, 0, 0], [0, 0.01, 0]]), np.array([[0, 1, 2]]))
    first = psurf_to_text(mesh, "a")
    assert psurf_to_text(mesh, "a") == first
    assert psurf_to_text(mesh, "b") != first  # the comment is part of the text
    mesh.vertices[1, 0] = 0.02  # edited in place: same object, other content
    again = psurf_to_text(mesh, "a")
    assert again != first
    assert np.allclose(parse_psurf(again).vertices, mesh.vertices)
