"""Fuzzing the CAD readers (OBJ text, binary and ASCII STL, PLY, OFF, glTF JSON): mutated files
only ever raise the project's one-line errors naming the file, and what imports is finite with
valid faces."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from fuzz_helpers import FUZZ, byte_mutations, check_error, mutate, mutate_bytes, mutations
from hypothesis import given, settings
from hypothesis import strategies as st

from jackpy.errors import JackpyError
from jackpy.scene.cad import import_cad

BOX = trimesh.creation.box(extents=(1.0, 2.0, 3.0))


def _export(fmt: str) -> bytes:
    if fmt == "gltf":  # one self-contained JSON file (buffers as data: URIs)
        return trimesh.exchange.gltf.export_gltf(BOX, embed_buffers=True)["model.gltf"]
    data = BOX.export(file_type=fmt)
    return data.encode() if isinstance(data, str) else data


SEEDS = {fmt: _export(fmt) for fmt in ("obj", "stl", "ply", "off", "gltf")}
SEEDS["stl_ascii"] = trimesh.exchange.stl.export_stl_ascii(BOX).encode()
SUFFIX = {"stl_ascii": "stl"}
WORDS = ["v", "f", "vn", "vt", "0", "-1", "1e308", "nan", "inf", "-0", "99999999999999999999", "facet", "vertex",
         "endsolid", "element", "face", "property", "end_header", "OFF", '"uri"', '"buffers"', "data:", "../x.bin"]


def _import(tmp_path, fmt: str, data: bytes) -> None:
    path = tmp_path / f"fuzz.{SUFFIX.get(fmt, fmt)}"
    path.write_bytes(data)
    try:
        obj = import_cad(path)
    except JackpyError as exc:
        check_error(exc, path.name)
        return
    mesh = obj.mesh()
    assert np.all(np.isfinite(mesh.vertices)) and len(mesh.faces) > 0
    assert mesh.faces.min() >= 0 and mesh.faces.max() < len(mesh.vertices)


@pytest.mark.parametrize("fmt", ["obj", "stl_ascii", "ply", "off", "gltf"])
@settings(FUZZ, max_examples=60)
@given(data=st.data())
def test_mutated_text_cad_files(tmp_path_factory, fmt: str, data) -> None:
    text = SEEDS[fmt].decode("latin-1")
    ops = data.draw(mutations(text, WORDS))
    _import(tmp_path_factory.mktemp("cad"), fmt, mutate(text, ops).encode("latin-1", "replace"))


@pytest.mark.parametrize("fmt", ["stl", "ply"])
@settings(FUZZ, max_examples=60)
@given(data=st.data())
def test_mutated_binary_cad_files(tmp_path_factory, fmt: str, data) -> None:
    ops = data.draw(byte_mutations(SEEDS[fmt]))
    _import(tmp_path_factory.mktemp("cad"), fmt, mutate_bytes(SEEDS[fmt], ops))

