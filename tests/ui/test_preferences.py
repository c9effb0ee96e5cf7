"""Per-user preferences: saved under $JACKPY_HOME, read back, a malformed file reported and
replaced by defaults, recent files newest first and bounded, remembered by saves and opens."""

import json
from pathlib import Path

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.preferences import RECENT_MAX, Preferences, preferences_path


def test_round_trip_and_defaults(tmp_path):
    path = tmp_path / "p.json"
    assert Preferences.load(path).as_dict() == {"mouse_preset": "default", "native_dialogs": True, "recent": []}
    prefs = Preferences.load(path)
    prefs.mouse_preset, prefs.native_dialogs = "blender", False
    prefs.save()
    assert Preferences.load(path).as_dict() == {"mouse_preset": "blender", "native_dialogs": False, "recent": []}


def test_malformed_file_is_reported_and_never_stops_the_start(tmp_path):
    path = tmp_path / "p.json"
    path.write_text("{not json")
    prefs = Preferences.load(path)
    assert prefs.problem.startswith("warning: preferences") and prefs.mouse_preset == "default"
    path.write_text(json.dumps({"mouse_preset": "no such preset", "recent": ["/a.env", 3], "native_dialogs": "yes"}))
    prefs = Preferences.load(path)
    assert prefs.problem is None and prefs.as_dict() == {"mouse_preset": "default", "native_dialogs": True,
                                                         "recent": ["/a.env"]}


def test_recent_files_newest_first_once_and_bounded(tmp_path):
    prefs = Preferences.load(tmp_path / "p.json")
    for i in range(RECENT_MAX + 3):
        prefs.add_recent(tmp_path / f"s{i}.env")
    prefs.add_recent(tmp_path / "s5.env")
    recent = Preferences.load(tmp_path / "p.json").recent
    assert len(recent) == RECENT_MAX and recent[0] == str(tmp_path / "s5.env") and recent.count(recent[0]) == 1
    prefs.forget_recent(recent[0])
    assert str(tmp_path / "s5.env") not in Preferences.load(tmp_path / "p.json").recent
    prefs.forget_recent()
    assert Preferences.load(tmp_path / "p.json").recent == []


def test_saves_and_opens_are_remembered_but_not_the_recovery_file(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    session.save_session(app, "rel.env")  # relative: remembered absolute
    session.autosave(app)  # the recovery file is not a recent file
    assert Preferences.load().recent == [str(tmp_path / "rel.env")]
    session.open_session(app, tmp_path / "rel.env")
    assert Preferences.load().recent == [str(tmp_path / "rel.env")]
    assert preferences_path().parent == Path(str(tmp_path / "jackpy_home"))
