"""``jackpy walk SCENE --to X,Z | --to-object NAME[.SITE] | --path "x,z x,z ..." [--facing DEG]``:
a standard human walks from where the scene stands it (or ``--from``), written as a motion file
(the walk as a timeline motion, plus its baked frames; optionally BVH). ``--to`` and
``--to-object`` plan around the scene's objects (an object: stand in front of it, facing it),
``--path`` follows the points as given. See docs/walking.md."""

from __future__ import annotations

import argparse

import numpy as np


def _point(text: str) -> tuple[float, float]:
    parts = text.split(",")
    if len(parts) != 2:
        raise argparse.ArgumentTypeError(f"expected X,Z in metres, not {text!r}")
    try:
        x, z = (float(v) for v in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected X,Z in metres, not {text!r}") from None
    if not (np.isfinite(x) and np.isfinite(z)):
        raise argparse.ArgumentTypeError(f"X,Z must be finite, not {text!r}")
    return x, z


def _path(text: str) -> list[tuple[float, float]]:
    pts = [_point(t) for t in text.split()]
    if not pts:
        raise argparse.ArgumentTypeError("the path needs at least one point x,z")
    return pts


def _fps(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, not {text!r}") from None
    if not 0 < v <= 240:
        raise argparse.ArgumentTypeError(f"fps must be in (0, 240], not {text}")
    return v


def register(subparsers) -> None:
    p = subparsers.add_parser("walk", help="walk a standard human to a point or along a path (baked motion)")
    p.add_argument("scene", metavar="SCENE", help="workplace scene (JSON; the figure starts at its stand), or -")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--to", type=_point, metavar="X,Z", help="walk to this floor point (m)")
    g.add_argument("--to-object", dest="to_object", default=None, metavar="NAME[.SITE]",
                   help="walk to stand in front of this scene object (or beside its site), facing it")
    g.add_argument("--shuffle", type=_point, default=None, metavar="RIGHT,FORWARD",
                   help="short steps keeping the heading: this far to the figure's right and forward "
                        "(m; negative: left, backwards; at most 1.5 m)")
    g.add_argument("--path", type=_path, metavar='"x,z x,z ..."', help="walk through these floor points (m)")
    p.add_argument("--facing", type=float, default=None, metavar="DEG",
                   help="heading at the end (degrees about +y, 0 faces +z; default: along the path)")
    p.add_argument("--steer", action="store_true",
                   help="with --to: steer toward the point step by step (45° at most per step, the "
                        "incremental walker) instead of planning round the objects")
    p.add_argument("--from", dest="start", type=_point, default=None, metavar="X,Z",
                   help="start here (m; default: the scene's stand)")
    p.add_argument("--figure", default="male:50", metavar="NAME", help="standard human (male:50, female:5, ...)")
    p.add_argument("--name", default="walker", help="the figure's name in the motion file (default walker)")
    p.add_argument("--fps", type=_fps, default=30.0, help="frame rate of the baked motion (default 30)")
    p.add_argument("-o", "--output", required=True, metavar="OUT.motion.json")
    p.add_argument("--bvh", default=None, metavar="OUT.bvh", help="also write the walk as BVH")
    p.set_defaults(func=run)


def run(args) -> int:
    from jackpy.commands.motion import Progress
    from jackpy.locomotion import footsteps, walk_path, walk_solve
    from jackpy.locomotion.walk_gait import GaitParams
    from jackpy.locomotion.walk_to import WalkError
    from jackpy.motion import cast, motion_file

    stand = (0.0, 0.0, 0.0)
    if args.scene != "-":
        from jackpy.scene.workplace import load_workplace

        wp = load_workplace(args.scene)
        stand = (float(wp.stand.position[0]), float(wp.stand.position[1]), float(wp.stand.heading))
    objects = list(wp.objects.values()) if args.scene != "-" else []
    if args.start is not None:
        stand = (args.start[0], args.start[1], stand[2])
    fig = cast.make_figure(args.name, {"human": args.figure, "position": list(stand[:2]),
                                      "heading_deg": float(np.degrees(stand[2]))})
    p = GaitParams.for_figure(fig)
    facing = None if args.facing is None else float(np.radians(args.facing))
    if args.steer and args.to is None:
        raise WalkError("--steer goes with --to X,Z")
    if args.shuffle is not None:
        try:
            steps = footsteps.shuffle(p, stand[0], stand[1], stand[2], args.shuffle[0], args.shuffle[1])
        except ValueError as exc:
            raise WalkError(str(exc)) from None
    elif args.steer:
        from jackpy.locomotion.stepper import Approach, Stepper

        steps = Stepper(p, footsteps.standing(p, *stand), Approach(args.to, facing=facing)).run()
    elif args.to is not None or args.to_object is not None:
        from jackpy.locomotion.walk_target import plan

        steps, _, _ = plan(fig, p, args.to if args.to is not None else args.to_object, objects, facing=facing,
                           start=stand[:2])
    else:
        pts = [tuple(stand[:2])] + list(args.path)
        steps = footsteps.from_path(p, np.array(pts), facing=facing)
    walk = walk_path.Walk(steps, p)
    mf = walk_solve.motion_file(fig, walk, args.fps, args.figure, Progress("walking"))
    motion_file.save(mf, args.output)
    if args.bvh:
        from jackpy.motion.bvh_export import write_bvh

        write_bvh(fig, mf.baked[fig.name], args.fps, args.bvh)
    print(f"{len(steps) - 2} steps, {mf.duration:.2f} s, {mf.n_frames} frames -> {args.output}")
    return 0
