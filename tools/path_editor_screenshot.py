"""Write the README's picture of the path editor in use (1280x800, the default scene): four path
points, the panel floated out of the right dock and enlarged as a user would.

Run under a display (``xvfb-run -a -s "-screen 0 1600x1200x24" python tools/path_editor_screenshot.py``);
writes ``figures/workbench/path_editor.png``. The panel is tested in tests/ui/test_panel_path_editor.py."""

from __future__ import annotations

from pathlib import Path

import moderngl
from imgui_bundle import imgui
from PIL import Image

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.panels import path_editor as pe
from jackpy.ui.window import Window

OUT = Path(__file__).resolve().parents[1] / "figures" / "workbench" / "path_editor.png"
env, base = session.default_scene()
app = App(env)
app.scene_dir = base
win = Window(app, "jackpy", (1280, 800), visible=False)
try:
    for _ in range(10):
        win.frame()
    win.ui.open_panels[pe.TITLE] = True
    st = win.ui.panel_state(pe.TITLE, pe.defaults())
    fig = app.figure_of_interest()
    x0, z0 = pe.start_of(fig)
    for q in ((x0 + 0.2, z0 + 1.4), (x0 + 1.3, z0 + 1.6), (x0 + 1.2, z0 + 0.2), (x0 + 2.4, z0 - 0.6)):
        pe.add_point(app.doc, st, fig, q)
    st["selected"] = 2
    win.frame()

    def float_it():
        imgui.internal.dock_builder_dock_window(pe.TITLE, 0)
        imgui.set_window_pos(pe.TITLE, (560, 40))
        imgui.set_window_size(pe.TITLE, (700, 580))

    win.panels_frame(float_it)
    for _ in range(30):
        win.frame()
    screen = moderngl.get_context().screen
    rgb = Image.frombytes("RGB", (screen.width, screen.height), screen.read(components=3))
    rgb.transpose(Image.FLIP_TOP_BOTTOM).save(OUT)
finally:
    win.close()
