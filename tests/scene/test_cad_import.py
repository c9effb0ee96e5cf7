"""CAD import: every format through trimesh, units and up axis honoured, malformed files rejected."""

from __future__ import annotations

import importlib.util
import re

import numpy as np
import pytest
import trimesh

from jackpy.errors import ImportCADError
from jackpy.peabody import Environment
from jackpy.scene import add_cad, decimate, import_cad
from jackpy.scene.cad import UNITS

NEEDS = {"3mf": "lxml", "dae": "collada", "step": "cascadio"}


def _available(fmt: str) -> bool:
    return fmt not in NEEDS or importlib.util.find_spec(NEEDS[fmt]) is not None


def _box_file(tmp_path, fmt: str, extents=(10.0, 20.0, 30.0)):
    if not _available(fmt):
        pytest.skip(f"{fmt} needs optional package {NEEDS[fmt]}")
    box = trimesh.creation.box(extents=extents)
    box.apply_translation([5.0, 10.0, 15.0])  # corner at the origin, max corner = extents
    path = tmp_path / f"box.{fmt}"
    if fmt == "gltf":
        files = box.export(file_type="gltf")
        for name, data in files.items():
            (tmp_path / name).write_bytes(data)
        (tmp_path / "model.gltf").rename(path)
    else:
        box.export(str(path))
    return path


UNITLESS = ["obj", "stl", "ply", "off"]
#: 3MF unit names and COLLADA <unit meter> of each jackpy unit
_3MF = {"mm": "millimeter", "cm": "centimeter", "m": "meter", "in": "inch"}
PART = np.array([100.0, 50.0, 20.0])  # the known part: 100 x 50 x 20 file units


def _declared_file(tmp_path, fmt: str, unit: str):
    """The known part in a format that declares its unit, declared in ``unit`` (glTF: metres, the
    only unit it has, so the part is written at its size in ``unit`` converted to metres)."""
    if not _available(fmt):
        pytest.skip(f"{fmt} needs optional package {NEEDS.get(fmt, fmt)}")
    s = UNITS[unit]
    if fmt == "step":
        from step_box import step_box

        path = tmp_path / "part.step"
        path.write_text(step_box(tuple(PART), unit))
        return path
    box = trimesh.creation.box(extents=PART * (s if fmt in ("gltf", "glb") else 1.0))
    box.apply_translation(box.extents / 2)
    path = tmp_path / f"part.{fmt}"
    if fmt == "gltf":
        for name, data in box.export(file_type="gltf").items():
            (tmp_path / name).write_bytes(data)
        (tmp_path / "model.gltf").rename(path)
    elif fmt == "3mf":
        import zipfile

        box.export(str(tmp_path / "plain.3mf"))
        with zipfile.ZipFile(tmp_path / "plain.3mf") as src, zipfile.ZipFile(path, "w") as dst:
            for item in src.infolist():
                data = src.read(item.filename)
                if item.filename.lower().endswith("3dmodel.model"):
                    data = re.sub(rb'unit="\w+"', f'unit="{_3MF[unit]}"'.encode(), data, count=1)
                    assert f'unit="{_3MF[unit]}"'.encode() in data
                dst.writestr(item, data)
    elif fmt == "dae":
        text = box.export(file_type="dae").decode()
        path.write_text(text.replace("<asset>", f'<asset>\n    <unit meter="{s}" name="{unit}"/>', 1))
    else:
        box.export(str(path))
    return path


@pytest.mark.parametrize("fmt", UNITLESS)
@pytest.mark.parametrize("units", ["mm", "cm", "m", "in"])
def test_unitless_formats_take_the_given_units_at_true_size(tmp_path, fmt, units):
    obj = import_cad(_box_file(tmp_path, fmt, extents=tuple(PART)), units=units, up="y")
    lo, hi = obj.mesh().bounds()
    np.testing.assert_allclose(hi - lo, PART * UNITS[units], rtol=1e-3)  # +-0.1 %
    assert obj.settings.units == units and obj.settings.source.endswith(f"box.{fmt}")
    assert len(obj.mesh().faces) == 12


@pytest.mark.parametrize("fmt", ["gltf", "glb", "3mf", "dae", "step"])
@pytest.mark.parametrize("declared", ["mm", "cm", "m", "in"])
def test_formats_that_declare_units_come_in_at_true_size(tmp_path, fmt, declared):
    """The file's own unit wins: a 100 x 50 x 20 mm STEP part is 0.1 x 0.05 x 0.02 m whatever
    ``units`` says (the STEP reader already converts to metres; it must not be scaled again)."""
    path = _declared_file(tmp_path, fmt, declared)
    for units in ("mm", "m"):
        obj = import_cad(path, units=units, up="y")
        lo, hi = obj.mesh().bounds()
        np.testing.assert_allclose(hi - lo, PART * UNITS[declared], rtol=1e-3)  # +-0.1 %


@pytest.mark.parametrize("up,expected", [("y", (10, 20, 30)), ("z", (10, 30, 20)), ("x", (20, 10, 30))])
def test_up_axis_maps_to_y(tmp_path, up, expected):
    obj = import_cad(_box_file(tmp_path, "stl"), units="m", up=up)
    lo, hi = obj.mesh().bounds()
    np.testing.assert_allclose(hi - lo, expected, atol=1e-9)
    if up == "z":  # the file's +z (up) becomes +y: the box sits on the floor, above y = 0
        assert lo[1] == pytest.approx(0.0) and hi[1] == pytest.approx(30.0)


