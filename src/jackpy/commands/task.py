"""``jackpy task SCRIPT [--scene SCENE] -o OUT.motion.json [--table OUT.csv]``: run a task script
(the checklist grammar, docs/tasks.md) on a scene, write the resulting timeline as a motion file
and the Fitts timing table. Exit 0 when every command succeeded or its failure had an
``If that fails`` hook, 1 otherwise; 2 for a malformed script or scene."""

from __future__ import annotations

import argparse
import sys


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("task", help="run a task script (look, turn, reach, put ...) into a motion timeline")
    p.add_argument("script", metavar="SCRIPT", help="checklist script (e.g. examples/tasks/panel/panel.task)")
    p.add_argument("--scene", default=None, metavar="SCENE", help="scene file with NAME.semantics.json sidecars")
    p.add_argument("-o", "--output", required=True, metavar="OUT.motion.json")
    p.add_argument("--table", default=None, metavar="OUT.csv", help="write the timing table as CSV")
    p.add_argument("--fps", type=float, default=15.0, help="simulation rate (default 15 frames/s)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from jackpy.atomic import atomic_write_text
    from jackpy.motion import motion_file
    from jackpy.tasks import checklist, fitts

    script = checklist.load(args.script)
    script.fps = args.fps
    result = script.run(args.scene)
    motion_file.save(motion_file.MotionFile(result.timeline), args.output)
    if args.table:
        atomic_write_text(args.table, fitts.table_csv(result.rows))
    unhandled = 0
    entries = {e.name: e for e in script.entries if not isinstance(e, list)}
    for block in script.entries:
        if isinstance(block, list):
            entries.update({e.name: e for e in block})
    for r in result.reports:
        where = f"{r.origin}: " if r.origin else ""
        line = f"{where}{r.actor}: {r.command}: {r.start:.3f}-{r.end:.3f} s {r.status}"
        if r.reason:
            line += f": {r.reason}"
        print(line, file=sys.stdout if r.status == "done" else sys.stderr)
        e = entries.get(r.name)
        if r.status == "failed" and not (e is not None and e.on_failure):
            unhandled += 1
    for name, state in sorted(result.controls.items()):
        print(f"control {name}: {state}")
    print(f"{len(result.rows)} timed steps, {result.timeline.duration:.3f} s; timeline written to {args.output}")
    return 1 if unhandled else 0
