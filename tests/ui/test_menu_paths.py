"""Save-as defaults are absolute: the document's own path, else the user's home."""

from pathlib import Path

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.panels.menu_bar import default_save_path


def test_save_as_default_is_absolute(monkeypatch, tmp_path):
    monkeypatch.setenv("HOME", str(tmp_path))
    monkeypatch.chdir(tmp_path)
    env, _ = session.default_scene()
    app = App(env)
    app.session_path = None
    assert Path(default_save_path(app)) == tmp_path / "scene.env"
    app.session_path = Path("work/bench.env")  # relative: made absolute against the working folder
    assert Path(default_save_path(app)) == tmp_path / "work" / "bench.env"
    assert Path(default_save_path(app)).is_absolute()
