"""The Scene and File → Recover menus in a real window, clicked by Dear ImGui's test engine
(Xvfb): Scene → Example terrain, then Remove terrain; File → Recover lists a crashed run's
recovery file and recovers it."""

import os

import pytest
from ui_support import in_child_process

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from test_gui_engine import MENU, default_app, drive  # noqa: E402

from jackpy.document import recovery  # noqa: E402
from jackpy.document import session as doc_session  # noqa: E402
from jackpy.document.terrain import terrain_of  # noqa: E402


def test_scene_terrain_and_file_recover_from_the_menus(request, tmp_path, monkeypatch):
    if in_child_process(request):
        return
    app = default_app(tmp_path, monkeypatch)
    crashed = default_app(tmp_path, monkeypatch)
    fig = crashed.figure_of_interest()
    fig.q = fig.q * 0.5 + 0.5 * (fig.lower + fig.upper) * 0.5
    crashed.doc.view_state["autosave_of"] = None
    orphan = doc_session.save(crashed.doc, recovery.recovery_dir() / "untitled-999999999.env")  # a dead run's

    def terrain(ctx, win):
        ctx.set_ref(MENU)
        ctx.menu_click("Scene/Example terrain")
        ctx.yield_(2)
        assert terrain_of(app.doc) is not None and app.dirty
        ctx.menu_click("Scene/Remove terrain")
        ctx.yield_(2)
        assert terrain_of(app.doc) is None
        app.doc.dirty = False  # (nothing to ask about before recovering)

    def recover(ctx, win):
        ctx.set_ref(MENU)
        ctx.menu_click("File/Recover/###recover0")
        ctx.yield_(2)
        assert app.dirty and not orphan.exists()
        assert (app.figure_of_interest().q == fig.q).all()

    drive(app, [("scene terrain", terrain), ("file recover", recover)])
