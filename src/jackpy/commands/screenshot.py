"""``jackpy screenshot SCENE -o out.png``: render a scene offscreen to a PNG."""

from __future__ import annotations

import argparse
import re


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("screenshot", help="render a scene (.env/.fig, or 'default') offscreen to a PNG")
    p.add_argument("scene", help="scene file, or 'default' for the default scene")
    p.add_argument("-o", "--output", required=True, help="PNG file to write")
    p.add_argument("--size", default="1280x800", help="image size WxH in pixels (default 1280x800)")
    p.add_argument("--view", default="iso", choices=["front", "side", "top", "iso"], help="camera direction")
    p.add_argument("--skeleton", action="store_true", help="draw figures as balls and sticks")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from jackpy.render import write_png
    from jackpy.ui.screenshot import render_scene
    from jackpy.ui.session import default_scene, load_session

    m = re.fullmatch(r"(\d+)[xX](\d+)", args.size)
    if not m or not (16 <= int(m[1]) <= 8192 and 16 <= int(m[2]) <= 8192):
        raise ValueError(f"--size must be WxH between 16 and 8192 pixels, not {args.size!r}")
    env = default_scene()[0] if args.scene == "default" else load_session(args.scene)[0]
    write_png(args.output, render_scene(env, (int(m[1]), int(m[2])), args.view, args.skeleton))
    print(f"wrote {args.output}")
    return 0
