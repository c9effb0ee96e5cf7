"""Image files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image


def write_png(path: str | Path, pixels: np.ndarray) -> None:
    """Save (H, W, 4) uint8 RGBA pixels, first row at the top, as a PNG file."""
    Image.fromarray(np.asarray(pixels, np.uint8), "RGBA").save(Path(path))
