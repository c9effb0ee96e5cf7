"""``jackpy bench``: run the benchmark cases and print a table (or JSON lines)."""

from __future__ import annotations

import argparse

from jackpy.errors import JackpyError


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("bench", help="run the benchmarks: medians, p90 and ratios against baselines")
    p.add_argument("--only", metavar="NAME", action="append", default=None,
                   help="run only cases whose name starts with NAME (repeatable)")
    p.add_argument("--json", action="store_true", help="one JSON object per case")
    p.add_argument("--quick", action="store_true", help="fewer repetitions (a smoke run)")
    p.add_argument("--list", action="store_true", help="list the cases and exit")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from jackpy.bench.runner import all_cases, format_row, header, print_json

    cases = all_cases()
    if args.list:
        for c in cases:
            print(f"{c.name:<22}{c.description}")
        return 0
    if args.only:
        cases = [c for c in cases if any(c.name.startswith(o) for o in args.only)]
        if not cases:
            raise JackpyError(f"no benchmark case matches {', '.join(args.only)}")
    from jackpy import compiled

    warmed = compiled.warm(compiled.announce_on_stderr)  # no case times a kernel's compilation or loading
    if not args.json:
        print(f"# numba kernels: {warmed}", flush=True)
        print(header(), flush=True)
    for case in cases:
        result = case.run(args.quick)
        if args.json:
            print_json(result)
        else:
            print(format_row(result), flush=True)
    return 0
