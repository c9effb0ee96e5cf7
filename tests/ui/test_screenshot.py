"""``jackpy screenshot``: the default scene renders headless and the figure is visible."""

import numpy as np
import pytest
from PIL import Image

from jackpy.cli import main


@pytest.fixture(autouse=True)
def _needs_egl():
    from jackpy.render import create_egl_context

    try:
        create_egl_context().release()
    except Exception as exc:
        pytest.skip(f"no offscreen OpenGL context: {exc}")


def skin_pixels(img: np.ndarray) -> int:
    """Pixels in the figure's skin tone (red > green > blue, bright)."""
    r, g, b = (img[..., k].astype(int) for k in range(3))
    return int(np.count_nonzero((r > 150) & (r - b > 50) & (r > g) & (g > b)))


@pytest.mark.parametrize("view", ["front", "iso"])
def test_default_scene_png_shows_the_figure(tmp_path, view):
    out = tmp_path / f"{view}.png"
    assert main(["screenshot", "default", "-o", str(out), "--size", "320x240", "--view", view]) == 0
    img = np.asarray(Image.open(out))
    assert img.shape == (240, 320, 4)
    assert skin_pixels(img) > 300
    background = np.array([0.16, 0.17, 0.19]) * 255
    assert np.abs(img[5, 5, :3] - background).max() < 12  # top corner: empty sky


def test_skeleton_mode_draws_balls_and_sticks_instead_of_segments(tmp_path):
    images = {}
    for mode in ("mesh", "skeleton"):
        out = tmp_path / f"{mode}.png"
        extra = ["--skeleton"] if mode == "skeleton" else []
        assert main(["screenshot", "default", "-o", str(out), "--size", "320x240", *extra]) == 0
        images[mode] = np.asarray(Image.open(out))
    gold = images["skeleton"].astype(int)
    balls = (gold[..., 0] > 170) & (gold[..., 1] > 120) & (gold[..., 2] < 110)
    assert np.count_nonzero(balls) > 30
    assert skin_pixels(images["skeleton"]) < skin_pixels(images["mesh"]) / 2


def test_bad_size_is_one_line_error(tmp_path, capsys):
    assert main(["screenshot", "default", "-o", str(tmp_path / "x.png"), "--size", "big"]) == 1
    assert "--size" in capsys.readouterr().err
