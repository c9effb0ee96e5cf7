"""Headless workplace analysis for a set of figure sizes, written as ``report.html`` (with pictures),
``results.json`` and ``results.csv`` (``jackpy analyze``).

Per figure (sex and percentile of the standard human, standing where the scene says): point reach
of every reach site with the chosen hand, the hand's reachable workspace (sites classified inside or
outside), visibility of every view target from the eyes with its view cone and occluders, joint
torques against strength while reaching the first reach site holding the load, the clearance
to every object and, when asked, the ergonomic assessments of that same posture
(:mod:`jackpy.ergonomics`). Pictures: an overall view, the eye view, the reach envelope and, per
ergonomic method, the assessed posture with its worst body part in the action level's colour.
"""

from __future__ import annotations

import csv
import html
import io
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from jackpy.analysis.clearance import ClearanceChecker
from jackpy.render.bodies import Body, BodyRenderer as OffscreenRenderer, look_at, perspective_matrix as perspective
from jackpy.analysis.parts import figure_parts
from jackpy.analysis.reach import Posture, point_reach
from jackpy.analysis.statics import Load, joint_torques
from jackpy.analysis.strength import (
    dof_strengths,
    joint_utilisation,
    torque_vertex_colours,
    utilisation,
)
from jackpy.analysis.view import (
    environment_bodies,
    eye_view,
    figure_bodies,
    object_visibility,
    point_visibility,
)
from jackpy.analysis.workspace import Chain, reachable_workspace
from jackpy.atomic import atomic_write_bytes, atomic_write_text
from jackpy.ergonomics.summary import flat, json_ready, value_text
from jackpy.errors import JackpyError
from jackpy.peabody.model import Figure
from jackpy.scene.workplace import Workplace, resolve_target, stand_figure

PICTURE_SIZE = (640, 480)
#: how the report names each point-reach mode
REACH_MODE_TEXT = {"arm": "arm only (torso and feet fixed)", "body": "whole body, feet planted, balanced",
                   "step": "whole body, balanced, allowed to step"}


@dataclass
class Options:
    """What to analyse: figure sizes ``(sex, percentile)``, reach and view targets (``object.site``
    or ``object``), the load in the hand (kg), the hand, the workspace resolution (cells per axis)
    and the point-reach mode (``"arm"``, ``"body"`` or ``"step"``, see :func:`point_reach`); the
    ergonomic methods to run (names of :func:`jackpy.ergonomics.methods`) and their
    :class:`~jackpy.ergonomics.Task` (default: the load in the hands)."""

    figures: list[tuple[str, float]]
    reach: list[str] = field(default_factory=list)
    view: list[str] = field(default_factory=list)
    load_kg: float = 0.0
    hand: str = "right"
    resolution: int = 48
    reach_mode: str = "arm"
    ergonomics: list[str] = field(default_factory=list)
    ergo_task: Any = None
    #: reach respects the workplace: no segment deeper than this (m) into an object (issue 16)
    contact_tolerance: float = 0.01


def parse_figures(text: str) -> list[tuple[str, float]]:
    """``"female:5,male:95"`` -> ``[("female", 5.0), ("male", 95.0)]``."""
    out = []
    for item in filter(None, (s.strip() for s in text.split(","))):
        sex, _, pct = item.partition(":")
        try:
            p = float(pct)
        except ValueError:
            raise JackpyError(f"bad figure {item!r}: write SEX:PERCENTILE, e.g. female:5") from None
        if sex not in ("female", "male") or not 0 < p < 100:
            raise JackpyError(f"bad figure {item!r}: sex is female or male, percentile in (0, 100)")
        out.append((sex, p))
    if not out:
        raise JackpyError("no figures given")
    return out


def _human(sex: str, percentile: float) -> Figure:
    from jackpy.body import make_human

    return make_human(sex, percentile)


def _strength_table(figure: Figure):
    from jackpy.body.strength import strength_table

    return dof_strengths(strength_table(figure))


