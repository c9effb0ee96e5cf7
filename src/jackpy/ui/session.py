"""Scenes on disk: the default scene, save/open, CAD import, autosave and crash recovery.

A session is two files written atomically side by side:

- ``NAME.env``: the Peabody environment (figures, placements, joint displacements) through
  :func:`jackpy.peabody.writer.write_environment`, readable by any Peabody tool;
- ``NAME.jackpy.json``: the sidecar with what Peabody cannot say: goals, settings, camera, each
  figure's displacements and placement as exact binary64 numbers (the ``.env`` holds them rounded
  to its text precision, so the sidecar wins when both are present), and how to rebuild imported
  CAD objects (source file, units, up axis).

Autosave writes the same pair to ``$JACKPY_HOME/recovery/recovery.env`` (default ``~/.jackpy``)
every ``Settings.autosave_s`` seconds; a clean exit deletes it, so finding it at start-up means
the last run crashed, and the workbench offers to recover it.
"""

from __future__ import annotations

import copy
import functools
import json
import os
from dataclasses import asdict, fields
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

import jackpy
from jackpy import jsonfile
from jackpy.atomic import atomic_write_text
from jackpy.errors import JackpyError, SessionError
from jackpy.peabody import Environment, Figure
from jackpy.peabody.reader import read_environment, read_figures
from jackpy.peabody.writer import write_environment
from jackpy.scene.cad import CADObject, add_cad, import_cad

if TYPE_CHECKING:
    from jackpy.ui.app import App

SIDECAR_SUFFIX = ".jackpy.json"
FORMAT = "jackpy-session"
VERSION = 1


def figures_dir() -> Path | None:
    """The project's ``figures/`` directory (Peabody files of the standard objects), if present."""
    for base in (Path(os.environ.get("JACKPY_FIGURES", "")), Path(jackpy.__file__).resolve().parents[2] / "figures"):
        if str(base) and (base / "chair.fig").is_file():
            return base
    return None


@functools.lru_cache(maxsize=4)
def _standard_human(sex: str, percentile: float) -> Figure:
    from jackpy.body.human import make_human

    return make_human(sex, percentile)


def standard_human(sex: str = "male", percentile: float = 50.0) -> Figure:
    """A fresh copy of ``make_human(sex, percentile)`` (generated once per process)."""
    return copy.deepcopy(_standard_human(sex, float(percentile)))


def default_scene() -> tuple[Environment, Path | None]:
    """The scene ``jackpy`` opens with: the 50th-percentile male standing on the floor at the
    origin (facing +z), a chair on his right and a work table on his left.

    Returns the environment and the directory its included files are relative to.
    """
    env = Environment()
    env.add(standard_human("male", 50.0))
    base = figures_dir()
    if base is not None:
        for name, place in (("worktable.fig", (1.2, 0.0, 0.1)), ("chair.fig", (-1.0, 0.0, 0.0))):
            for fig in read_figures(base / name):
                fig.location = np.eye(4)
                fig.location[:3, 3] = place
                env.add(fig)
            env.includes.append(name)
    return env, base


def sidecar_path(env_path: Path) -> Path:
    """``NAME.env`` → ``NAME.jackpy.json``."""
    return Path(env_path).with_suffix(SIDECAR_SUFFIX)


# ---------------------------------------------------------------------- JSON
def _m(a: np.ndarray) -> list[float]:
    return [float(x) for x in np.asarray(a, float).reshape(-1)]


def session_dict(app: App) -> dict[str, Any]:
    """The sidecar content for the app's current state."""
    cam = app.camera
    figs: dict[str, Any] = {}
    for name, fig in app.env.figures.items():
        entry: dict[str, Any] = {"q": _m(fig.q), "location": _m(fig.location)}
        if fig.root is not None:
            entry["root"] = list(fig.root)
        if isinstance(fig, CADObject):
            s = fig.settings
            entry["cad"] = {"source": str(Path(s.source).resolve()), "units": s.units, "up": s.up}
        spec = getattr(fig, "body_spec", None)
        if spec is not None:
            entry["human"] = {"sex": spec.sex, "percentile": float(spec.percentile),
                              "population": spec.population}
        figs[name] = entry
    return {
        "format": FORMAT, "version": VERSION,
        "settings": asdict(app.settings),
        "camera": {"target": _m(cam.target), "distance": cam.distance, "yaw": cam.yaw, "pitch": cam.pitch,
                   "orthographic": cam.orthographic},
        "figures": figs,
        "behaviors": {name: {b.name: {"enabled": bool(b.enabled), "params": _params(b.params)}
                             for b in loop.behaviors} for name, loop in app.loops.items()},
        "goals": [{"key": g.key, "figure": g.figure, "site": g.site, "kind": g.kind, "target": _m(g.target),
                   "enabled": g.enabled, "weight": g.weight, "priority": g.priority, "chain": g.chain,
                   "manip": _m(g.manip), "offset": _m(g.offset), "axis": _m(g.axis)} for g in app.goals],
    }


