"""The file dialog's logic without a window: start folders, listing, names resolved against the
folder, Replace before overwriting, and when the desktop's dialog is used."""

import stat

from jackpy.ui.file_dialog import FileDialog, FileRequest, list_folder, native_available, resolve_choice, start_folder


def scene_request(tmp_path, save=True):
    return FileRequest("save_as" if save else "open", "Save scene as", save, (".env",), tmp_path, "scene.env")


def test_start_folder_is_the_documents_folder_else_home(tmp_path, monkeypatch):
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    (tmp_path / "home").mkdir()
    (tmp_path / "work").mkdir()
    monkeypatch.chdir(tmp_path)
    assert start_folder(None) == tmp_path / "home"
    assert start_folder("work/bench.env") == tmp_path / "work"  # relative: made absolute
    assert start_folder(tmp_path / "gone" / "x.env") == tmp_path / "home"  # a folder that is gone
    assert start_folder("work/bench.env").is_absolute()


def test_listing_shows_folders_then_matching_files(tmp_path):
    for name in ("b.env", "A.ENV", "notes.txt", ".hidden.env"):
        (tmp_path / name).write_text("x")
    (tmp_path / "zeta").mkdir()
    (tmp_path / "Alpha").mkdir()
    names = [(e.name, e.is_dir) for e in list_folder(tmp_path, (".env",), False)]
    assert names == [("Alpha", True), ("zeta", True), ("A.ENV", False), ("b.env", False)]
    assert "notes.txt" in [e.name for e in list_folder(tmp_path, (".env",), True)]
    assert list_folder(tmp_path / "missing", (".env",), False) == []


def test_names_resolve_against_the_folder(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "old.env").write_text("x")
    req = scene_request(tmp_path)
    assert resolve_choice(tmp_path, "bench", req) == (tmp_path / "bench.env", None)  # extension added
    assert resolve_choice(tmp_path, "sub/../x.png", req)[0].name == "x.png"  # an extension is kept
    assert resolve_choice(tmp_path, str(tmp_path / "sub" / "a.env"), req) == (tmp_path / "sub" / "a.env", None)
    assert resolve_choice(tmp_path, "", req)[1] == "type a file name or pick a file"
    assert "is a folder" in resolve_choice(tmp_path, "sub", req)[1]
    assert "no folder" in resolve_choice(tmp_path, "nowhere/a.env", req)[1]
    opening = scene_request(tmp_path, save=False)
    assert resolve_choice(tmp_path, "old.env", opening) == (tmp_path / "old.env", None)
    assert "no file" in resolve_choice(tmp_path, "missing.env", opening)[1]


def test_saving_over_a_file_asks_replace_first(tmp_path):
    (tmp_path / "scene.env").write_text("mine")
    dialog = FileDialog()
    dialog.ask(scene_request(tmp_path))
    assert dialog.active and dialog.folder == tmp_path and dialog.name == "scene.env"
    assert dialog.accept() is None and dialog.replace == tmp_path / "scene.env" and dialog.active
    assert dialog.accept() == tmp_path / "scene.env" and not dialog.active  # the second press replaces
    dialog.ask(scene_request(tmp_path))
    dialog.name = "sub"
    (tmp_path / "sub").mkdir()
    assert dialog.accept() is None and "is a folder" in dialog.error


def test_the_desktop_dialog_is_used_only_where_one_is_installed(tmp_path, monkeypatch):
    monkeypatch.setenv("PATH", str(tmp_path))
    assert not native_available()
    dialog = FileDialog()
    dialog.ask(scene_request(tmp_path), native=True)
    assert not dialog.native  # no zenity/kdialog: the in-app browser
    fake = tmp_path / "zenity"
    fake.write_text("#!/bin/sh\nexit 1\n")
    fake.chmod(fake.stat().st_mode | stat.S_IXUSR)
    assert native_available()
