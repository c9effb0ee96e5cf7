"""``jackpy convert IN OUT``: Peabody ``.fig``/``.env`` to ``.glb``/``.obj``/``.stl``/``.ply`` (posed
geometry, metres) or to ``.fig``/``.env`` (Peabody text)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from jackpy.errors import JackpyError
from jackpy.peabody.model import Environment

#: the standard human's driver kinds and the modules that register them (imported only when a
#: file names them: see jackpy.peabody.groups.DRIVER_MODULES)
BODY_DRIVERS = {"spine": "jackpy.body.spine", "shoulder": "jackpy.body.shoulder"}


def add_path_options(p: argparse.ArgumentParser) -> None:
    """``--allow-outside`` and ``--library``, shared by the commands that read Peabody files."""
    p.add_argument("--allow-outside", action="store_true",
                   help="read include/psurf files outside the scene's folder and the library path (reported)")
    p.add_argument("--library", action="append", default=[], metavar="DIR",
                   help="a folder referenced files may also come from (repeatable; also JACKPY_LIBRARY)")


def load_scene(path: str, args: argparse.Namespace, *, require_geometry: bool) -> Environment:
    """Read a ``.fig``/``.env`` as the options say; files read from outside are noted on stderr."""
    from jackpy.peabody.groups import DRIVER_MODULES
    from jackpy.peabody.reader import load

    for kind, module in BODY_DRIVERS.items():
        DRIVER_MODULES.setdefault(kind, module)
    env = load(path, require_geometry=require_geometry, allow_outside=args.allow_outside or None,
               library=args.library)
    for p in env.outside:
        print(f"jackpy: note: read {p}, outside the scene's folder (--allow-outside)", file=sys.stderr)
    return env


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("convert", help="convert a .fig/.env file to .glb/.obj/.stl/.ply geometry or .fig/.env text")
    p.add_argument("input", metavar="IN", help="a Peabody .fig or .env file")
    p.add_argument("output", metavar="OUT", help="the file to write (.glb, .obj, .stl, .ply, .fig or .env)")
    add_path_options(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from jackpy.peabody.export import SCENE_FORMATS, export_scene
    from jackpy.peabody.writer import write_environment, write_figures

    out_ext = Path(args.output).suffix.lower()
    if out_ext not in (*SCENE_FORMATS, ".fig", ".env"):
        raise JackpyError(f"{args.output}: cannot convert to {out_ext!r} "
                          f"(use {', '.join(SCENE_FORMATS)}, .fig or .env)")
    text_out = out_ext in (".fig", ".env")
    env = load_scene(args.input, args, require_geometry=not text_out)
    source_dir = Path(args.input).parent
    if out_ext == ".fig":
        write_figures(args.output, env.figures.values(), source_dir=source_dir)
    elif out_ext == ".env":
        write_environment(args.output, env, source_dir=source_dir)
    else:
        export_scene(args.output, env)
    print(f"wrote {args.output} ({len(env.figures)} figure{'s' if len(env.figures) != 1 else ''})")
    return 0
