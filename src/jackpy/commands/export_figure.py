"""``jackpy export-figure FIG|SCENE -o OUT.urdf|OUT.xml``: a figure's kinematic tree as URDF or MJCF.

FIG|SCENE is a Peabody ``.fig``/``.env`` file or a standard human written ``SEX:PERCENTILE``
(``male:50``, ``female:5``). A file with several articulated figures needs ``--figure NAME``.
"""

from __future__ import annotations

import argparse
import re

from jackpy.errors import JackpyError

_HUMAN = re.compile(r"^(male|female):(\d+(?:\.\d*)?)$")


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("export-figure", help="export a figure's kinematic tree as URDF (.urdf) or MJCF (.xml)")
    p.add_argument("source", metavar="FIG|SCENE", help="a .fig or .env file, or a standard human like male:50")
    p.add_argument("-o", "--output", required=True, metavar="OUT", help="OUT.urdf or OUT.xml (MJCF)")
    p.add_argument("--figure", default=None, metavar="NAME", help="which figure of a scene with several")
    p.add_argument("--floating", action="store_true", help="MJCF: give the root body a free joint")
    p.add_argument("--freeze", action="append", default=[], metavar="JOINT",
                   help="weld JOINT at its current displacement (repeatable)")
    p.set_defaults(func=run)


def load_figure(source: str, name: str | None):
    """The figure named by ``source`` (file or ``SEX:PERCENTILE``) and ``--figure``."""
    m = _HUMAN.match(source)
    if m:
        from jackpy.body.human import make_human

        return make_human(m[1], float(m[2]))
    from jackpy.peabody.reader import load

    env = load(source, require_geometry=False)
    figures = env.figures
    if name is not None:
        if name not in figures:
            raise JackpyError(f"{source}: no figure {name!r} (figures: {', '.join(figures) or 'none'})")
        return figures[name]
    moving = [f for f in figures.values() if f.joints] or list(figures.values())
    if len(moving) != 1:
        raise JackpyError(f"{source}: {len(moving)} figures ({', '.join(f.name for f in moving) or 'none'}); "
                          "choose one with --figure NAME")
    return moving[0]


def run(args: argparse.Namespace) -> int:
    from jackpy.motion.robot_export import export

    fig = load_figure(args.source, args.figure)
    kind = export(fig, args.output, floating=args.floating, frozen=args.freeze)
    print(f"{args.output}: {kind.upper()} of figure {fig.name} ({len(fig.segments)} bodies, {fig.ndof} DOFs)")
    return 0
