"""``jackpy analyze``: run the workplace analyses headless for several figure sizes and write a report."""

from __future__ import annotations

import argparse


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("analyze", help="reach, view, strength and clearance of a workplace scene; "
                                       "writes report.html, results.json and results.csv")
    p.add_argument("scene", metavar="SCENE", help="workplace scene file (JSON, see docs/analysis.md)")
    p.add_argument("--figures", default="female:5,male:95",
                   help="figure sizes as SEX:PERCENTILE, comma separated (default: female:5,male:95)")
    p.add_argument("--reach", default=None, help="reach targets object.site, comma separated (default: the scene's)")
    p.add_argument("--view", default=None, help="view targets object or object.site, comma separated (default: the scene's)")
    p.add_argument("--load", type=float, default=None, metavar="KG", help="load held in the hand, kg (default: the scene's)")
    p.add_argument("--hand", choices=("right", "left"), default=None, help="reaching hand (default: the scene's)")
    p.add_argument("--reach-mode", choices=("arm", "body", "step"), default="arm",
                   help="point reach with the arm only (default), the whole body with the feet planted "
                        "(bends and shifts its weight, balanced), or the whole body allowed to step")
    p.add_argument("--contact-tolerance", type=float, default=10.0, metavar="MM",
                   help="a target counts as reached only with no body segment deeper than this into any "
                        "object (mm, default 10: touching a surface is allowed, passing through it is not)")
    p.add_argument("--resolution", type=int, default=48, help="workspace voxels per axis (default 48)")
    p.add_argument("--ergonomics", default=None, metavar="M[,M...]",
                   help="ergonomic assessments of the strength posture: rula, reba, owas, niosh, lowback, capable "
                        "(comma separated, or all); a report section per method")
    p.add_argument("--ergo-task", default=None, metavar="TASK.json",
                   help="ergonomic task parameters (docs/ergonomics.md; default: the load in the hands)")
    p.add_argument("--no-pictures", action="store_true", help="skip rendering (and visibility, which renders)")
    p.add_argument("-o", "--output", required=True, metavar="DIR", help="folder for the report")
    p.set_defaults(func=run)


def _list(text: str | None, default: list[str]) -> list[str]:
    return default if text is None else [s.strip() for s in text.split(",") if s.strip()]


def run(args: argparse.Namespace) -> int:
    from jackpy.analysis.report import Options, parse_figures, write_report
    from jackpy.errors import JackpyError
    from jackpy.scene.workplace import load_workplace, resolve_target

    wp = load_workplace(args.scene)
    opts = Options(parse_figures(args.figures), _list(args.reach, wp.plan.reach), _list(args.view, wp.plan.view),
                   wp.plan.load_kg if args.load is None else args.load, args.hand or wp.plan.hand, args.resolution,
                   args.reach_mode)
    if opts.load_kg < 0 or opts.resolution < 4 or args.contact_tolerance < 0:
        raise JackpyError("--load and --contact-tolerance must be >= 0 and --resolution >= 4")
    opts.contact_tolerance = args.contact_tolerance / 1000.0
    if args.ergonomics is not None:  # bad methods or task parameters fail before any work
        from jackpy.ergonomics import parse_methods
        from jackpy.ergonomics.inputs import load_task

        opts.ergonomics = parse_methods(args.ergonomics)
        opts.ergo_task = load_task(args.ergo_task, None if args.ergo_task else opts.load_kg)
        if "niosh" in opts.ergonomics and not opts.ergo_task.lifts:
            raise JackpyError("--ergonomics niosh needs a lifting task: give --ergo-task with \"lifts\"")
    for ref in opts.reach + opts.view:
        resolve_target(wp.env, ref)  # unknown names fail before any work
    results = write_report(wp, opts, args.output, render=not args.no_pictures)
    for r in results["figures"]:
        reached = sum(v["reached"] for v in r["reach"].values())
        seen = ", ".join(f"{k} {100 * v['visible_fraction']:.0f}%" for k, v in r["view"].items()) or "-"
        steps = sum(v["steps"] for v in r["reach"].values())
        stepped = f" ({steps} step{'s' if steps != 1 else ''})" if opts.reach_mode == "step" else ""
        print(f"{r['sex']} {r['percentile']:g}%: reach {reached}/{len(r['reach'])}{stepped}, view {seen}")
    print(f"report: {args.output}/report.html")
    return 0
