"""Scene → Load terrain... / Example terrain / Remove terrain, headless through the menu's
command table and the file dialog's answer: each one undo step; a bad file changes nothing."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

from jackpy.document.terrain import terrain_of
from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.commands import commands, file_chosen
from jackpy.ui.panels import UiState

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "creatures"


def _app():
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    return app, UiState()


def _command(label):
    return next(c for c in commands([]) if c.menu == "Scene" and c.label == label)


def test_example_terrain_and_remove_are_menu_commands_each_undone_in_one_step():
    app, ui = _app()
    remove = _command("Remove terrain")
    assert not remove.enabled(app, ui)  # greyed out without a terrain
    _command("Example terrain").run(app, ui)
    example = terrain_of(app.doc)
    assert example is not None and example.shape == (61, 61) and app.dirty
    assert 0.05 < np.ptp(example.heights) < 0.2 and not example.forbidden.any()
    assert remove.enabled(app, ui)
    remove.run(app, ui)
    assert terrain_of(app.doc) is None
    app.undo()
    assert np.array_equal(terrain_of(app.doc).heights, example.heights)
    app.undo()
    assert terrain_of(app.doc) is None
    app.redo()
    assert terrain_of(app.doc) is not None


def test_load_terrain_asks_for_a_grid_heightmap_or_mesh_and_loads_it_undoably(tmp_path):
    app, ui = _app()
    _command("Load terrain...").run(app, ui)
    request = ui.files.request
    assert request is not None and request.kind == "terrain"
    assert {".json", ".png", ".stl", ".obj"} <= set(request.extensions)
    ui.files.request = None
    assert file_chosen(app, ui, request, EXAMPLES / "steps.terrain.json")
    assert terrain_of(app.doc).name == "steps" and app.log[-1].startswith("terrain steps loaded")
    ramp = trimesh.Trimesh([[0, 0, 0], [2, 0.2, 0], [2, 0.2, 2], [0, 0, 2]], [[0, 2, 1], [0, 3, 2]])
    ramp.export(tmp_path / "ramp.stl")  # a 10 % slope along x, metres, y up
    assert file_chosen(app, ui, request, tmp_path / "ramp.stl")
    t = terrain_of(app.doc)
    assert t.name == "ramp" and abs(t.height(1.0, 1.0) - 0.1) < 1e-6 and abs(t.height(1.5, 0.4) - 0.15) < 1e-6
    app.undo()
    assert terrain_of(app.doc).name == "steps"
    (tmp_path / "bad.json").write_text('{"heights": [[0, 1]], "cell": 0.1}')
    assert not file_chosen(app, ui, request, tmp_path / "bad.json")
    assert app.log[-1].startswith("error:") and "bad.json" in app.log[-1]
    assert terrain_of(app.doc).name == "steps"  # unchanged
    (tmp_path / "bad.stl").write_text("solid nothing\nendsolid nothing\n")
    assert not file_chosen(app, ui, request, tmp_path / "bad.stl")
    assert app.log[-1].startswith("error:") and terrain_of(app.doc).name == "steps"
