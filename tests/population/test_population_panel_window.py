"""The Population panel draws in the real workbench window (Xvfb), in a fresh interpreter (a GLX
window cannot share a process with the EGL contexts of offscreen tests)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run)", allow_module_level=True)

SCRIPT = """
from jackpy.ui import session
from jackpy.ui.app import App
from jackpy.ui.window import Window
env, base = session.default_scene()
app = App(env)
win = Window(app, "population", (900, 640), visible=False)
try:
    win.ui.open_panels["Population"] = True
    for _ in range(3):
        win.frame()
    state = win.ui.panel_states["Population"]
    assert state["share"] == 90.0 and state["job"] is None
finally:
    win.close()
print("drawn")
"""


def test_population_panel_draws() -> None:
    run = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=240)
    assert run.returncode == 0 and "drawn" in run.stdout, run.stderr[-3000:]
