"""Assessments over every baked frame of a motion: rows, a text table, CSV/JSON files and SVG plots."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path
from typing import Any

from jackpy.ergonomics.base import ErgonomicsError, Task
from jackpy.ergonomics.summary import json_ready, value_text
from jackpy.peabody.model import Figure


def baked_human(motion_path: str, name: str | None, human: str | None) -> tuple[str | None, str | None]:
    """For a human made here (workplace scene or empty floor): the figure name and size to make so
    the motion's frames apply — with one baked figure, its name and its ``human`` size unless given."""
    from jackpy.motion import motion_file

    mf = motion_file.load(motion_path)
    if name is None and len(mf.baked) == 1:
        name = next(iter(mf.baked))
    baked = mf.baked.get(name) if name is not None else None
    if human is None and baked is not None and baked.human:
        human = baked.human
    return name, human


def per_frame(figure: Figure, motion_path: str, names: list[str], task: Task) -> dict[str, Any]:
    """Score ``names`` at every baked frame of the motion file for ``figure`` (matched by name);
    the figure's own posture is restored afterwards. Returns ``{"figure", "fps", "frames": [{"frame",
    "time", "<method>": score, "<method>_level": level, "<method>_worst": part}...]}``."""
    from jackpy.ergonomics import assess
    from jackpy.motion import motion_file
    from jackpy.motion.bake import Posture

    mf = motion_file.load(motion_path)
    baked = mf.baked.get(figure.name)
    if baked is None:
        known = ", ".join(sorted(mf.baked)) or "none"
        raise ErgonomicsError(f"{motion_path}: no baked frames for figure {figure.name!r} (baked: {known}); "
                              "bake the motion first (jackpy motion) or choose the figure with --figure")
    keep = Posture.of(figure)
    fps = float(mf.fps or 0.0)
    rows = []
    try:
        for i in range(baked.n_frames):
            baked.posture(figure, i).apply_to(figure)
            res = assess(figure, names, task)
            row: dict[str, Any] = {"frame": i, "time": i / fps if fps else 0.0}
            for n, a in res.items():
                row[n] = a.score
                row[f"{n}_level"] = a.level
                row[f"{n}_worst"] = a.worst
            rows.append(row)
    finally:
        keep.apply_to(figure)
    return {"figure": figure.name, "motion": str(motion_path), "fps": fps, "frames": rows}


def frames_table(frames: dict[str, Any], names: list[str]) -> str:
    """A fixed-width text table: frame, time and each method's score and level."""
    head = ["frame", "time_s"] + [h for n in names for h in (n, "level")]
    lines = ["  ".join(f"{h:>8}" for h in head)]
    for r in frames["frames"]:
        cells = [str(r["frame"]), f"{r['time']:.3f}"] + [c for n in names
                                                        for c in (value_text(r[n]), str(r[f"{n}_level"]))]
        lines.append("  ".join(f"{c:>8}" for c in cells))
    return "\n".join(lines)


def frames_csv(frames: dict[str, Any], names: list[str]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    cols = ["frame", "time"] + [c for n in names for c in (n, f"{n}_level", f"{n}_worst")]
    w.writerow(cols)
    for r in frames["frames"]:
        w.writerow([r[c] for c in cols])
    return buf.getvalue()


def svg_plot(times: list[float], values: list[float], title: str, width: int = 640, height: int = 240) -> str:
    """A line plot of ``values`` over ``times`` as standalone SVG text (axes with their ranges)."""
    import math

    pts = [(t, v) for t, v in zip(times, values) if v is not None and math.isfinite(v)]
    m = 40
    t0, t1 = (min(times), max(times)) if times else (0.0, 1.0)
    v0 = min((v for _, v in pts), default=0.0)
    v1 = max((v for _, v in pts), default=1.0)
    v0, v1 = min(v0, 0.0), (v1 if v1 > v0 else v0 + 1.0)
    sx = (width - 2 * m) / ((t1 - t0) or 1.0)
    sy = (height - 2 * m) / (v1 - v0)
    line = " ".join(f"{m + (t - t0) * sx:.1f},{height - m - (v - v0) * sy:.1f}" for t, v in pts)
    esc = title.replace("&", "&amp;").replace("<", "&lt;")
    return (f"<svg xmlns='http://www.w3.org/2000/svg' width='{width}' height='{height}' font-family='sans-serif' "
            f"font-size='11'><rect width='100%' height='100%' fill='white'/>"
            f"<text x='{m}' y='20' font-size='13'>{esc}</text>"
            f"<line x1='{m}' y1='{height - m}' x2='{width - m}' y2='{height - m}' stroke='black'/>"
            f"<line x1='{m}' y1='{m}' x2='{m}' y2='{height - m}' stroke='black'/>"
            f"<text x='{m}' y='{height - m + 15}'>{t0:.2f} s</text>"
            f"<text x='{width - m}' y='{height - m + 15}' text-anchor='end'>{t1:.2f} s</text>"
            f"<text x='{m - 4}' y='{height - m}' text-anchor='end'>{v0:.3g}</text>"
            f"<text x='{m - 4}' y='{m + 4}' text-anchor='end'>{v1:.3g}</text>"
            f"<polyline fill='none' stroke='#1f5fbf' stroke-width='1.5' points='{line}'/></svg>\n")


def write_frames(frames: dict[str, Any], names: list[str], out: Path) -> list[Path]:
    """Write ``frames.csv``, ``frames.json`` and ``<method>.svg`` into ``out`` (atomically, each file
    whole or not at all; everything is computed before the first write)."""
    from jackpy.atomic import atomic_write_text

    times = [r["time"] for r in frames["frames"]]
    files = {"frames.csv": frames_csv(frames, names),
             "frames.json": json.dumps(json_ready(frames), indent=1) + "\n"}
    for n in names:
        files[f"{n}.svg"] = svg_plot(times, [r[n] for r in frames["frames"]], f"{n} over time ({frames['figure']})")
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, text in files.items():
        atomic_write_text(out / name, text)
        written.append(out / name)
    return written
