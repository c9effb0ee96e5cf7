"""Write the README's pictures of the workbench (1280x800, the default scene).

Run under a display: ``xvfb-run -a -s "-screen 0 1600x1200x24" python tools/workbench_screenshot.py [PICTURE ...]``
(all of them without arguments). Each is written to ``figures/workbench/<picture>.png``:

- ``default_layout``: the default docked layout (tested in tests/ui/test_window_layout.py);
- ``old_layout_new_panel``: started on a layout.ini saved before the Step editor and Preferences
  panels existed, then both opened: they dock as tabs on the right (``jackpy.ui.layout.dock_unknown``),
  not over the figure (tested in tests/ui/test_window_layout.py);
- ``path_editor``: four path points in the path editor, floated out of the right dock and enlarged
  as a user would (tested in tests/ui/test_panel_path_editor.py);
- ``devices_live``: the Devices panel driving the human from the simulated Flock playing the shipped
  reach, split frames on (tested in tests/ui/test_panels_devices_split.py).
"""

from __future__ import annotations

import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

import moderngl
from imgui_bundle import imgui
from PIL import Image

from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.window import Window

FIGURES = Path(__file__).resolve().parents[1] / "figures" / "workbench"
SETTLE_FRAMES = 30  # the docked layout settles over the first frames
NEW_PANELS = ("Step editor", "Preferences")


def _window(layout_file: Path | None = None) -> tuple[App, Window]:
    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    return app, Window(app, "jackpy", (1280, 800), visible=False, layout_file=layout_file)


def _settle_and_save(win: Window, name: str) -> Path:
    for _ in range(SETTLE_FRAMES):
        win.frame()
    screen = moderngl.get_context().screen
    rgb = Image.frombytes("RGB", (screen.width, screen.height), screen.read(components=3))
    out = FIGURES / f"{name}.png"
    rgb.transpose(Image.FLIP_TOP_BOTTOM).save(out)
    return out


def default_layout() -> None:
    _, win = _window()
    try:
        _settle_and_save(win, "default_layout")
    finally:
        win.close()


def old_layout_new_panel() -> None:
    ini = Path(tempfile.mkdtemp()) / "layout.ini"
    _, win = _window(ini)
    win.frame()
    win.close()
    blocks = ini.read_text().split("\n\n")
    ini.write_text("\n\n".join(b for b in blocks if not any(b.startswith(f"[Window][{t}]") for t in NEW_PANELS)))
    _, win = _window(ini)
    try:
        for title in NEW_PANELS:
            win.ui.open_panels[title] = True
        _settle_and_save(win, "old_layout_new_panel")
    finally:
        win.close()


def path_editor() -> None:
    from jackpy.ui.panels import path_editor as pe

    app, win = _window()
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

        def float_it() -> None:
            imgui.internal.dock_builder_dock_window(pe.TITLE, 0)
            imgui.set_window_pos(pe.TITLE, (560, 40))
            imgui.set_window_size(pe.TITLE, (700, 580))

        win.panels_frame(float_it)
        _settle_and_save(win, "path_editor")
    finally:
        win.close()


def devices_live() -> None:
    """The Devices panel driving the human live: a simulator plays the shipped reach on a pty, the
    panel connected with the reach's sensor configuration, calibrated and started (split frames on),
    the picture taken mid-reach."""
    from jackpy.devices.flock.simulator import FlockSimulator
    from jackpy.devices.recording import FrameMotion, read_recording
    from jackpy.ui.panels.devices import link_of

    example = Path(__file__).resolve().parents[1] / "examples" / "flock"
    motion = FrameMotion(read_recording(example / "reach.jsonl"))
    with FlockSimulator(4, motion=motion, rate=100.0, autoconfig_delay=0.05) as sim:
        app, win = _window()
        try:
            win.ui.open_panels["Devices"] = True
            link = link_of(app)
            link.sensors_path = str(example / "reach-sensors.json")
            assert link.connect(sim.paths[0], 4, rts_reset=None, measurement_rate=100.0, autoconfig_wait=0.05), link.error
            for _ in range(10):
                win.frame()
            assert link.calibrate() and link.start(), link.error
            motion.play()
            for _ in range(90):
                win.frame()

            def float_it() -> None:
                imgui.internal.dock_builder_dock_window("Devices", 0)
                imgui.set_window_pos("Devices", (820, 60))
                imgui.set_window_size("Devices", (440, 420))

            win.panels_frame(float_it)
            _settle_and_save(win, "devices_live")
        finally:
            link.disconnect()
            win.close()


PICTURES: dict[str, Callable[[], None]] = {f.__name__: f for f in (default_layout, old_layout_new_panel, path_editor,
                                                                   devices_live)}


def main(names: list[str]) -> None:
    unknown = [n for n in names if n not in PICTURES]
    if unknown:
        sys.exit(f"unknown picture(s) {', '.join(unknown)}; choose from {', '.join(PICTURES)}")
    for name in names or list(PICTURES):
        PICTURES[name]()
        print(FIGURES / f"{name}.png")


if __name__ == "__main__":
    main(sys.argv[1:])