def analyse_figure(wp: Workplace, figure: Figure, opts: Options, renderer: OffscreenRenderer | None,
                   strength_table: Callable[[Figure], Any] = _strength_table,
                   pictures: dict[str, bytes] | None = None, tag: str = "") -> dict[str, Any]:
    """Run every analysis for one figure standing in ``wp``; returns the JSON-ready results and, with
    a renderer, adds PNG pictures to ``pictures`` under ``{tag}-overall.png`` etc."""
    stand_figure(figure, wp.stand)
    parts = figure_parts(figure)
    hand = parts.hands[opts.hand]
    neutral = Posture.of(figure)
    res: dict[str, Any] = {"figure": figure.name, "stature_m": _stature(figure), "hand": opts.hand}
    # --- reach --------------------------------------------------------------------------------
    reaches = {}
    postures = {}
    for ref in opts.reach:
        obj, p = resolve_target(wp.env, ref)
        r = point_reach(figure, p, opts.hand, mode=opts.reach_mode, obstacles=list(wp.objects.values()),
                        target_object=obj.name, contact_tolerance=opts.contact_tolerance)
        postures[ref] = r.posture if r.posture is not None else neutral
        reaches[ref] = {"reached": r.reached, "shortfall_m": r.shortfall, "text": r.describe(),
                        "target": p.tolist(), "ik_status": r.status, "mode": r.mode, "stepped": r.stepped,
                        "steps": r.steps, "balanced": r.balanced, "com_margin_m": r.com_margin,
                        "hand_position": r.position.tolist(), **r.verdict.to_dict()}
    res["reach"] = reaches
    chain = Chain.to_site(figure, hand.start_joint, hand.segment, hand.site)
    ws = reachable_workspace(chain, opts.resolution)
    removed = ws.remove_solids(_object_meshes(wp))
    sites = {ref: resolve_target(wp.env, ref)[1] for ref in opts.reach}
    # a site counts inside the workspace only when the collision-aware reach reached it as well
    res["workspace"] = {"resolution": opts.resolution, "volume_m3": ws.volume(), "samples": ws.samples,
                        "converged": ws.converged, "voxels_inside_objects_removed": removed,
                        "sites": {n: {"inside": i and reaches[n]["reached"], "inside_envelope": i, "distance_m": d}
                                  for n, (i, d) in ws.classify(sites).items()}}
    # --- view ---------------------------------------------------------------------------------
    ev = eye_view(figure)
    views = {}
    if opts.view and renderer is None:
        res["view_skipped"] = "rendering disabled"
    if opts.view and renderer is not None:
        for ref in opts.view:
            obj, p = resolve_target(wp.env, ref)
            others = environment_bodies(wp.env, exclude={obj.name}, eye=ev.position) + figure_bodies(figure, ev.position)
            if "." in ref:
                v = point_visibility(renderer, ev.position, p, others + figure_bodies(obj), ref)
            else:
                v = object_visibility(renderer, ev.position, figure_bodies(obj), others, ref)
            views[ref] = {"visible_fraction": v.fraction, "occluders": v.occluders,
                          "angle_deg": float(np.degrees(ev.angle_to(p))), "cone": ev.cone(p)}
    res["view"] = views
    # --- strength -----------------------------------------------------------------------------
    first = opts.reach[0] if opts.reach else None
    # the first reach's whole posture (after steps the figure stands elsewhere), kept on its own root
    (postures[first] if first else neutral).apply(figure, root=neutral.root)
    loads = [Load.held_mass(figure, hand.segment, hand.site, opts.load_kg)] if opts.load_kg > 0 else []
    tau = joint_torques(figure, loads)
    try:
        table = strength_table(figure)
    except (ImportError, JackpyError, KeyError) as exc:
        res["strength"] = {"available": False, "reason": f"{type(exc).__name__}: {exc}"}
        util = None
    else:
        util = utilisation(figure, tau, table)
        ju = joint_utilisation(figure, util)
        arm = [figure.dof_names()[i] for i in chain.dofs]
        names = figure.dof_names()
        res["strength"] = {
            "available": True, "posture": first or "neutral", "load_kg": opts.load_kg,
            "max_joint": max((j for j in ju if not np.isnan(ju[j])), key=lambda j: ju[j], default=None),
            "max_utilisation": float(np.nanmax(util)) if np.any(~np.isnan(util)) else None,
            "arm": [{"dof": n, "torque_Nm": float(tau[names.index(n)]),
                     "strength_Nm": float(table[n].against(tau[names.index(n)])) if n in table else None,
                     "utilisation": float(util[names.index(n)])} for n in arm],
        }
    # --- clearance ----------------------------------------------------------------------------
    chk = ClearanceChecker(figure, list(wp.objects.values()), self_collision=False)
    res["clearance"] = {}
    for name in wp.objects:
        c = chk.clearance(name)
        res["clearance"][name] = {"distance_m": c.distance, "segment": c.segment}
    res["clearance_posture"] = first or "neutral"
    # --- ergonomics (the strength posture) ----------------------------------------------------
    assessed = _ergonomics(figure, opts)
    if assessed:
        res["ergonomics"] = {"posture": first or "neutral",
                             "methods": {n: json_ready(a.to_dict()) for n, a in assessed.items()}}
    # --- pictures -----------------------------------------------------------------------------
    if renderer is not None and pictures is not None:
        colours = torque_vertex_colours(figure, joint_utilisation(figure, util)) if util is not None else {}
        _pictures(renderer, wp, figure, colours, ws, ev, pictures, tag)
        _ergonomics_pictures(renderer, wp, figure, assessed, pictures, tag)
    neutral.apply(figure)
    return res


