"""``jackpy ergo``: ergonomic assessments (RULA, REBA, OWAS, NIOSH, low back, percent capable) of a
posed figure in a session, or of every baked frame of a motion."""

from __future__ import annotations

import argparse


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("ergo", help="ergonomic assessments (RULA, REBA, OWAS, NIOSH lifting, L5/S1 low back, "
                                    "percent capable) of a posed figure or of every frame of a motion")
    p.add_argument("scene", metavar="SCENE", help="a session (.env, the figures as posed), a workplace scene "
                                                  "(.json: a standard human standing where it says) or - (a "
                                                  "standard human on an empty floor)")
    p.add_argument("--figure", default=None, metavar="NAME", help="the figure to assess (default: the only human)")
    p.add_argument("--human", default=None, metavar="SEX:PCT",
                   help="size of the standard human for a workplace scene or - (default: the motion's, else male:50)")
    p.add_argument("--method", default="rula,reba", metavar="M[,M...]",
                   help="rula, reba, owas, niosh, lowback, capable, comma separated, or all (default rula,reba)")
    p.add_argument("--task", default=None, metavar="TASK.json", help="task parameters (docs/ergonomics.md)")
    p.add_argument("--load", type=float, default=None, metavar="KG", help="load in the hands, kg (overrides the task's)")
    p.add_argument("--motion", default=None, metavar="MOTION.json",
                   help="assess every baked frame of this motion file (a table, or with -o a CSV and SVG plots)")
    p.add_argument("--json", action="store_true", help="print JSON instead of text")
    p.add_argument("-o", "--output", default=None, metavar="DIR",
                   help="with --motion: write frames.csv, frames.json and one <method>.svg plot per method here")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import json
    from pathlib import Path

    from jackpy.ergonomics import parse_methods
    from jackpy.ergonomics.frames import frames_table, per_frame, write_frames
    from jackpy.ergonomics.inputs import figure_from_scene, load_task
    from jackpy.ergonomics.summary import json_ready, text

    names = parse_methods(args.method)
    task = load_task(args.task, args.load)
    name, human = args.figure, args.human
    if args.motion is not None and not args.scene.endswith(".env"):  # a made human: the motion's figure
        from jackpy.ergonomics.frames import baked_human

        name, human = baked_human(args.motion, name, human)
    figure = figure_from_scene(args.scene, name, human or "male:50")
    if args.motion is None:
        from jackpy.ergonomics import assess

        results = assess(figure, names, task)
        if args.json:
            print(json.dumps(json_ready({"scene": args.scene, "figure": figure.name,
                                         "methods": {n: a.to_dict() for n, a in results.items()}}), indent=1))
        else:
            print(f"{figure.name} in {args.scene}")
            for a in results.values():
                print(text(a))
        return 0
    frames = per_frame(figure, args.motion, names, task)
    if args.output is not None:
        written = write_frames(frames, names, Path(args.output))
        if not args.json:
            print("wrote " + ", ".join(str(p) for p in written))
    if args.json:
        print(json.dumps(json_ready(frames), indent=1))
    elif args.output is None:
        print(frames_table(frames, names))
    return 0