def _params(params: Any) -> dict[str, Any]:
    out = {}
    for k, v in asdict(params).items():
        out[k] = v.tolist() if isinstance(v, np.ndarray) else (float(v) if isinstance(v, np.floating) else v)
    return out


def _matrix(values: Any, shape: tuple[int, ...], where: str) -> np.ndarray:
    try:
        a = np.asarray(values, dtype=float).reshape(shape)
    except (TypeError, ValueError):
        raise SessionError(f"{where}: expected {int(np.prod(shape))} numbers") from None
    return a


# ---------------------------------------------------------------------- save / open
def save_session(app: App, path: str | os.PathLike[str], *, remember: bool = True) -> None:
    """Write the scene to ``path`` (``.env``) and its sidecar, atomically."""
    path = Path(path)
    if path.suffix.lower() != ".env":
        path = path.with_suffix(".env")
    path.parent.mkdir(parents=True, exist_ok=True)
    env = _writable(app.env, path, app.scene_dir)
    write_environment(path, env, source_dir=app.scene_dir)
    atomic_write_text(sidecar_path(path), json.dumps(session_dict(app), indent=1) + "\n")
    if remember:
        app.session_path = path
        app.scene_dir = path.parent
        app.dirty = False
        app.info(f"saved {path}")


def _writable(env: Environment, path: Path, source_dir: Path | None) -> Environment:
    """``env`` as it can be written to ``path``: each generated human (a figure with a body
    specification) is replaced by its :func:`~jackpy.body.human.peabody_copy`, its surfaces written
    as ``NAME_psurf/FIGURE/SEGMENT.pss`` beside the scene (names relative to ``source_dir``, where
    the writer expects them)."""
    from jackpy.body.human import peabody_copy
    from jackpy.peabody.psurf_io import write_psurf

    humans = [f for f in env.figures.values() if getattr(f, "body_spec", None) is not None]
    if not humans:
        return env
    out = Environment(dict(env.figures), list(env.includes))
    base = Path(source_dir) if source_dir is not None else path.parent
    for fig in humans:
        folder = path.parent / f"{path.stem}_psurf" / fig.name
        folder.mkdir(parents=True, exist_ok=True)
        for seg in fig.segments.values():
            if seg.psurf is not None and seg.psurf.mesh is not None:
                write_psurf(folder / f"{seg.name}.pss", seg.psurf.mesh, f"{fig.name}.{seg.name}, generated by jackpy.body")
        rel = Path(os.path.relpath(folder.resolve(), base.resolve())).as_posix()
        out.figures[fig.name] = peabody_copy(fig, rel)
    return out


def _restore_human(fig: Figure, entry: dict[str, Any], where: str) -> None:
    """A generated human read back: its spine and shoulder groups and its body specification."""
    from jackpy.body.human import attach_groups, build_spec

    h = entry["human"]
    q = fig.q.copy()
    try:
        attach_groups(fig)
        fig.q = q  # the sidecar's exact displacements (attaching re-derives them from the angles)
        fig.body_spec = build_spec(h["sex"], float(h["percentile"]), h.get("population", "ansur2"))  # type: ignore[attr-defined]
    except (JackpyError, KeyError, ValueError, TypeError) as exc:
        raise SessionError(f"{where}: cannot restore the human ({exc})") from None