def _object_meshes(wp: Workplace) -> list:
    """Every workplace object's meshes in world coordinates."""
    out = []
    for obj in wp.objects.values():
        world = obj.world_transforms()
        for name, seg in obj.segments.items():
            m = seg.psurf.posed_mesh() if seg.psurf is not None else None
            if m is not None and len(m.faces):
                out.append(m.transformed(world[name]))
    return out


def _ergonomics(figure: Figure, opts: Options) -> dict[str, Any]:
    """The assessments ``opts.ergonomics`` of the figure's current posture (empty when none asked)."""
    if not opts.ergonomics:
        return {}
    from jackpy.ergonomics import Task, assess

    task = opts.ergo_task if opts.ergo_task is not None else Task(load_kg=opts.load_kg)
    return assess(figure, opts.ergonomics, task)


def _ergonomics_pictures(renderer: OffscreenRenderer, wp: Workplace, figure: Figure, assessed: dict[str, Any],
                         pictures: dict[str, bytes], tag: str) -> None:
    """Per method, the posture from the front-left with the worst body part in its level's colour."""
    from jackpy.ergonomics.summary import level_colour, worst_segments

    if not assessed:
        return
    bodies = figure_bodies(figure)
    pts = np.vstack([b.mesh.vertices @ b.model[:3, :3].T + b.model[:3, 3] for b in bodies])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre, radius = (lo + hi) / 2, float(np.linalg.norm(hi - lo)) / 2
    fwd = figure.world_transforms()["pelvis"][:3, 2]
    side = np.cross([0.0, 1.0, 0.0], fwd)
    eye = centre + radius * 2.4 * (0.55 * fwd + 0.85 * side + np.array([0.0, 0.25, 0.0]))
    view = look_at(eye, centre)
    proj = perspective(np.radians(40), PICTURE_SIZE[0] / PICTURE_SIZE[1], 0.05, radius * 8)
    env = environment_bodies(wp.env)
    for name, a in assessed.items():
        hot = set(worst_segments(a))
        colour = tuple(level_colour(a)) + (1.0,)
        for b in bodies:
            b.colour = colour if b.name.split(".", 1)[1] in hot else (0.9, 0.9, 0.9, 1.0)
        pictures[f"{tag}-ergo-{name}.png"] = _png(renderer.render(env + bodies, view, proj))


def _stature(figure: Figure) -> float:
    ys = []
    for name, t in figure.world_transforms().items():
        seg = figure.segments[name]
        if seg.psurf is not None and seg.psurf.mesh is not None:
            ys.append((seg.psurf.posed_mesh().vertices @ t[:3, :3].T + t[:3, 3])[:, 1])
    return float(np.ptp(np.concatenate(ys))) if ys else 0.0


def _png(rgb: np.ndarray) -> bytes:
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(rgb).save(buf, format="PNG")
    return buf.getvalue()


