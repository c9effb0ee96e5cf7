"""New, Open and Open Recent with unsaved changes ask Save / Discard / Cancel first (issue 21:
"Quit, New, Open ... with unsaved changes ask"), headless: the App and the menu's command table,
no window. Cancel keeps the work; Discard goes on; Save saves (through Save-as for an unnamed
document) and then goes on; a document with nothing unsaved is not asked about."""

from __future__ import annotations

import numpy as np

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.commands import commands, file_chosen, open_recent, unsaved_choice
from jackpy.ui.panels import UiState


def _app(tmp_path, monkeypatch):
    monkeypatch.setenv("JACKPY_HOME", str(tmp_path / "home"))
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    return app, UiState()


def _run(app, ui, label):
    next(c for c in commands([]) if c.menu == "File" and c.label == label).run(app, ui)


def _modify(app) -> float:
    fig = app.figure_of_interest()
    value = app.doc.set_dof(fig, "right_elbow", 0, 0.5)
    assert app.dirty
    return value


def _elbow(app) -> float:
    return float(app.figure_of_interest().joint("right_elbow").displacement[0])


def test_new_asks_first_and_cancel_keeps_the_work(tmp_path, monkeypatch):
    app, ui = _app(tmp_path, monkeypatch)
    bent = _modify(app)
    _run(app, ui, "New")
    assert ui.confirm == "unsaved" and "new scene" in ui.pending[0]
    assert _elbow(app) == bent  # nothing happened yet
    unsaved_choice(app, ui, "cancel")
    assert ui.confirm is None and ui.pending is None and app.dirty and _elbow(app) == bent
    _run(app, ui, "New")
    unsaved_choice(app, ui, "discard")
    assert ui.confirm is None and not np.isclose(_elbow(app), bent)  # the default scene again
    assert not app.dirty  # ... with nothing to save: opening another scene now asks nothing
    app.undo()
    assert np.isclose(_elbow(app), bent) and app.dirty  # New is undoable


def test_open_with_a_named_document_saves_then_asks_for_the_file(tmp_path, monkeypatch):
    app, ui = _app(tmp_path, monkeypatch)
    app.doc.path = tmp_path / "work.env"
    bent = _modify(app)
    _run(app, ui, "Open...")
    assert ui.confirm == "unsaved" and not ui.files.active
    unsaved_choice(app, ui, "save")
    assert (tmp_path / "work.env").is_file() and not app.dirty
    assert ui.files.active and ui.files.request.kind == "open"  # only now the Open dialog
    doc, _ = session.load_session(tmp_path / "work.env")
    assert np.isclose(doc.figures[app.figure_of_interest().name].joint("right_elbow").displacement[0], bent)


def test_save_of_an_unnamed_document_goes_through_save_as_then_goes_on(tmp_path, monkeypatch):
    app, ui = _app(tmp_path, monkeypatch)
    saved = tmp_path / "first.env"
    session.save_session(app, saved)  # a recent file to open
    _modify(app)
    app.doc.path = None
    open_recent(app, ui, str(saved))
    assert ui.confirm == "unsaved" and "first.env" in ui.pending[0]
    unsaved_choice(app, ui, "save")
    assert ui.files.active and ui.files.request.kind == "save_as" and ui.after_save is not None
    request = ui.files.request
    ui.files.request = None  # the dialog answered
    assert file_chosen(app, ui, request, tmp_path / "second.env")
    assert (tmp_path / "second.env").is_file() and ui.after_save is None
    assert app.session_path is not None and app.session_path.name == "first.env"  # then it opened
    assert not app.dirty


def test_nothing_unsaved_is_not_asked_about(tmp_path, monkeypatch):
    app, ui = _app(tmp_path, monkeypatch)
    if app.dirty:
        app.doc.path = tmp_path / "clean.env"
        session.save_session(app, app.doc.path)
    assert not app.dirty
    _run(app, ui, "Open...")
    assert ui.confirm is None and ui.files.active