MALFORMED = {
    "obj": b"v 1 2\nf 1 2 9\nthis is not obj\n",
    "stl": b"solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0\n",
    "ply": b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nend_header\n\x00\x01",
    "off": b"OFF\n3 1 0\n0 0 0\n1 0 0\n",
    "glb": b"glTF\x02\x00\x00\x00garbage",
    "gltf": b"{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 7}}]}]}",
    "3mf": b"PK\x03\x04 not a zip",
    "dae": b"<COLLADA><library_geometries><geometry><mesh>",
    "step": b"ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=NONSENSE(;\nENDSEC;\nEND-ISO-10303-21;\n",
}


@pytest.mark.parametrize("fmt", sorted(MALFORMED))
def test_malformed_file_is_a_clear_error_and_scene_is_untouched(tmp_path, fmt):
    env = Environment()
    good = add_cad(env, _box_file(tmp_path, "stl"), units="mm")
    before = dict(env.figures)
    bad = tmp_path / f"broken.{fmt}"
    bad.write_bytes(MALFORMED[fmt])
    with pytest.raises(ImportCADError) as info:
        add_cad(env, bad, units="mm")
    assert "broken." + fmt in str(info.value)
    assert env.figures == before and env.figures["box"] is good


def test_unknown_format_missing_file_bad_units(tmp_path):
    (tmp_path / "a.xyz123").write_text("x")
    with pytest.raises(ImportCADError, match="unsupported CAD format"):
        import_cad(tmp_path / "a.xyz123")
    with pytest.raises(ImportCADError, match="no such file"):
        import_cad(tmp_path / "missing.stl")
    with pytest.raises(ImportCADError, match="unknown units"):
        import_cad(_box_file(tmp_path, "stl"), units="furlong")
    with pytest.raises(ImportCADError, match="unknown up axis"):
        import_cad(_box_file(tmp_path, "stl"), up="w")


def test_duplicate_name_rejected(tmp_path):
    env = Environment()
    path = _box_file(tmp_path, "obj")
    add_cad(env, path)
    with pytest.raises(ImportCADError, match="already has an object"):
        add_cad(env, path)
    assert len(env.figures) == 1


def test_place_move_rotate_and_sites(tmp_path):
    obj = import_cad(_box_file(tmp_path, "obj"), units="cm")
    obj.add_site("handle", np.array([0.1, 0.2, 0.3]))
    obj.place(np.array([1.0, 0.0, 2.0]))
    np.testing.assert_allclose(obj.site_position("handle"), [1.1, 0.2, 2.3])
    obj.move(np.array([0.0, 0.5, 0.0]))
    np.testing.assert_allclose(obj.site_position("handle"), [1.1, 0.7, 2.3])
    obj.rotate("y", np.pi / 2)  # about the object origin (1, .5, 2): local +x -> world -z
    np.testing.assert_allclose(obj.site_position("handle"), [1.3, 0.7, 1.9], atol=1e-12)
    np.testing.assert_allclose(obj.site_world(obj.name, "handle")[:3, 3], obj.site_position("handle"))
    assert set(obj.user_sites()) == {"handle"}
    with pytest.raises(ImportCADError):
        obj.add_site("a.b", np.zeros(3))


def test_large_model_display_copy_is_decimated_full_mesh_kept(tmp_path):
    sphere = trimesh.creation.icosphere(subdivisions=6)  # 81920 triangles
    path = tmp_path / "ball.ply"
    sphere.export(str(path))
    obj = import_cad(path)
    assert obj.triangle_count == 81920
    disp = obj.display_mesh(max_triangles=5000)
    assert 500 < len(disp.faces) <= 5000
    # the decimated copy stays on the sphere (radius 1) to within about one cell
    r = np.linalg.norm(disp.vertices, axis=1)
    assert np.all(np.abs(r - 1.0) < 0.1)
    assert obj.display_mesh(max_triangles=10**6) is obj.mesh()
    assert obj.display_mesh(max_triangles=5000) is disp  # cached


def test_decimate_keeps_valid_indices():
    m = trimesh.creation.box()
    from jackpy.peabody import Mesh
    out = decimate(Mesh(m.vertices, m.faces), 12)
    assert out.faces.max() < len(out.vertices) and len(out.faces) <= 12


@pytest.mark.parametrize("text, where, message", [
    ("v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n", "2:3", "not a finite number"),
    ("v 0 0 0\nv -1e308 0 0\nv 0 1 0\nf 1 2 3\n", "2:3", "not a finite number"),
    ("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "2:3", "not a finite number"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "4:3", "face refers to vertex '0'"),
])
def test_obj_with_huge_or_nan_coordinates_or_face_zero_is_refused_at_its_line(tmp_path, text, where, message):
    path = tmp_path / "part.obj"
    path.write_text(text)
    with pytest.raises(ImportCADError) as info:
        import_cad(path, units="mm")
    assert str(info.value).startswith(f"{path}:{where}: ") and message in str(info.value)


def test_bad_step_says_what_is_wrong_without_noise(tmp_path, capfd):
    if not _available("step"):
        pytest.skip("STEP needs cascadio")
    bad = tmp_path / "bad.step"
    bad.write_text("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=NONSENSE(;\nENDSEC;\nEND-ISO-10303-21;\n")
    with pytest.raises(ImportCADError, match=r"bad\.step: cannot read STEP file: OpenCascade found no shapes"):
        import_cad(bad)
    out, err = capfd.readouterr()
    assert out == "" and err == "" and "converted.glb" not in out + err