def _pictures(renderer: OffscreenRenderer, wp: Workplace, figure: Figure, colours: dict[str, np.ndarray],
              ws, ev, pictures: dict[str, bytes], tag: str) -> None:
    env_bodies = [Body(b.name, b.mesh, b.model,
                       tuple(getattr(wp.env.figures[b.name.split(".")[0]], "colour", b.colour[:3]))[:3] + (1.0,))
                  for b in environment_bodies(wp.env)]
    fig_bodies = figure_bodies(figure)
    for b in fig_bodies:
        seg = b.name.split(".", 1)[1]
        if seg in colours:
            b.vertex_colours = colours[seg]
        else:
            b.colour = (0.95, 0.95, 0.95, 1.0)
    everything = env_bodies + fig_bodies
    pts = np.vstack([b.mesh.vertices @ b.model[:3, :3].T + b.model[:3, 3] for b in everything])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre = (lo + hi) / 2
    radius = float(np.linalg.norm(hi - lo)) / 2
    aspect = PICTURE_SIZE[0] / PICTURE_SIZE[1]
    eye = centre + radius * 2.2 * np.array([0.75, 0.45, 0.85]) / np.linalg.norm([0.75, 0.45, 0.85])
    proj = perspective(np.radians(40), aspect, 0.05, radius * 6)
    view = look_at(eye, centre)
    pictures[f"{tag}-overall.png"] = _png(renderer.render(everything, view, proj))
    pictures[f"{tag}-eye.png"] = _png(renderer.render(
        environment_bodies(wp.env) + figure_bodies(figure, ev.position), ev.view_matrix(), ev.projection()))
    envelope = Body("envelope", ws.surface(), np.eye(4), (0.2, 0.5, 1.0, 0.3))
    pictures[f"{tag}-reach.png"] = _png(renderer.render(everything, view, proj, translucent=[envelope]))


