"""Small SVG charts for the sweep report (no plotting library): a scatter plot with pass/fail
colours and optional ellipses, and a horizontal bar chart of shares."""

from __future__ import annotations

import html
from collections.abc import Sequence

import numpy as np

from jackpy.analysis.ticks import nice_ticks

PASS_COLOUR = "#2e8b57"
FAIL_COLOUR = "#d62728"
_W, _H, _M = 560, 400, 56


def scatter(x: np.ndarray, y: np.ndarray, passed: np.ndarray, title: str, xlabel: str, ylabel: str,
            ellipses: Sequence[np.ndarray] = (), markers: Sequence[str] | None = None) -> str:
    """Scatter of (x, y), green where ``passed`` else red; ``ellipses``: (k, 2) outlines drawn as
    polylines; ``markers``: per point ``o`` (circle) or ``s`` (square, e.g. the other sex)."""
    pts = [np.column_stack([x, y])] + [np.asarray(e) for e in ellipses]
    allp = np.vstack(pts)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    pad = (hi - lo) * 0.05 + 1e-9
    lo, hi = lo - pad, hi + pad

    def px(p: np.ndarray) -> np.ndarray:
        return np.column_stack([_M + (p[:, 0] - lo[0]) / (hi[0] - lo[0]) * (_W - 1.5 * _M),
                                _H - _M - (p[:, 1] - lo[1]) / (hi[1] - lo[1]) * (_H - 1.7 * _M)])

    out = [_head(title)]
    out += _axes(lo, hi, xlabel, ylabel)
    for e in ellipses:
        q = px(np.asarray(e))
        out.append('<polyline fill="none" stroke="#444" stroke-dasharray="4 3" points="'
                   + " ".join(f"{a:.1f},{b:.1f}" for a, b in q) + '"/>')
    for k, (a, b) in enumerate(px(np.column_stack([x, y]))):
        colour = PASS_COLOUR if passed[k] else FAIL_COLOUR
        if markers is not None and markers[k] == "s":
            out.append(f'<rect x="{a - 2.5:.1f}" y="{b - 2.5:.1f}" width="5" height="5" fill="{colour}" '
                       'fill-opacity="0.6"/>')
        else:
            out.append(f'<circle cx="{a:.1f}" cy="{b:.1f}" r="2.6" fill="{colour}" fill-opacity="0.6"/>')
    out.append(_legend([("pass", PASS_COLOUR), ("fail", FAIL_COLOUR)]))
    out.append("</svg>")
    return "\n".join(out)


def bars(labels: Sequence[str], shares: Sequence[float], title: str) -> str:
    """Horizontal bars of ``shares`` (0..1) with percent labels."""
    row = 24
    height = 60 + row * len(labels)
    left = 220
    width = _W - left - 60
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{_W}" height="{height}" font-family="sans-serif" '
           'font-size="12">', f'<text x="{_W / 2}" y="20" text-anchor="middle" font-size="14">{html.escape(title)}</text>']
    for k, (lab, s) in enumerate(zip(labels, shares)):
        y = 36 + k * row
        out.append(f'<text x="{left - 6}" y="{y + 14}" text-anchor="end">{html.escape(lab)}</text>')
        out.append(f'<rect x="{left}" y="{y}" width="{width}" height="{row - 6}" fill="#eee"/>')
        out.append(f'<rect x="{left}" y="{y}" width="{width * s:.1f}" height="{row - 6}" fill="{PASS_COLOUR}"/>')
        out.append(f'<text x="{left + width + 6}" y="{y + 14}">{100 * s:.1f} %</text>')
    out.append("</svg>")
    return "\n".join(out)


def _head(title: str) -> str:
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{_W}" height="{_H}" font-family="sans-serif" '
            f'font-size="12"><text x="{_W / 2}" y="20" text-anchor="middle" font-size="14">{html.escape(title)}</text>')


def _axes(lo: np.ndarray, hi: np.ndarray, xlabel: str, ylabel: str) -> list[str]:
    x0, x1, y0, y1 = _M, _W - _M / 2, _H - _M, _M * 0.7
    out = [f'<rect x="{x0}" y="{y1}" width="{x1 - x0}" height="{y0 - y1}" fill="none" stroke="#888"/>']
    for t in nice_ticks(lo[0], hi[0]):
        a = x0 + (t - lo[0]) / (hi[0] - lo[0]) * (x1 - x0)
        out.append(f'<line x1="{a:.1f}" y1="{y0}" x2="{a:.1f}" y2="{y0 + 4}" stroke="#888"/>'
                   f'<text x="{a:.1f}" y="{y0 + 16}" text-anchor="middle">{t:g}</text>')
    for t in nice_ticks(lo[1], hi[1]):
        b = y0 - (t - lo[1]) / (hi[1] - lo[1]) * (y0 - y1)
        out.append(f'<line x1="{x0 - 4}" y1="{b:.1f}" x2="{x0}" y2="{b:.1f}" stroke="#888"/>'
                   f'<text x="{x0 - 6}" y="{b + 4:.1f}" text-anchor="end">{t:g}</text>')
    out.append(f'<text x="{(x0 + x1) / 2}" y="{_H - 14}" text-anchor="middle">{html.escape(xlabel)}</text>')
    out.append(f'<text x="14" y="{(y0 + y1) / 2}" text-anchor="middle" '
               f'transform="rotate(-90 14 {(y0 + y1) / 2})">{html.escape(ylabel)}</text>')
    return out


def _legend(items: list[tuple[str, str]]) -> str:
    parts = []
    for k, (label, colour) in enumerate(items):
        x = _W - _M / 2 - 120 + 60 * k
        parts.append(f'<circle cx="{x}" cy="{_M * 0.7 - 10}" r="4" fill="{colour}"/>'
                     f'<text x="{x + 8}" y="{_M * 0.7 - 6}">{label}</text>')
    return "".join(parts)
