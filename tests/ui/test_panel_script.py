"""The Script panel in a real window (Xvfb): a malformed script marks its line; a good one runs in
the background on the panel example and its timeline lands in the document."""

import os
import time
from pathlib import Path

import pytest
from ui_support import in_child_process

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.panels import script as panel
from jackpy.ui.window import Window

SCENE = Path(__file__).resolve().parents[2] / "examples" / "tasks" / "panel" / "panel.json"


def test_script_panel_errors_and_run(request):
    if in_child_process(request):
        return
    env, _ = session.default_scene()
    app = App(env)
    win = Window(app, "jackpy script", (1000, 700), visible=False)
    try:
        win.ui.open_panels[panel.TITLE] = True
        win.frame()
        st = panel.state_of(win.ui)
        st.editor.set_text("John is a 50 percentile male.\nJohn, look twf-1.\n")
        panel.run_script(st, st.editor.get_text())
        panel.mark(st)
        win.frame()
        assert [p.line for p in st.problems] == [2] and "expected 'at'" in st.problems[0].message
        assert st.editor.has_markers()
        st.scene = str(SCENE)
        st.editor.set_text("Jane is a 50 percentile female.\nJane, look at twf-3.\nJane, walk to the door.\n")
        panel.run_script(st, st.editor.get_text())
        t_end = time.monotonic() + 120
        while (st.running is not None) and time.monotonic() < t_end:
            win.frame()
        assert st.running is None and st.result is not None
        assert [p.line for p in st.problems] == [3] and "nothing in the scene is called 'door'" in st.problems[0].message
        tl = app.doc.timeline
        assert tl is not None and tl.motions[0].kind == "gaze" and "Jane" in app.doc.env.figures
    finally:
        win.close()
