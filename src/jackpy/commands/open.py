"""``jackpy open [SCENE]``: the interactive workbench window (``jackpy`` alone runs this)."""

from __future__ import annotations

import argparse


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("open", help="open the workbench window (on SCENE, or the default scene)")
    p.add_argument("scene", nargs="?", default=None, help="scene file (.env or .fig) to open")
    p.add_argument("--frames", type=int, default=None, metavar="N",
                   help="draw N frames and exit (a smoke test of the window)")
    p.add_argument("--motion", default=None, metavar="MOTION",
                   help="motion file (NAME.motion.json) to load into the timeline (see docs/motion.md)")
    p.add_argument("--flock", metavar="PORT", default=argparse.SUPPRESS,
                   help="connect to a Flock of Birds on PORT or URL (as `jackpy --flock PORT`)")
    p.add_argument("--birds", type=int, default=4, metavar="N",
                   help="number of sensor birds on the --flock port (default 4: waist, neck, palms)")
    p.add_argument("--sensors", default=None, metavar="JSON",
                   help="sensor configuration (mounts, offsets; default: Jack's four) for --flock or the Devices panel's Connect")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from jackpy import compiled
    from jackpy.ui import session
    from jackpy.ui.app import App
    from jackpy.ui.window import Window

    env, base = session.default_scene()
    app = App(env)
    app.scene_dir = base
    if args.scene is not None:  # a bad scene is reported before any window opens
        session.open_session(app, Path(args.scene))
    if getattr(args, "motion", None):  # a bad motion file too is reported before the window opens
        from jackpy.motion.player import load_into

        load_into(app.doc, args.motion)
    sensors = getattr(args, "sensors", None)
    if sensors:  # a bad sensor configuration too (file:line:column), before the window opens
        from jackpy.devices.sensors import load_sensor_config

        load_sensor_config(Path(sensors).expanduser())
    compiled.warm(compiled.announce_on_stderr)  # before any frame: no solve compiles or loads a kernel
    window = Window(app, "jackpy")
    try:
        offer = session.recovery_offer(args.scene)  # a crashed run's autosave of this scene
        window.ui.recovery_offer = str(offer) if offer is not None else None
        flock = getattr(args, "flock", None)
        if flock or sensors:
            from jackpy.ui.panels.devices import link_of

            window.ui.open_panels["Devices"] = True
            link = link_of(app)
            link.sensors_path = sensors or ""  # without --flock: the panel's Connect uses it
            if flock:
                link.connect(flock, getattr(args, "birds", 4))  # an error is in the log panel
        frames = getattr(args, "frames", None)
        if frames is None:
            window.run(autosave=lambda: session.autosave(app))
        else:
            for _ in range(frames):
                window.frame()
    finally:
        link = getattr(app, "device_link", None)
        if link is not None:
            link.disconnect()
        session.finish_autosave(app, clean=False)  # after an exception: wait, keep the recovery file
        window.close()
    return 0
