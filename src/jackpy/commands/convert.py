"""``jackpy convert IN OUT``: Peabody ``.fig``/``.env`` to ``.glb``/``.obj``/``.stl``/``.ply`` (posed
geometry, metres) or to ``.fig``/``.env`` (Peabody text)."""

from __future__ import annotations

import argparse
from pathlib import Path

from jackpy.errors import JackpyError


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("convert", help="convert a .fig/.env file to .glb/.obj/.stl/.ply geometry or .fig/.env text")
    p.add_argument("input", metavar="IN", help="a Peabody .fig or .env file")
    p.add_argument("output", metavar="OUT", help="the file to write (.glb, .obj, .stl, .ply, .fig or .env)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from jackpy.peabody.export import SCENE_FORMATS, export_scene
    from jackpy.peabody.reader import load
    from jackpy.peabody.writer import write_environment, write_figures

    out_ext = Path(args.output).suffix.lower()
    if out_ext not in (*SCENE_FORMATS, ".fig", ".env"):
        raise JackpyError(f"{args.output}: cannot convert to {out_ext!r} "
                          f"(use {', '.join(SCENE_FORMATS)}, .fig or .env)")
    text_out = out_ext in (".fig", ".env")
    env = load(args.input, require_geometry=not text_out)
    source_dir = Path(args.input).parent
    if out_ext == ".fig":
        write_figures(args.output, env.figures.values(), source_dir=source_dir)
    elif out_ext == ".env":
        write_environment(args.output, env, source_dir=source_dir)
    else:
        export_scene(args.output, env)
    print(f"wrote {args.output} ({len(env.figures)} figure{'s' if len(env.figures) != 1 else ''})")
    return 0
