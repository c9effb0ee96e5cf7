"""``jackpy reach``: one collision-aware reach in a workplace scene, optionally by staged posture
planning (arm, torso, knees, step) and with a planned collision-free reach motion (``--plan``, OMPL);
writes ``reach.json`` with the verdict, the stage, every attempt and the motion's summary, and
``reach.motion.json`` (baked frames) with ``--plan`` (docs/planning.md)."""

from __future__ import annotations

import argparse

from jackpy.commands.motion import positive


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("reach", help="collision-aware reach of a workplace target (verdict, staged posture "
                                     "planning); writes reach.json")
    p.add_argument("scene", metavar="SCENE", help="workplace scene file (JSON, see docs/analysis.md)")
    p.add_argument("--figure", default="female:5", help="figure size SEX:PERCENTILE (default female:5)")
    p.add_argument("--target", required=True, help="reach target object.site")
    p.add_argument("--hand", choices=("right", "left"), default=None, help="reaching hand (default: the scene's)")
    p.add_argument("--stages", action="store_true",
                   help="staged posture planning: arm, then torso, then knees bent, then a step, each only "
                        "when the one before fails (default: the arm only)")
    p.add_argument("--plan", action="store_true",
                   help="plan a collision-free reach motion of the arm (OMPL RRT-Connect, needs the planning "
                        "extra) from the standing posture to the target; writes reach.motion.json")
    p.add_argument("--seed", type=int, default=0, help="seed of the motion planner (default 0: repeatable)")
    p.add_argument("--time-limit", type=positive, default=120.0, metavar="S",
                   help="longest planner run (s, default 120; a run that finds no path in it reports 'no path')")
    p.add_argument("--fps", type=positive, default=30.0, help="frame rate of reach.motion.json (default 30)")
    p.add_argument("--contact-tolerance", type=float, default=10.0, metavar="MM",
                   help="deepest allowed contact of a body segment with an object (mm, default 10)")
    p.add_argument("-o", "--output", required=True, metavar="DIR",
                   help="folder for reach.json (and reach.motion.json with --plan)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from jackpy.analysis.report import _human, parse_figures
    from jackpy.atomic import atomic_write_text
    from jackpy.errors import JackpyError
    import json
    from jackpy.planning.stages import STAGE_TEXT, STAGES, staged_reach
    from jackpy.scene.workplace import load_workplace, resolve_target, stand_figure

    wp = load_workplace(args.scene)
    figures = parse_figures(args.figure)
    if len(figures) != 1:
        raise JackpyError(f"--figure takes one SEX:PERCENTILE, not {args.figure!r}")
    if args.contact_tolerance < 0:
        raise JackpyError("--contact-tolerance must be >= 0")
    obj, target = resolve_target(wp.env, args.target)
    figure = _human(*figures[0])
    stand_figure(figure, wp.stand)
    hand = args.hand or wp.plan.hand
    s = staged_reach(figure, target, hand, list(wp.objects.values()), obj.name,
                     stages=STAGES if args.stages else ("arm",), contact_tolerance=args.contact_tolerance / 1000.0)
    attempts = [{"stage": st, "reached": r.reached, "shortfall_m": r.shortfall, "text": r.describe(),
                 "com_margin_m": r.com_margin, "steps": r.steps,
                 **(r.verdict.to_dict() if r.verdict is not None else {})} for st, r in s.attempts]
    out = {"scene": str(args.scene), "figure": figure.name, "target": args.target, "target_position": target.tolist(),
           "hand": hand, "stage": s.stage, "text": s.describe(), "reached": s.result.reached,
           "shortfall_m": s.result.shortfall, "attempts": attempts}
    out["stages"] = [{"stage": st, "text": STAGE_TEXT[st], "reached": r.reached} for st, r in s.attempts]
    Path(args.output).mkdir(parents=True, exist_ok=True)
    motion = None
    if args.plan:
        from jackpy.motion import motion_file
        from jackpy.planning.reach_motion import plan_reach_motion

        motion = plan_reach_motion(figure, target, hand, list(wp.objects.values()), obj.name,
                                   contact_tolerance=args.contact_tolerance / 1000.0, seed=args.seed,
                                   time_limit=args.time_limit)
        out["motion"] = motion.to_dict()
        if motion.planned:
            motion_file.save(motion.motion_file(args.fps, human=args.figure), Path(args.output) / "reach.motion.json")
    note = _write_picture(wp.env, figure, s.result.posture, target, Path(args.output) / "reach.png")
    out["picture"] = "reach.png" if note is None else None
    atomic_write_text(Path(args.output) / "reach.json", json.dumps(out, indent=1) + "\n")
    print(f"{args.figure} {args.target}: {s.describe()}")
    if note is not None:
        print(f"  no picture: {note}")
    if motion is not None:
        print(f"  {motion.describe()}")
    return 0


def _write_picture(env, figure, posture, target, path) -> str | None:
    """The final posture's picture at ``path``; the reason when there is none (no offscreen GL)."""
    from jackpy.atomic import atomic_write_bytes
    from jackpy.errors import JackpyError
    from jackpy.planning.stage_picture import posture_picture

    try:
        atomic_write_bytes(path, posture_picture(env, figure, posture, target))
    except JackpyError as exc:
        return str(exc)
    return None
