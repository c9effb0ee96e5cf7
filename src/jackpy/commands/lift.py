"""``jackpy lift [SCENE] --load KG [--goal X Y Z | --to OBJ.SITE] [--start X Y Z | --from OBJ.SITE]
[--comfort CL] [--exertion PE] -o OUT/``: strength-guided lifting (book §5.3) by a standard human
standing at the scene's stand (without a scene: at the origin facing +z); writes
``lift.json`` (summary and per-step series), ``lift.png`` (hand paths of the load and the
``--compare`` loads, torque ratios, energy) and ``lift.motion.json`` (the baked lift).
Exit status 0 when the load reached the goal, 1 when the lift stopped short. See docs/lifting.md."""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path

import numpy as np

_MASS = re.compile(r"^\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(kg|lb)?\s*$")
#: pounds to kilograms
LB = 0.45359237


def _mass(text: str) -> float:
    m = _MASS.match(text)
    if not m:
        raise argparse.ArgumentTypeError(f"expected a mass such as 10, 10kg or 22lb, not {text!r}")
    kg = float(m.group(1)) * (LB if m.group(2) == "lb" else 1.0)
    if not np.isfinite(kg) or kg > 500.0:
        raise argparse.ArgumentTypeError(f"load must be a finite mass up to 500 kg, not {text!r}")
    return kg


def _fraction(lo_open: bool):
    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number, not {text!r}") from None
        if not ((0.0 < v) if lo_open else (0.0 <= v)) or not v <= 1.0:
            raise argparse.ArgumentTypeError(f"expected a value in {'(0' if lo_open else '[0'}, 1], not {text}")
        return v
    return parse


def _coordinate(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a coordinate in metres, not {text!r}") from None
    if not np.isfinite(v):
        raise argparse.ArgumentTypeError(f"coordinate must be finite, not {text!r}")
    return v


def _fps(text: str) -> float:
    v = _coordinate(text)
    if not 0 < v <= 240:
        raise argparse.ArgumentTypeError(f"fps must be in (0, 240], not {text}")
    return v


def _site(env, ref: str) -> np.ndarray:
    from jackpy.scene.workplace import resolve_target

    return np.asarray(resolve_target(env, ref)[1], dtype=float)


def register(subparsers) -> None:
    p = subparsers.add_parser("lift", help="strength-guided lifting of a load to a goal (book 5.3)")
    p.add_argument("scene", metavar="SCENE", nargs="?", default=None,
                   help="workplace scene (JSON): the figure stands at its stand; --from/--to name its sites")
    p.add_argument("--load", type=_mass, required=True, metavar="KG", help="mass held in the hand: 10, 10kg or 22lb")
    goal = p.add_mutually_exclusive_group()
    goal.add_argument("--goal", type=_coordinate, nargs=3, metavar=("X", "Y", "Z"), default=None,
                      help="where the load goes (world m, y up; default: above the head, 30 cm in front)")
    goal.add_argument("--to", dest="to_site", metavar="OBJ.SITE", default=None,
                      help="where the load goes: a site of the scene (object.site or object)")
    start = p.add_mutually_exclusive_group()
    start.add_argument("--start", type=_coordinate, nargs=3, metavar=("X", "Y", "Z"), default=None,
                       help="where the hand holds the load first (world m; default: in front of the chest)")
    start.add_argument("--from", dest="from_site", metavar="OBJ.SITE", default=None,
                       help="where the hand holds the load first: a site of the scene")
    p.add_argument("--comfort", type=_fraction(True), default=0.5, metavar="CL",
                   help="largest torque / strength ratio the lifter accepts, (0, 1] (default 0.5)")
    p.add_argument("--exertion", type=_fraction(False), default=0.3, metavar="PE",
                   help="perceived exertion: path deviation cone of PE x 90 degrees, [0, 1] (default 0.3)")
    p.add_argument("--figure", default="male:50", metavar="NAME", help="standard human (male:50, female:5, ...)")
    p.add_argument("--hand", choices=("right", "left"), default="right")
    p.add_argument("--no-waist", action="store_true", help="keep the waist out of the chain (no added joint)")
    p.add_argument("--compare", type=_mass, nargs="*", default=None, metavar="KG",
                   help="other loads to plot beside it (default: 1/3 and 2/3 of --load)")
    p.add_argument("--fps", type=_fps, default=30.0, help="frame rate of the baked motion (default 30)")
    p.add_argument("-o", "--output", required=True, metavar="OUT/",
                   help="folder for lift.json, lift.png, lift.motion.json")
    p.set_defaults(func=run)


def run(args) -> int:
    from jackpy.atomic import atomic_write_bytes, atomic_write_text
    from jackpy.errors import SessionError
    from jackpy.motion import cast, motion_file
    from jackpy.planning.lifting import DEFAULT_GOAL, DEFAULT_START, LiftTask, figure_offset, strength_guided_lift
    from jackpy.planning.lifting_motion import lift_motion
    from jackpy.planning.lifting_plot import lift_plot_png

    spec = {"human": args.figure}
    env = None
    if args.scene is not None:
        from jackpy.scene.workplace import load_workplace

        wp = load_workplace(args.scene)
        env = wp.env
        spec |= {"position": [float(wp.stand.position[0]), float(wp.stand.position[1])],
                 "heading_deg": float(np.degrees(wp.stand.heading))}
    elif args.to_site or args.from_site:
        raise SessionError("--from and --to name sites of a scene: give the SCENE file first")
    fig = cast.make_figure("lifter", spec)
    goal = (np.array(args.goal) if args.goal is not None else _site(env, args.to_site) if args.to_site
            else figure_offset(fig, DEFAULT_GOAL, args.hand))
    start = (np.array(args.start) if args.start is not None else _site(env, args.from_site) if args.from_site
             else figure_offset(fig, DEFAULT_START, args.hand))
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        raise NotADirectoryError(f"{out}: the output must be a folder")
    out.mkdir(parents=True, exist_ok=True)
    compare = args.compare if args.compare is not None else [args.load / 3.0, 2.0 * args.load / 3.0]
    loads = sorted({round(float(m), 6) for m in compare} - {round(args.load, 6)}) + [args.load]

    def lift(kg: float):
        return strength_guided_lift(fig, LiftTask(kg, goal, start, comfort=args.comfort, exertion=args.exertion,
                                                  hand=args.hand, allow_waist=not args.no_waist))

    results = [lift(kg) for kg in loads]
    main = results[-1]
    summary = main.summary()
    summary["figure"] = args.figure
    summary["compare"] = [{"load_kg": r.task.load_kg, "reached": r.reached, "reason": r.reason,
                           "waist_added_at": r.waist_added_at,
                           "mean_hand_shoulder_horizontal_m": float(r.horizontal_distance().mean()),
                           "peak_discomfort": float(max(f.discomfort for f in r.frames))} for r in results[:-1]]
    atomic_write_text(out / "lift.json", json.dumps(summary, indent=1) + "\n")
    atomic_write_bytes(out / "lift.png", lift_plot_png(fig, results))
    motion_file.save(lift_motion(fig, main, args.fps, args.figure), out / "lift.motion.json")
    how = "reached the goal" if main.reached else f"stopped {summary['final_distance_to_goal_m'] * 100:.1f} cm short"
    waist = "" if main.waist_added_at is None else f", waist added ({summary['waist_motion_deg']:.1f} deg)"
    print(f"{main.task.load_kg:g} kg {how} in {summary['duration_s']:.2f} s; strategies: "
          f"{', '.join(main.strategies_used())}{waist}; peak torque ratio {summary['peak_discomfort']:.2f} -> {out}")
    return 0 if main.reached else 1
