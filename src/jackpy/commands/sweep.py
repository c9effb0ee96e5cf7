"""``jackpy sweep``: run a study over a Monte Carlo population or a manikin family, on a local
process pool or a Dask cluster; writes the per-body table, the accommodation table and a report."""

from __future__ import annotations

import argparse
import sys


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("sweep", help="population accommodation: run a study (reach, view, clearance, strength, "
                                     "ergonomics) over many bodies; see docs/population.md")
    p.add_argument("scene", metavar="SCENE", help="workplace scene file (JSON)")
    p.add_argument("--study", required=True, metavar="STUDY.json", help="the criteria (docs/population.md)")
    who = p.add_mutually_exclusive_group()
    who.add_argument("--n", type=int, default=None, help="Monte Carlo bodies (default 2000)")
    who.add_argument("--family", default=None, metavar="SHARE",
                     help="a manikin family holding SHARE of each sex, e.g. 90%% (boundary and centre cases)")
    p.add_argument("--family-dims", default="stature,weight",
                   help="family dimensions, comma separated (default stature,weight; 3 or more: PCA)")
    p.add_argument("--components", type=int, default=None, help="principal components of a PCA family (default 3)")
    p.add_argument("--sex-mix", type=float, default=0.5, help="share of women, 0..1 (default 0.5)")
    p.add_argument("--seed", type=int, default=0, help="Monte Carlo seed (default 0)")
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: every core)")
    p.add_argument("--scheduler", default=None, metavar="ADDR", help="Dask scheduler, e.g. tcp://HOST:8786")
    p.add_argument("--resume", action="store_true", help="finish the interrupted sweep in OUT")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("-o", "--output", required=True, metavar="OUT", help="output folder")
    p.set_defaults(func=run)


def parse_share(text: str) -> float:
    """``90%`` or ``0.9`` -> 0.9."""
    from jackpy.errors import JackpyError

    t = text.strip()
    try:
        v = float(t[:-1]) / 100.0 if t.endswith("%") else float(t)
    except ValueError:
        raise JackpyError(f"bad --family {text!r}: write a share such as 90% or 0.9") from None
    if not 0.0 < v < 1.0:
        raise JackpyError(f"bad --family {text!r}: the share must be between 0 and 100 % (exclusive)")
    return v


def run(args: argparse.Namespace) -> int:
    from jackpy.errors import JackpyError
    from jackpy.population.run import population_bodies, sweep
    from jackpy.population.study import check_against_scene, load_study
    from jackpy.scene.workplace import load_workplace

    if not 0.0 <= args.sex_mix <= 1.0:
        raise JackpyError(f"--sex-mix must be between 0 and 1, not {args.sex_mix}")
    if args.n is not None and args.n < 1:
        raise JackpyError(f"--n must be at least 1, not {args.n}")
    if args.workers is not None and args.workers < 0:
        raise JackpyError(f"--workers must be 0 or more, not {args.workers}")
    wp, study = load_workplace(args.scene), load_study(args.study)
    check_against_scene(study, wp.env)  # bad names fail before any work
    client = _connect(args.scheduler) if args.scheduler else None  # so does an unreachable scheduler
    bodies = None
    description: dict = {}
    if not args.resume:
        dims = [d.strip() for d in args.family_dims.split(",") if d.strip()]
        share = parse_share(args.family) if args.family is not None else None
        bodies = population_bodies(args.n, share, args.sex_mix, args.seed, dims, args.components)
        description = {"population": {"n": len(bodies), "family": share, "family_dims": dims if share else None,
                                      "sex_mix": args.sex_mix, "seed": args.seed}}
    try:
        result, table = sweep(wp, study, bodies, args.output, workers=args.workers, client=client,
                              resume=args.resume, progress=not args.no_progress, description=description)
    except KeyboardInterrupt:
        from jackpy.population.evaluate import columns
        from jackpy.population.journal import Journal

        kept = len(Journal(args.output).finished(columns(study)))
        print(f"\njackpy: interrupted: {kept} finished rows kept in {args.output}; finish with --resume",
              file=sys.stderr)
        return 130
    finally:
        if client is not None:
            client.close()
    for a in table:
        binding = f", binding {a.binding_dimension} ({a.fails_when} fail)" if a.binding_dimension else ""
        print(f"{a.criterion}: {100 * a.share:.1f} % ({a.passed}/{a.bodies}){binding}")
    print(f"{result.evaluated} bodies in {result.seconds:.1f} s; report: {args.output}/report.html")
    return 0


def _connect(address: str):
    """A Dask client of the scheduler at ``address`` (one-line error when it cannot be reached)."""
    from jackpy.population.journal import SweepError

    try:
        from dask.distributed import Client
    except ImportError:
        raise SweepError("Dask is not installed: pip install 'jackpy[cluster]' (dask distributed)") from None
    try:
        return Client(address, timeout="10s")
    except (OSError, TimeoutError, ValueError) as exc:
        raise SweepError(f"cannot reach the Dask scheduler at {address}: {exc}") from None