def load_session(path: str | os.PathLike[str]) -> tuple[Environment, dict[str, Any] | None]:
    """Read a ``.env`` file and its sidecar (None when absent); CAD objects are re-imported."""
    path = Path(path)
    if not path.is_file():
        raise SessionError(f"{path}: no such scene file")
    side = sidecar_path(path)
    data = None
    if side.is_file():
        try:
            data = jsonfile.load(side, SessionError)
        except OSError as exc:
            raise SessionError(f"{side}: not a readable session sidecar ({exc.strerror or exc})") from None
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise SessionError(f"{side}: not a jackpy session sidecar")
        try:
            _check_sidecar(data)
        except jsonfile.Invalid as exc:
            raise jsonfile.schema_error(SessionError, str(side), exc) from None
    figs = (data or {}).get("figures", {})
    env = read_environment(path, require_geometry=not any("cad" in f for f in figs.values()))
    for name, entry in figs.items():
        if "cad" in entry and name in env.figures:
            cad = entry["cad"]
            obj = import_cad(cad["source"], cad.get("units", "m"), cad.get("up", "y"), name)
            env.figures[name] = obj
    for name, entry in figs.items():
        fig = env.figures.get(name)
        if fig is None:
            raise SessionError(f"{side}: figure {name!r} is not in {path.name}")
        root = entry.get("root")
        if root is not None and tuple(root) != fig.root:
            try:
                fig.reroot(*root)
            except JackpyError as exc:
                raise SessionError(f"{side}: figure {name!r} root: {exc}") from None
        fig.q = _matrix(entry["q"], (fig.ndof,), f"{side}: figure {name!r} q")
        fig.location = _matrix(entry["location"], (4, 4), f"{side}: figure {name!r} location")
        if "human" in entry:
            _restore_human(fig, entry, f"{side}: figure {name!r}")
    return env, data


def _check_sidecar(data: dict[str, Any]) -> None:
    """The shape of a sidecar's content, before anything uses it (raises :class:`jsonfile.Invalid`
    naming the key path; values are checked where they are applied)."""
    from jackpy.scene.cad import UNITS, UP_AXES

    for name, entry in jsonfile.obj(data.get("figures", {}), "figures").items():
        where = f"figures.{name}"
        entry = jsonfile.obj(entry, where)
        for i, x in enumerate(jsonfile.arr(jsonfile.required(entry, "q", where), f"{where}.q")):
            jsonfile.num(x, f"{where}.q[{i}]")
        jsonfile.vector(jsonfile.required(entry, "location", where), f"{where}.location", 16)
        if entry.get("root") is not None:
            root = jsonfile.arr(entry["root"], f"{where}.root")
            if len(root) != 2:
                raise jsonfile.Invalid(f"{where}.root", "expected [SEGMENT, SITE]")
            for i, r in enumerate(root):
                jsonfile.string(r, f"{where}.root[{i}]")
        if "cad" in entry:
            cad = jsonfile.obj(entry["cad"], f"{where}.cad")
            jsonfile.string(jsonfile.required(cad, "source", f"{where}.cad"), f"{where}.cad.source")
            jsonfile.string(cad.get("units", "m"), f"{where}.cad.units", UNITS)
            jsonfile.string(cad.get("up", "y"), f"{where}.cad.up", UP_AXES)
        if "human" in entry:
            h = jsonfile.obj(entry["human"], f"{where}.human")
            jsonfile.string(jsonfile.required(h, "sex", f"{where}.human"), f"{where}.human.sex", ("male", "female"))
            jsonfile.num(jsonfile.required(h, "percentile", f"{where}.human"), f"{where}.human.percentile", 1, 99)
            jsonfile.string(h.get("population", "ansur2"), f"{where}.human.population")
    jsonfile.obj(data.get("settings", {}), "settings")
    jsonfile.obj(data.get("behaviors") or {}, "behaviors")
    for k, g in enumerate(jsonfile.arr(data.get("goals", []), "goals")):
        where = f"goals[{k}]"
        g = jsonfile.obj(g, where)
        for name in ("key", "figure", "site", "kind"):
            jsonfile.string(jsonfile.required(g, name, where), f"{where}.{name}")
        from jackpy.ui.app import GOAL_KINDS

        jsonfile.string(g["kind"], f"{where}.kind", GOAL_KINDS)
        if "axis" in g:
            jsonfile.vector(g["axis"], f"{where}.axis", 3)
        for name, n in (("target", 16), ("manip", 16), ("offset", 9)):
            jsonfile.vector(jsonfile.required(g, name, where), f"{where}.{name}", n)
        jsonfile.boolean(jsonfile.required(g, "enabled", where), f"{where}.enabled")
        jsonfile.num(jsonfile.required(g, "weight", where), f"{where}.weight", 0.0)
        jsonfile.integer(jsonfile.required(g, "priority", where), f"{where}.priority", -2**31, 2**31 - 1)
    if "camera" in data:
        c = jsonfile.obj(data["camera"], "camera")
        jsonfile.vector(jsonfile.required(c, "target", "camera"), "camera.target", 3)
        for name in ("distance", "yaw", "pitch"):
            jsonfile.num(jsonfile.required(c, name, "camera"), f"camera.{name}")