def write_report(wp: Workplace, opts: Options, out_dir: str | Path,
                 make_figure: Callable[[str, float], Figure] = _human,
                 strength_table: Callable[[Figure], Any] = _strength_table,
                 render: bool = True, renderer: OffscreenRenderer | None = None,
                 progress: Callable[[float, str], None] | None = None) -> dict[str, Any]:
    """Analyse every figure size of ``opts`` and write ``report.html``, ``results.json``,
    ``results.csv`` and the pictures into ``out_dir`` (created; files written atomically).

    ``renderer``: render with this one (``PICTURE_SIZE``-sized, not released here) instead of a new
    EGL one (the workbench passes one on its window's context). ``progress(fraction, what)`` is
    called before each figure and when the files are written."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    own_renderer = render and renderer is None
    if own_renderer:
        renderer = OffscreenRenderer(PICTURE_SIZE)
    elif not render:
        renderer = None
    pictures: dict[str, bytes] = {}
    results = {"scene": str(wp.path) if wp.path else None, "load_kg": opts.load_kg, "hand": opts.hand,
               "reach_mode": opts.reach_mode, "contact_tolerance_m": opts.contact_tolerance, "figures": []}
    try:
        for k, (sex, pct) in enumerate(opts.figures):
            if progress is not None:
                progress(k / max(len(opts.figures), 1), f"{sex} {pct:g}%")
            fig = make_figure(sex, pct)
            tag = f"{sex}{pct:g}"
            r = analyse_figure(wp, fig, opts, renderer, strength_table, pictures, tag)
            r.update({"sex": sex, "percentile": pct, "tag": tag})
            results["figures"].append(r)
    finally:
        if own_renderer and renderer is not None:
            renderer.release()
    for name, data in pictures.items():
        atomic_write_bytes(out / name, data)
    atomic_write_text(out / "results.json", json.dumps(results, indent=1, default=_json_default) + "\n")
    atomic_write_text(out / "results.csv", _csv(results))
    atomic_write_text(out / "report.html", _html(results, pictures))
    if progress is not None:
        progress(1.0, "written")
    return results


def _json_default(o: Any) -> Any:
    if isinstance(o, np.generic):
        return o.item()
    raise TypeError(type(o).__name__)


def _rows(results: dict[str, Any]) -> list[list[Any]]:
    rows = []
    for r in results["figures"]:
        f = f"{r['sex']}:{r['percentile']:g}"
        for ref, v in r["reach"].items():
            mode = v.get("mode", "arm")
            rows.append([f, "reach", ref, "shortfall", round(v["shortfall_m"], 4), "m", v["text"], mode])
            if mode != "arm":
                rows.append([f, "reach", ref, "steps", v["steps"], "count",
                             "balanced" if v["balanced"] else "not balanced", mode])
        for ref, v in r["workspace"]["sites"].items():
            rows.append([f, "workspace", ref, "distance", round(v["distance_m"], 4), "m",
                         "inside" if v["inside"] else "outside"])
        rows.append([f, "workspace", r["hand"], "volume", round(r["workspace"]["volume_m3"], 4), "m3", ""])
        for ref, v in r["view"].items():
            occ = "; ".join(f"{k} {100 * s:.0f}%" for k, s in v["occluders"].items())
            rows.append([f, "view", ref, "visible", round(v["visible_fraction"], 3), "fraction",
                         f"{v['cone'] or 'outside field'}" + (f"; hidden by {occ}" if occ else "")])
        s = r["strength"]
        if s.get("available"):
            for d in s["arm"]:
                rows.append([f, "strength", d["dof"], "utilisation", round(d["utilisation"], 3), "fraction",
                             f"{d['torque_Nm']:.1f} N m of {d['strength_Nm']:.1f}" if d["strength_Nm"] is not None else ""])
        for name, c in r["clearance"].items():
            rows.append([f, "clearance", name, "distance", round(c["distance_m"], 4), "m", c["segment"]])
        for name, a in r.get("ergonomics", {}).get("methods", {}).items():
            rows.append([f, "ergonomics", name, "score", a["score"], a["unit"], a["action"]])
            rows.append([f, "ergonomics", name, "level", a["level"], "", "; ".join(a["flags"])])
            rows += [[f, "ergonomics", name, k, v, "", "worksheet"] for k, v in flat(a["worksheet"])]
            rows += [[f, "ergonomics", name, k, v, "", "posture"] for k, v in flat(a["posture"])]
    return rows


def _csv(results: dict[str, Any]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["figure", "analysis", "target", "metric", "value", "unit", "note", "reach_mode"])
    w.writerows(row + [""] * (8 - len(row)) for row in _rows(results))
    return buf.getvalue()


def _records(v: Any) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def _ergonomics_html(r: dict[str, Any], pictures: dict[str, bytes]) -> str:
    """The report's ergonomics sections: per method its score, flags, worksheet and posture picture."""
    e = html.escape
    t = r["tag"]
    out = [f"<h3>Ergonomics</h3><p>Posture: {e(r['ergonomics']['posture'])}.</p>"]
    for name, a in r["ergonomics"]["methods"].items():
        score = value_text(a["score"]) if a["score"] is not None else "inf"
        out.append(f"<h4>{e(name)}: {e(score)} {e(a['unit'])} (level {a['level']})</h4><p>{e(a['action'])}; worst: "
                   f"{e(str(a['worst']))}.</p>")
        if f"{t}-ergo-{name}.png" in pictures:
            out.append(f"<img src='{t}-ergo-{name}.png' alt='{e(name)} posture' width='427'>")
        out += [f"<p class='bad'>{e(f)}</p>" for f in a["flags"]]
        rows = {k: v for k, v in a["worksheet"].items() if not _records(v)}
        out.append("<table><tr><th>worksheet</th><th>value</th></tr>")
        out += [f"<tr><td>{e(k)}</td><td>{e(value_text(v))}</td></tr>" for k, v in flat(rows)]
        out.append("</table>")
        for k, v in a["worksheet"].items():  # lists of records (joints, lifts) as tables of their own
            if _records(v):
                cols = list(dict.fromkeys(c for r in v for c, _ in flat(r)))
                out.append(f"<table><tr><th>{e(k)}</th>" + "".join(f"<th>{e(c)}</th>" for c in cols) + "</tr>")
                for i, r in enumerate(v):
                    cells = dict(flat(r))
                    out.append(f"<tr><td>{i + 1}</td>" + "".join(f"<td>{e(value_text(cells.get(c, '')))}</td>"
                                                                for c in cols) + "</tr>")
                out.append("</table>")
        out.append(f"<table><tr><th>posture ({e(a['frame'])})</th><th>value</th></tr>")
        out += [f"<tr><td>{e(k)}</td><td>{e(value_text(v))}</td></tr>" for k, v in flat(a["posture"])]
        out.append("</table>")
    return "\n".join(out)


