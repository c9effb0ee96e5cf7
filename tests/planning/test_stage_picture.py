"""The final posture's picture of `jackpy reach` (issue 16: the report records the stage that
succeeded and the final posture's picture): a real offscreen render (moderngl EGL) shows the
figure and the target's red marker, and the CLI writes it beside reach.json."""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np
from PIL import Image

from jackpy.analysis.report import _human
from jackpy.cli import main
from jackpy.planning.stage_picture import SIZE, posture_picture
from jackpy.scene.workplace import load_workplace, resolve_target, stand_figure

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "workplace" / "workplace.json"


def _red(rgb: np.ndarray) -> int:
    r, g, b = (rgb[..., k].astype(int) for k in range(3))
    return int(((r > 180) & (g < 60) & (b < 60)).sum())


def test_the_picture_shows_the_figure_and_the_target():
    wp = load_workplace(EXAMPLE)
    figure = _human("female", 5)
    stand_figure(figure, wp.stand)
    _, hand = resolve_target(wp.env, "desk.button")  # on the desk, seen from above
    rgb = np.asarray(Image.open(io.BytesIO(posture_picture(wp.env, figure, None, hand))).convert("RGB"))
    assert rgb.shape == (SIZE[1], SIZE[0], 3)
    assert _red(rgb) > 30  # the marker
    far = np.asarray(Image.open(io.BytesIO(posture_picture(wp.env, figure, None, hand + [0, 50.0, 0]))))
    assert _red(far[..., :3]) == 0  # ... and only the marker is that red


def test_jackpy_reach_writes_the_final_posture_picture(tmp_path):
    out = tmp_path / "out"
    assert main(["reach", str(EXAMPLE), "--figure", "female:5", "--target", "desk.button", "-o", str(out)]) == 0
    res = json.loads((out / "reach.json").read_text())
    assert res["picture"] == "reach.png"
    rgb = np.asarray(Image.open(out / "reach.png").convert("RGB"))
    assert rgb.std() > 10  # a scene, not a blank image
