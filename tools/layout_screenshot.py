"""Write the README's picture of the workbench's default layout (1280x800, the default scene).

Run under a display (``xvfb-run -a -s "-screen 0 1600x1200x24" python tools/layout_screenshot.py``);
writes ``figures/workbench/default_layout.png``. The layout itself is tested in
tests/ui/test_window_layout.py."""

from __future__ import annotations

from pathlib import Path

import moderngl
from PIL import Image

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.window import Window

OUT = Path(__file__).resolve().parents[1] / "figures" / "workbench" / "default_layout.png"


def main() -> None:
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    win = Window(app, "jackpy", (1280, 800), visible=False)
    try:
        for _ in range(30):  # the docked layout settles over the first frames
            win.frame()
        screen = moderngl.get_context().screen
        rgb = Image.frombytes("RGB", (screen.width, screen.height), screen.read(components=3))
        rgb.transpose(Image.FLIP_TOP_BOTTOM).save(OUT)
    finally:
        win.close()


if __name__ == "__main__":
    main()
