"""Axis ticks for the report charts (the sweep's SVG charts, the lifting plot)."""

from __future__ import annotations

import numpy as np


def nice_ticks(lo: float, hi: float, n: int = 5) -> np.ndarray:
    """Round tick values covering [lo, hi] with about ``n`` steps of 1, 2 or 5 × 10^k."""
    span = hi - lo if hi > lo else 1.0
    step = 10 ** np.floor(np.log10(span / n))
    for m in (1, 2, 5, 10):
        if span / (step * m) <= n:
            step *= m
            break
    return np.arange(np.ceil(lo / step) * step, hi + step * 1e-9, step)
