"""``jackpy motion bake|import-bvh|export``: bake a timeline onto a scene's figures, import BVH
motion capture onto a standard human, export baked motion as BVH, glTF (.glb) or CSV.
See docs/motion.md."""

from __future__ import annotations

import argparse
import sys
import time

from jackpy.errors import ParseError


def positive(text: str) -> float:
    """An argparse type: a number > 0."""
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, not {text!r}") from None
    if not v > 0 or v != v or v == float("inf"):
        raise argparse.ArgumentTypeError(f"must be > 0, not {text}")
    return v


class Progress:
    """A one-line progress bar on stderr, shown once a job has run for more than ``after_s``."""

    def __init__(self, label: str, after_s: float = 1.0, stream=None) -> None:
        self.label, self.after_s = label, after_s
        self.stream = stream or sys.stderr
        self.t0 = time.perf_counter()
        self.shown = False

    def __call__(self, done: int, total: int) -> None:
        elapsed = time.perf_counter() - self.t0
        if elapsed < self.after_s and done < total:
            return
        if not self.shown and done >= total and elapsed < self.after_s:
            return
        self.shown = True
        width = 30
        filled = int(width * done / max(total, 1))
        rate = done / elapsed if elapsed > 0 else 0.0
        end = "\n" if done >= total else ""
        self.stream.write(f"\r{self.label} [{'#' * filled}{'.' * (width - filled)}] {done}/{total} frames "
                          f"{rate:.1f}/s{end}")
        self.stream.flush()


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("motion", help="bake motions, import BVH motion capture, export BVH/glTF/CSV")
    msub = p.add_subparsers(dest="motion_command", required=True, metavar="COMMAND")

    b = msub.add_parser("bake", help="bake a motion file's timeline onto a scene's figures")
    b.add_argument("scene", metavar="SCENE", help="workplace scene (JSON), or - for an empty floor")
    b.add_argument("motion", metavar="MOTION", help="motion file (NAME.motion.json)")
    b.add_argument("-o", "--output", required=True, metavar="OUT.motion.json", help="motion file with baked frames")
    b.add_argument("--fps", type=positive, default=30.0, help="frames per second (default 30)")
    b.set_defaults(func=run_bake)

    i = msub.add_parser("import-bvh", help="retarget a BVH motion capture onto a standard human")
    i.add_argument("bvh", metavar="FILE.bvh")
    i.add_argument("--figure", default="male:50", metavar="male:50|female:5",
                   help="the human to drive (default male:50)")
    i.add_argument("--map", default=None, metavar="MAP.json", help="joint-name map file (see docs/motion.md)")
    i.add_argument("--fps", type=positive, default=None, help="resample to this rate (default: the file's)")
    i.add_argument("-o", "--output", required=True, metavar="OUT.motion.json")
    i.set_defaults(func=run_import)

    e = msub.add_parser("export", help="export a baked motion as BVH, glTF binary (.glb) or CSV")
    e.add_argument("motion", metavar="MOTION", help="motion file (baked, or baked now at --fps)")
    e.add_argument("--scene", default=None, metavar="SCENE", help="scene to bake in when the file is not baked")
    e.add_argument("--figure", default=None, metavar="NAME", help="figure to export (default: the first)")
    e.add_argument("--fps", type=positive, default=30.0, help="bake rate when the file is not baked (default 30)")
    e.add_argument("-o", "--output", required=True, metavar="OUT.bvh|OUT.glb|OUT.csv")
    e.set_defaults(func=run_export)


def bake_motion_file(mf, scene: str | None, fps: float, progress=None):
    """Bake ``mf``'s timeline in ``scene`` at ``fps``; returns (motion file with frames, env, loops)."""
    from jackpy.motion import cast
    from jackpy.motion.bake import Baker
    from jackpy.motion.motion_file import BakedFigure, MotionFile

    env, loops = cast.build(mf.timeline, None if scene in (None, "-") else scene)
    if not loops:
        raise ParseError("the motion drives no figure (no motions, key tracks or figures)", "timeline")
    baker = Baker(mf.timeline, loops, env, fps)
    frames = baker.bake(progress)
    baked = {}
    for name, loop in baker.loops.items():
        human = mf.timeline.cast.get(name, {}).get("human", cast.DEFAULT_HUMAN)
        baked[name] = BakedFigure.from_postures(loop.figure, [f[name] for f in frames], human)
    return MotionFile(mf.timeline, fps, baked), env, baker.loops


def run_bake(args: argparse.Namespace) -> int:
    from jackpy.motion import motion_file

    mf = motion_file.load(args.motion)
    out, _, _ = bake_motion_file(mf, args.scene, args.fps, Progress("baking"))
    motion_file.save(out, args.output)
    print(f"{args.output}: {out.n_frames} frames at {args.fps:g} fps of {', '.join(out.baked)}")
    return 0


def run_import(args: argparse.Namespace) -> int:
    from jackpy.motion import motion_file
    from jackpy.motion.retarget import import_bvh

    mf = import_bvh(args.bvh, args.figure, map_file=args.map, fps=args.fps, progress=Progress("importing"))
    motion_file.save(mf, args.output)
    name = next(iter(mf.baked))
    print(f"{args.output}: {mf.n_frames} frames at {mf.fps:g} fps on {name}")
    return 0


def run_export(args: argparse.Namespace) -> int:
    from pathlib import Path

    from jackpy.motion import cast, motion_file

    mf = motion_file.load(args.motion)
    if not mf.baked:
        mf, _, _ = bake_motion_file(mf, args.scene, args.fps, Progress("baking"))
    name = args.figure or next(iter(mf.baked))
    if name not in mf.baked:
        raise ParseError(f"no baked figure {name!r} (figures: {', '.join(mf.baked)})", args.motion)
    baked = mf.baked[name]
    fig = cast.make_figure(name, {"human": baked.human or cast.DEFAULT_HUMAN})
    suffix = Path(args.output).suffix.lower()
    if suffix == ".bvh":
        from jackpy.motion.bvh_export import write_bvh

        write_bvh(fig, baked, mf.fps, args.output)
    elif suffix == ".glb":
        from jackpy.motion.gltf_export import write_glb

        write_glb(fig, baked, mf.fps, args.output)
    elif suffix == ".csv":
        from jackpy.motion.csv_export import write_csv

        write_csv(fig, baked, mf.fps, args.output)
    else:
        raise ParseError(f"export as .bvh, .glb or .csv, not {suffix or 'no extension'!r}", args.output)
    print(f"{args.output}: {baked.n_frames} frames of {name}")
    return 0
