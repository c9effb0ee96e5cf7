"""Write the picture of a panel docked after starting with an older saved layout (1280x800).

A layout is saved, the Step editor and Preferences sections are taken out of it (a layout.ini
from before those panels existed), the workbench starts on it and opens both panels: they dock as
tabs on the right (``jackpy.ui.layout.dock_unknown``), not over the figure. Run under a display
(``xvfb-run -a -s "-screen 0 1600x1200x24" python tools/old_layout_screenshot.py``); writes
``figures/workbench/old_layout_new_panel.png``. Tested in tests/ui/test_window_layout.py."""

from __future__ import annotations

import tempfile
from pathlib import Path

import moderngl
from PIL import Image

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.window import Window

OUT = Path(__file__).resolve().parents[1] / "figures" / "workbench" / "old_layout_new_panel.png"
NEW = ("Step editor", "Preferences")


def main() -> None:
    env, base = session.default_scene()
    ini = Path(tempfile.mkdtemp()) / "layout.ini"
    win = Window(App(env), "jackpy", (1280, 800), visible=False, layout_file=ini)
    win.frame()
    win.close()
    blocks = ini.read_text().split("\n\n")
    ini.write_text("\n\n".join(b for b in blocks if not any(b.startswith(f"[Window][{t}]") for t in NEW)))
    app = App(env)
    app.scene_dir = base
    win = Window(app, "jackpy", (1280, 800), visible=False, layout_file=ini)
    try:
        for title in NEW:
            win.ui.open_panels[title] = True
        for _ in range(30):  # the docked layout settles over the first frames
            win.frame()
        screen = moderngl.get_context().screen
        rgb = Image.frombytes("RGB", (screen.width, screen.height), screen.read(components=3))
        rgb.transpose(Image.FLIP_TOP_BOTTOM).save(OUT)
    finally:
        win.close()


if __name__ == "__main__":
    main()
