"""``jackpy info FILE``: summarise a Peabody ``.fig`` or ``.env`` file (figures, joints, DOFs, bounds)."""

from __future__ import annotations

import argparse
import json
import math

import numpy as np

from jackpy.commands.convert import add_path_options, load_scene
from jackpy.peabody.model import Figure


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("info", help="summarise a .fig/.env file: figures, segments, joints, DOFs, sites, bounds")
    p.add_argument("file", metavar="FILE", help="a Peabody .fig or .env file")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--no-geometry", action="store_true",
                   help="do not require the psurf geometry files (bounds then come from sites)")
    add_path_options(p)
    p.set_defaults(func=run)


def figure_summary(fig: Figure) -> dict:
    """A JSON-ready summary of one figure; lengths in centimetres, world frame."""
    from jackpy.peabody.export import world_bounds

    with np.errstate(all="ignore"):
        bounds, source = world_bounds(fig)
    human = fig.human
    return {
        "name": fig.name,
        "root": ".".join(fig.root) if fig.root else fig.root_segment(),
        "segments": list(fig.segments),
        "joints": [{"name": j.name, "from": f"{j.from_seg}.{j.from_site}", "to": f"{j.to_seg}.{j.to_site}",
                    "type": j.type_text(), "dofs": j.ndof} for j in fig.joints.values()],
        "groups": [{"name": g.name, "joints": g.joints, "angles": g.angle_names} for g in fig.groups.values()],
        "dofs": fig.ndof,
        "sites": [name for name, _ in fig.iter_sites()],
        "mass_kg": round(fig.total_mass, 9),
        "bounds_cm": {"min": [_number(v * 100) for v in bounds[0]],
                      "max": [_number(v * 100) for v in bounds[1]], "from": source},
        "human": None if human is None else {"population": human.population, "sex": human.sex,
                                             "percentile": human.percentile},
    }


def _number(v: float) -> float | None:
    """A JSON-ready rounded number; ``None`` (null) for a value that is not finite."""
    v = float(v)
    return round(v, 6) + 0.0 if math.isfinite(v) else None


def _vec(v: list[float | None]) -> str:
    return "(" + ", ".join("?" if x is None else f"{x:g}" for x in v) + ")"


def run(args: argparse.Namespace) -> int:
    env = load_scene(args.file, args, require_geometry=not args.no_geometry)
    figures = [figure_summary(f) for f in env.figures.values()]
    if args.json:
        print(json.dumps({"file": args.file, "includes": env.includes, "outside": env.outside, "figures": figures},
                         indent=2, allow_nan=False))
        return 0
    print(f"{args.file}: {len(figures)} figure{'s' if len(figures) != 1 else ''}"
          + (f", includes {', '.join(env.includes)}" if env.includes else ""))
    for f in figures:
        print(f"figure {f['name']}: {len(f['segments'])} segments, {len(f['joints'])} joints, "
              f"{f['dofs']} DOFs, {len(f['sites'])} sites, root {f['root']}, mass {f['mass_kg']:g} kg")
        if f["human"] is not None:
            h = f["human"]
            print(f"  jackpy human: {h['sex']}, percentile {h['percentile']:g}, population {h['population']}")
        print(f"  segments: {', '.join(f['segments'])}")
        for j in f["joints"]:
            print(f"  joint {j['name']}: {j['from']} -> {j['to']}, {j['type']}")
        for g in f["groups"]:
            print(f"  group {g['name']}: angles {', '.join(g['angles'])} drive {', '.join(g['joints'])}")
        print(f"  sites: {', '.join(f['sites'])}")
        b = f["bounds_cm"]
        print(f"  bounds (world, cm, from {b['from']}): min {_vec(b['min'])} max {_vec(b['max'])}")
    return 0
