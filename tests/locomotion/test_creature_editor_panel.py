"""The creature editor panel: the mouse table headless, and the panel drawn in the workbench
window under Xvfb with an insect drawn by presses, built into the scene, then walked."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from jackpy.locomotion.creature_editor import analyse
from jackpy.peabody.model import Environment
from jackpy.ui.panels.creature_editor import LEFT, MIDDLE, RIGHT, build_into_scene, defaults, press


def draw_insect_by_mouse() -> dict:
    """An insect by clicks only: the body line, then each leg clicked from its tip to the body."""
    st = defaults()
    for y in (-20, 0, 20):
        press(st, 0, y, LEFT)  # create + chain the body line
    press(st, 0, 40, RIGHT)  # abort the rubber band
    for y in (-20, 0, 20):
        for side in (-1, 1):
            press(st, side * 30, y, LEFT)  # tip: node + rubber band
            press(st, side * 14, y, LEFT)  # knee: node + link, rubber band goes on
            press(st, 0, y, LEFT)  # onto the body node: link completed
    return st


def test_mouse_table_headless():
    st = draw_insect_by_mouse()
    d = st["editor"].drawing
    assert len(d.nodes) == 15 and len(d.links) == 14
    an = analyse(d)
    assert len(an.legs) == 6 and sorted(an.body) == [0, 1, 2]
    press(st, 50, 50, MIDDLE)  # an unconnected node
    assert len(d.nodes) == 16
    press(st, 50, 50, MIDDLE)  # middle on a node deletes it
    assert len(st["editor"].drawing.nodes) == 15
    env = Environment()
    assert "6 legs" in build_into_scene(env, st["editor"].drawing)
    assert "creature" in env.figures


CHILD = textwrap.dedent("""
    import numpy as np
    from jackpy.ui import session
    from jackpy.ui.app import App
    from jackpy.ui.window import Window
    from jackpy.ui.panels.creature_editor import TITLE, defaults, build_into_scene
    from test_creature_editor_panel import draw_insect_by_mouse
    env, base = session.default_scene()
    app = App(env)
    win = Window(app, "creature editor", (900, 700), visible=False)
    try:
        win.ui.open_panels[TITLE] = True
        st = win.ui.panel_state(TITLE, defaults())
        st.update(draw_insect_by_mouse())
        for _ in range(3):
            win.frame()
        pixels = np.frombuffer(win.ctx.screen.read(components=3), np.uint8).reshape(700, 900, 3)
        drawing = st["editor"].drawing
        app.doc.command("build creature", lambda: build_into_scene(app.env, drawing), structural=True)
        for _ in range(2):
            win.frame()
        fig = app.env.figures["creature"]
        from jackpy.locomotion.creature_walk import walk
        from jackpy.locomotion.config import WalkConfig
        from jackpy.locomotion.terrain import Terrain
        r = walk(fig, Terrain.flat(6.0, 0.25), (0.0, 1.0), config=WalkConfig(fps=10.0))
        print("COLOURS", len(np.unique(pixels.reshape(-1, 3), axis=0)))
        print("LEGS", len(r.legs), "MISS", float(np.hypot(*(r.body_xz(-1) - r.goal))))
    finally:
        win.close()
""")


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="needs an X display (run under xvfb-run)")
def test_panel_in_the_window_draw_build_walk(tmp_path):
    env = dict(os.environ, JACKPY_HOME=str(tmp_path), JACKPY_WINDOW_CHILD="1",
               PYTHONPATH=os.path.dirname(__file__) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    out = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    lines = dict(line.split(" ", 1) for line in out.stdout.splitlines() if line.startswith(("COLOURS", "LEGS")))
    assert int(lines["COLOURS"]) > 50
    legs, _, miss = lines["LEGS"].split()
    assert int(legs) == 6 and float(miss) < 0.2
