"""The timeline panel in a real window (Xvfb): open a scene with a motion, press play, the figure
moves; scrub back, the posture equals the baked frame; Ctrl+Z undoes an edit."""

import json
import os
import subprocess
import sys
import time

import numpy as np
import pytest
from ui_support import in_child_process

if not os.environ.get("DISPLAY"):
    pytest.skip("window tests need an X display (run under xvfb-run, see scripts/test.sh)",
                allow_module_level=True)

from jackpy.motion.bake import Posture
from jackpy.motion.player import load_into
from jackpy.ui import session
from jackpy.ui.app import MOD_CONTROL, PRESS, App
from jackpy.ui.panels.timeline import TITLE, player_of
from jackpy.ui.window import Window


def write_motion(path, figure):
    path.write_text(json.dumps({"jackpy_motion": 1, "timeline": {
        "motions": [{"kind": "com", "figure": figure, "t0": 0.0, "t1": 0.4, "x": 0.2, "weight_fn": "ease"},
                    {"kind": "arm", "figure": figure, "side": "right", "t0": 0.1, "t1": 0.8,
                     "target": {"point": [-0.3, 1.2, 0.45]}}],
        "duration": 1.0}}))


def test_play_scrub_undo_in_the_window(request, tmp_path):
    if in_child_process(request):
        return
    env, _ = session.default_scene()
    app = App(env)
    fig = app.figure_of_interest()
    motion = tmp_path / "reach.motion.json"
    write_motion(motion, fig.name)
    load_into(app.doc, str(motion))
    win = Window(app, "jackpy timeline", (1000, 700), visible=False)
    try:
        win.ui.open_panels[TITLE] = True
        win.frame()
        player, _ = player_of(app, win.ui)
        start = Posture.of(fig)
        player.play()  # the Play button's action
        t_end = time.monotonic() + 60
        while player.playing and time.monotonic() < t_end:
            win.frame()
        assert not player.playing
        assert not Posture.of(fig).same(start)  # the figure moved
        pixels = np.frombuffer(win.ctx.screen.read(components=3), np.uint8)
        assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50
        # scrub back: the posture shown is the baked frame, to the bit
        player.scrub(0.3)
        win.frame()
        i = player.baker.frame_at(0.3)
        assert Posture.of(fig).same(player.baker.frames[i][fig.name])
        # an edit, then Ctrl+Z
        m = app.doc.timeline.motions[1]
        player.shift(m, 0.25)
        win.frame()
        assert m.t0 == pytest.approx(0.35)
        app.on_key(ord("Z"), 0, PRESS, MOD_CONTROL)
        win.frame()
        assert app.doc.timeline.motions[1].t0 == pytest.approx(0.1)
    finally:
        win.close()


def test_open_with_motion_runs_frames(tmp_path):
    motion = tmp_path / "m.motion.json"
    write_motion(motion, "male_p50")
    env = dict(os.environ, JACKPY_HOME=str(tmp_path))
    done = subprocess.run([sys.executable, "-m", "jackpy", "open", "--motion", str(motion), "--frames", "3"],
                          env=env, capture_output=True, text=True, timeout=180)
    assert done.returncode == 0, done.stderr
    bad = tmp_path / "bad.motion.json"
    bad.write_text("{")
    done = subprocess.run([sys.executable, "-m", "jackpy", "open", "--motion", str(bad), "--frames", "1"],
                          env=env, capture_output=True, text=True, timeout=180)
    assert done.returncode == 2 and "bad.motion.json:1:2" in done.stderr
