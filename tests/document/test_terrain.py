"""The scene's terrain in the document: loaded by the user, saved in the session file, reopened
exactly, undone and redone."""

from pathlib import Path

import numpy as np
import pytest

from jackpy.document import Document
from jackpy.document.session import default_scene
from jackpy.document.terrain import load_terrain, set_terrain, terrain_of
from jackpy.errors import ParseError
from jackpy.locomotion.terrain import Terrain

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "creatures"


def _doc() -> Document:
    env, base = default_scene()
    doc = Document(env)
    doc.scene_dir = base
    return doc


def test_loaded_terrain_survives_save_and_reopen(tmp_path):
    doc = _doc()
    loaded = load_terrain(doc, EXAMPLES / "steps.terrain.json")
    assert terrain_of(doc) is loaded and doc.dirty
    path = doc.save(tmp_path / "hills.env")
    back = terrain_of(Document.open(path))
    assert back is not None and back.name == "steps"
    assert np.array_equal(back.heights, loaded.heights)  # every height bit for bit
    assert (back.cell, back.x0, back.z0, back.max_slope_deg, back.foot_radius) == \
        (loaded.cell, loaded.x0, loaded.z0, loaded.max_slope_deg, loaded.foot_radius)
    assert back.forbidden.any() and np.array_equal(back.forbidden, loaded.forbidden)


def test_terrain_with_polygons_round_trips_and_a_scene_without_one_has_none(tmp_path):
    doc = _doc()
    assert terrain_of(doc) is None
    t = Terrain.from_function(lambda x, z: 0.1 * np.sin(x) * np.cos(z), (-2.0, 2.0), (-1.0, 3.0), 0.1,
                              polygons=[[(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)]])
    set_terrain(doc, t)
    back = terrain_of(Document.open(doc.save(tmp_path / "p.env")))
    assert np.array_equal(back.heights, t.heights) and len(back.polygons) == 1
    assert np.array_equal(back.polygons[0], t.polygons[0])
    plain = _doc()
    assert terrain_of(Document.open(plain.save(tmp_path / "plain.env"))) is None


def test_terrain_edits_undo_and_redo():
    doc = _doc()
    first = load_terrain(doc, EXAMPLES / "rolling_hills.terrain.json")
    load_terrain(doc, EXAMPLES / "steps.terrain.json")
    assert terrain_of(doc).name == "steps"
    assert doc.undo() and terrain_of(doc).name == "rolling_hills"
    assert np.array_equal(terrain_of(doc).heights, first.heights)
    assert doc.undo() and terrain_of(doc) is None
    assert doc.redo() and terrain_of(doc).name == "rolling_hills"
    set_terrain(doc, None)
    assert terrain_of(doc) is None and doc.undo() and terrain_of(doc) is not None


def test_a_bad_terrain_file_is_one_error_and_changes_nothing(tmp_path):
    doc = _doc()
    bad = tmp_path / "bad.terrain.json"
    bad.write_text('{"cell": 0.1, "heights": [[0, 1], [2]]}')
    with pytest.raises(ParseError, match="heights"):
        load_terrain(doc, bad)
    assert terrain_of(doc) is None and doc.undo_stack.undo_label is None