def apply_session(app: App, env: Environment, data: dict[str, Any] | None, base: Path | None) -> None:
    """Show a loaded scene with its goals, settings and camera."""
    from jackpy.ui.app import GoalEntry, Settings

    goals = None
    if data is not None:
        known = {f.name for f in fields(Settings)}
        app.settings = Settings(**{k: v for k, v in data.get("settings", {}).items() if k in known})
        goals = []
        for g in data.get("goals", []):
            where = f"goal {g.get('key')!r}"
            if g.get("figure") not in env.figures:
                raise SessionError(f"{where}: unknown figure {g.get('figure')!r}")
            goals.append(GoalEntry(g["key"], g["figure"], g["site"], g["kind"],
                                   _matrix(g["target"], (4, 4), where), bool(g["enabled"]), float(g["weight"]),
                                   int(g["priority"]), g.get("chain"), _matrix(g["manip"], (4, 4), where),
                                   _matrix(g["offset"], (3, 3), where),
                                   _matrix(g.get("axis", [0.0, 0.0, 1.0]), (3,), where)))
    app.scene_dir = base
    app.set_environment(env, goals)
    for name, fig in env.figures.items():
        if isinstance(fig, CADObject):
            app.view.cad_figures.add(name)
    for name, entries in ((data or {}).get("behaviors") or {}).items():
        loop = app.loops.get(name)
        if loop is None or not isinstance(entries, dict):
            continue
        for b in loop.behaviors:
            e = entries.get(b.name)
            if isinstance(e, dict):
                set_behavior(b, bool(e.get("enabled", True)), e.get("params") or {})
    if data is not None and "camera" in data:
        c = data["camera"]
        cam = app.camera
        cam.target = _matrix(c["target"], (3,), "camera target")
        cam.distance, cam.yaw, cam.pitch = float(c["distance"]), float(c["yaw"]), float(c["pitch"])
        cam.orthographic = bool(c.get("orthographic", False))


def set_behavior(behavior: Any, enabled: bool, params: dict[str, Any]) -> None:
    """Set a behavior's switch and the params that are valid (others keep their values)."""
    from jackpy.behaviors.base import validate

    behavior.enabled = enabled
    for k, v in params.items():
        if not hasattr(behavior.params, k):
            continue
        old = getattr(behavior.params, k)
        setattr(behavior.params, k, v)
        try:
            validate(behavior.params)
        except (ValueError, TypeError):
            setattr(behavior.params, k, old)


def open_session(app: App, path: str | os.PathLike[str]) -> None:
    """Replace the app's scene with the one saved at ``path``."""
    path = Path(path)
    env, data = load_session(path)
    apply_session(app, env, data, path.parent)
    app.session_path = path
    app.dirty = False
    app.info(f"opened {path}")


def new_scene(app: App) -> None:
    """Replace the scene with the default one."""
    env, base = default_scene()
    app.scene_dir = base
    app.set_environment(env)
    app.session_path = None


def import_cad_file(app: App, path: str | os.PathLike[str], units: str = "m", up: str = "y") -> CADObject:
    """Add a CAD file to the scene (drawn translucent; picked and moved like any object)."""
    obj = add_cad(app.env, path, units, up)
    app.view.cad_figures.add(obj.name)
    app.info(f"imported {Path(path).name}: {obj.triangle_count} triangles")
    return obj


# ---------------------------------------------------------------------- recovery
def recovery_path() -> Path:
    """Where autosave writes: ``$JACKPY_HOME/recovery/recovery.env`` (default ``~/.jackpy``)."""
    home = Path(os.environ.get("JACKPY_HOME", Path.home() / ".jackpy"))
    return home / "recovery" / "recovery.env"


def autosave(app: App) -> None:
    """Write the recovery pair (without changing the session's own path)."""
    save_session(app, recovery_path(), remember=False)


def pending_recovery() -> Path | None:
    """The recovery file a crashed run left behind, if any."""
    p = recovery_path()
    return p if p.is_file() else None


def recover(app: App, path: Path) -> None:
    """Open the recovery file as an unsaved scene, then delete it."""
    open_session(app, path)
    app.session_path = None
    app.dirty = True
    discard_recovery(path)


def discard_recovery(path: Path) -> None:
    """Delete a recovery pair (after recovering it, declining it, or a clean exit)."""
    for p in (path, sidecar_path(path)):
        p.unlink(missing_ok=True)