def _html(results: dict[str, Any], pictures: dict[str, bytes]) -> str:
    e = html.escape
    parts = ["<!doctype html><html><head><meta charset='utf-8'><title>jackpy workplace report</title>",
             ("<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;margin:1em 0}"
             "td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}img{margin:4px;border:1px solid #ccc}"
             ".bad{color:#b00}.good{color:#070}</style></head><body>"),
             (f"<h1>Workplace report</h1><p>Scene: {e(str(results['scene']))}; hand: {e(results['hand'])}; "
             f"load in the hand: {results['load_kg']:g} kg; reach: "
             f"{e(REACH_MODE_TEXT.get(results.get('reach_mode', 'arm'), ''))}; a target counts as reached only "
             f"with no body segment more than {1000 * results.get('contact_tolerance_m', 0.01):.0f} mm into "
             f"any object (the palm may meet the target's own object).</p>")]
    for r in results["figures"]:
        t = r["tag"]
        parts.append(f"<h2>{e(r['sex'])}, {r['percentile']:g}th percentile (stature {r['stature_m'] * 100:.1f} cm)</h2>")
        parts.append("".join(f"<img src='{t}-{k}.png' alt='{k}' width='427'>" for k in ("overall", "eye", "reach")
                             if f"{t}-{k}.png" in pictures))
        parts.append("<h3>Reach</h3><table><tr><th>target</th><th>result</th><th>steps</th><th>in workspace</th></tr>")
        for ref, v in r["reach"].items():
            ws = r["workspace"]["sites"].get(ref, {})
            cls = "good" if v["reached"] else "bad"
            steps = "–" if v.get("mode", "arm") != "step" else str(v["steps"])
            parts.append(f"<tr><td>{e(ref)}</td><td class='{cls}'>{e(v['text'])}</td><td>{steps}</td>"
                         f"<td>{'inside' if ws.get('inside') else 'outside'}</td></tr>")
        parts.append(f"</table><p>Workspace volume of the {e(r['hand'])} hand: "
                     f"{r['workspace']['volume_m3']:.3f} m³ ({r['workspace']['resolution']}³ voxels).</p>")
        if r["view"]:
            parts.append("<h3>View</h3><table><tr><th>target</th><th>visible</th><th>view cone</th><th>hidden by</th></tr>")
            for ref, v in r["view"].items():
                occ = ", ".join(f"{e(k)} ({100 * s:.0f}%)" for k, s in v["occluders"].items()) or "–"
                parts.append(f"<tr><td>{e(ref)}</td><td>{100 * v['visible_fraction']:.0f}%</td>"
                             f"<td>{e(v['cone'] or 'outside the visual field')} ({v['angle_deg']:.0f}°)</td><td>{occ}</td></tr>")
            parts.append("</table>")
        s = r["strength"]
        parts.append("<h3>Strength</h3>")
        if s.get("available"):
            parts.append(f"<p>Posture: reaching {e(s['posture'])}, {s['load_kg']:g} kg in the hand. Highest "
                         f"utilisation: {e(str(s['max_joint']))} at {100 * (s['max_utilisation'] or 0):.0f}% of strength.</p>"
                         "<table><tr><th>DOF</th><th>torque N m</th><th>strength N m</th><th>utilisation</th></tr>")
            for d in s["arm"]:
                cls = "bad" if d["utilisation"] > 1 else ""
                sn = f"{d['strength_Nm']:.1f}" if d["strength_Nm"] is not None else "–"
                parts.append(f"<tr><td>{e(d['dof'])}</td><td>{d['torque_Nm']:.1f}</td><td>{sn}</td>"
                             f"<td class='{cls}'>{100 * d['utilisation']:.0f}%</td></tr>")
            parts.append("</table>")
        else:
            parts.append(f"<p>Not available: {e(s['reason'])}</p>")
        parts.append(f"<h3>Clearance</h3><p>Posture: {e(r['clearance_posture'])}.</p>"
                     "<table><tr><th>object</th><th>clearance</th><th>nearest segment</th></tr>")
        for name, c in r["clearance"].items():
            parts.append(f"<tr><td>{e(name)}</td><td>{c['distance_m'] * 100:.1f} cm</td><td>{e(c['segment'])}</td></tr>")
        parts.append("</table>")
        if "ergonomics" in r:
            parts.append(_ergonomics_html(r, pictures))
    parts.append("</body></html>\n")
    return "\n".join(parts)
