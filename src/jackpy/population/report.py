"""The sweep report: ``accommodation.csv`` / ``accommodation.json`` and ``report.html`` with SVG plots
(``scatter.svg``: stature x weight coloured by passing every criterion, with each sex's 90 %
stature-weight ellipse; ``accommodation.svg``: the share per criterion; one scatter per criterion),
written atomically into the sweep's folder."""

from __future__ import annotations

import csv
import html
import io
import json
from pathlib import Path
from typing import Any

import numpy as np

from jackpy.atomic import atomic_write_text
from jackpy.population import svg
from jackpy.population.accommodation import COLUMNS, Accommodation, accommodation
from jackpy.population.families import boundary_points
from jackpy.population.model import PopulationModel
from jackpy.population.study import Study


def _ellipse(sex: str, share: float = 0.9) -> np.ndarray:
    sm = PopulationModel.ansur2(("stature", "weight")).sex(sex)
    pts = boundary_points(sm, ("stature", "weight"), share, n=72)
    xy = np.array([[p["stature"] * 100, p["weight"]] for p in pts])
    return np.vstack([xy, xy[:1]])


def _fmt(v: Any) -> str:
    if v is None:
        return ""
    return f"{v:.4f}" if isinstance(v, float) else str(v)


def write_report(folder: str | Path, study: Study, rows: list[dict[str, Any]], title: str,
                 complete: bool = True) -> list[Accommodation]:
    """Write the accommodation table, plots and ``report.html`` for ``rows``; returns the table."""
    out = Path(folder)
    table = accommodation(study, rows)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for a in table:
        w.writerow([_fmt(a.as_row()[c]) for c in COLUMNS])
    atomic_write_text(out / "accommodation.csv", buf.getvalue())
    atomic_write_text(out / "accommodation.json", json.dumps([a.as_row() for a in table], indent=1) + "\n")
    if not rows:
        return table
    stature = np.array([r["stature"] for r in rows]) * 100
    weight = np.array([r["weight"] for r in rows])
    markers = ["o" if r["sex"] == "female" else "s" for r in rows]
    sexes = sorted({r["sex"] for r in rows})
    ellipses = [_ellipse(s) for s in sexes]
    pictures = {"scatter.svg": svg.scatter(stature, weight, np.array([r["all"] for r in rows]),
                                           "All criteria: pass / fail", "stature (cm)", "weight (kg)", ellipses, markers),
                "accommodation.svg": svg.bars([a.criterion for a in table], [a.share for a in table],
                                              "Share accommodated")}
    for k, c in enumerate(study.criteria):
        pictures[f"criterion_{k + 1}.svg"] = svg.scatter(
            stature, weight, np.array([r[c.id] for r in rows]), c.id, "stature (cm)", "weight (kg)", ellipses, markers)
    for name, text in pictures.items():
        atomic_write_text(out / name, text)
    atomic_write_text(out / "report.html", _html(title, table, pictures, len(rows), complete))
    return table


def _html(title: str, table: list[Accommodation], pictures: dict[str, str], n: int, complete: bool) -> str:
    head = "".join(f"<th>{html.escape(c)}</th>" for c in COLUMNS)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(_fmt(a.as_row()[c]))}</td>" for c in COLUMNS) + "</tr>"
                   for a in table)
    note = "" if complete else "<p><b>Incomplete sweep</b>: resume it with <code>--resume</code>.</p>"
    figures = "".join(f"<figure>{text}<figcaption>{html.escape(name)}</figcaption></figure>"
                      for name, text in pictures.items())
    return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<style>body{{font-family:sans-serif;margin:2em}} table{{border-collapse:collapse}}
td,th{{border:1px solid #ccc;padding:3px 8px}} figure{{display:inline-block;margin:8px}}</style></head>
<body><h1>{html.escape(title)}</h1>{note}
<p>{n} bodies. Share = bodies passing / bodies evaluated; binding dimension = the body dimension most
correlated with passing (fails_when: small or large values fail). Circles: women; squares: men; dashed:
each sex's 90 % stature-weight ellipse. Per-body table: <code>bodies.csv</code>.</p>
<table><tr>{head}</tr>{body}</table>
{figures}
</body></html>
"""
