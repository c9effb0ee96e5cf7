"""``jackpy creature walk|new``: walk or pronk any N-legged figure over terrain to a goal (baked
motion), and build a 3-D creature figure from an editor drawing. See docs/creatures.md."""

from __future__ import annotations

import argparse
import math
import sys

from jackpy.errors import ParseError


def _point(text: str) -> tuple[float, float]:
    try:
        x, z = (float(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected X,Z in metres, not {text!r}") from None
    if not (math.isfinite(x) and math.isfinite(z)):
        raise argparse.ArgumentTypeError(f"expected finite X,Z, not {text!r}")
    return x, z


def _positive(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, not {text!r}") from None
    if not (v > 0 and math.isfinite(v)):
        raise argparse.ArgumentTypeError(f"must be > 0, not {text}")
    return v


def register(sub: argparse._SubParsersAction) -> None:
    from jackpy.locomotion.gaits import GAITS

    p = sub.add_parser("creature", help="walk or pronk jointed creatures over terrain; build creatures from drawings")
    csub = p.add_subparsers(dest="creature_command", required=True, metavar="COMMAND")
    w = csub.add_parser("walk", help="walk (or pronk) a figure over terrain to a goal; writes a baked motion")
    w.add_argument("figure", metavar="FIG", help="figure file (.fig); its posture is the neutral stance")
    w.add_argument("--figure-name", default=None, metavar="NAME", help="which figure of the file (default: the first)")
    w.add_argument("--terrain", default=None, metavar="TERRAIN", help="terrain (.json or .png); default flat ground")
    w.add_argument("--gait", choices=GAITS, default="auto", help="gait (default auto: trot up to 4 legs, else wave)")
    w.add_argument("--to", type=_point, default=None, metavar="X,Z", help="goal in metres (default 5 m ahead)")
    w.add_argument("--seconds", type=_positive, default=None, metavar="S", help="duration (default: until there)")
    w.add_argument("--fps", type=_positive, default=30.0, help="frames per second (default 30)")
    w.add_argument("--events", default=None, metavar="OUT.csv", help="also write the footstep event log as CSV")
    w.add_argument("-o", "--output", required=True, metavar="OUT.motion.json")
    w.set_defaults(func=run_walk)
    n = csub.add_parser("new", help="build a 3-D creature figure from a 2-D editor drawing (JSON)")
    n.add_argument("drawing", metavar="DRAWING.json")
    n.add_argument("--style", choices=("insect", "mammal"), default=None, help="axis style (default: the drawing's)")
    n.add_argument("-o", "--output", required=True, metavar="OUT.fig")
    n.set_defaults(func=run_new)


def run_walk(args: argparse.Namespace) -> int:
    import numpy as np

    from jackpy.locomotion import terrain as terrain_mod
    from jackpy.locomotion.config import PronkConfig, WalkConfig
    from jackpy.motion import motion_file
    from jackpy.peabody.reader import load

    env = load(args.figure)
    figs = [f for f in env.figures.values() if f.joints]
    if args.figure_name is not None:
        figs = [f for f in figs if f.name == args.figure_name]
    if not figs:
        raise ParseError("no articulated figure" + (f" named {args.figure_name!r}" if args.figure_name else ""), args.figure)
    fig = figs[0]
    terrain = terrain_mod.load(args.terrain) if args.terrain else terrain_mod.Terrain.flat(40.0, 0.25)
    if args.to is None:
        loc = fig.location
        goal = loc[[0, 2], 3] + 5.0 * loc[[0, 2], 2] / max(float(np.hypot(*loc[[0, 2], 2])), 1e-12)
    else:
        goal = np.array(args.to)
    if args.gait == "pronk":
        from jackpy.locomotion.pronk import pronk

        result = pronk(fig, terrain, goal, seconds=args.seconds, config=PronkConfig(fps=args.fps))
    else:
        from jackpy.locomotion.creature_walk import walk

        result = walk(fig, terrain, goal, seconds=args.seconds, config=WalkConfig(gait=args.gait, fps=args.fps))
    motion_file.save(result.to_motion_file(), args.output)
    if args.events:
        result.events.save_csv(args.events)
    end = result.body_xz(-1)
    print(f"{fig.name}: {len(result.postures)} frames, {len(result.legs)} legs, ended at "
          f"({end[0]:.3f}, {end[1]:.3f}) m, {float(np.hypot(*(end - goal))):.3f} m from the goal -> {args.output}",
          file=sys.stderr)
    return 0


def run_new(args: argparse.Namespace) -> int:
    from jackpy.locomotion.creature_editor import Drawing, analyse, build, save_figure

    drawing = Drawing.load(args.drawing)
    if args.style:
        drawing.style = args.style
    fig = build(drawing)
    save_figure(fig, args.output)
    an = analyse(drawing)
    print(f"{fig.name}: {len(an.legs)} legs, {len(an.of('head'))} head, {len(an.of('tail'))} tail, "
          f"{len(fig.joints)} joints, {fig.ndof} DOFs ({drawing.style}) -> {args.output}", file=sys.stderr)
    return 0
