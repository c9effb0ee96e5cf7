"""Documents on disk: one ``NAME.env`` file per session, written in one atomic step.

The file is a Peabody environment (figures, placements, joint displacements) readable by any
Peabody tool, and its last line is a comment that carries what Peabody cannot say::

    # jackpy-session 2: {"format": "jackpy-session", "version": 2, ...}

the goals (each with its registered kind, :data:`jackpy.ik.goals.GOAL_TYPES`), settings, the
window's view, each figure's displacements and placement as exact binary64 numbers (the Peabody
text holds them rounded to its precision, so the comment wins), how to rebuild imported CAD
objects, the behaviors' switches and parameters, and the motion timeline. The whole file is written
to a temporary file and renamed over the old one (:mod:`jackpy.atomic`): a save interrupted at any
point leaves the previous session or the new one, never a mix.

A generated human's surfaces are written first, as ``NAME_psurf/gTOKEN/FIGURE/SEGMENT.pss``, in a
folder of their own for each save (``TOKEN`` new each time, named in the comment), so the old file
keeps reading its own surfaces until the rename commits the new one. Leftovers of interrupted
saves (temporary files of our naming beside the file, surface folders no file names) are removed on
the next save or open of that file.

Version 1 sessions (``NAME.env`` plus a ``NAME.jackpy.json`` sidecar) still open; saving one
writes the single file and removes the sidecar.

A save is a :func:`snapshot` of the document (cheap, on the caller's thread) and :func:`write`
(the serialising and the files, any thread): autosave (:mod:`jackpy.document.recovery`) writes in
the background.
"""

from __future__ import annotations

import copy
import functools
import json
import os
import re
import shutil
import uuid
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

import jackpy
from jackpy import jsonfile
from jackpy.atomic import atomic_write_text, clean_stale_temps
from jackpy.errors import JackpyError, SessionError
from jackpy.peabody import Environment, Figure
from jackpy.peabody.reader import read_environment, read_figures
from jackpy.peabody.writer import environment_to_text, relocator
from jackpy.scene.cad import CADObject, import_cad

if TYPE_CHECKING:
    from jackpy.document.document import Document

SIDECAR_SUFFIX = ".jackpy.json"
FORMAT = "jackpy-session"
VERSION = 2
MARK = "# jackpy-session 2: "
"""How the session line of a version-2 file starts."""
PSURF_GENERATION = re.compile(r"g[0-9a-f]{12}")


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
    """``NAME.env`` → ``NAME.jackpy.json`` (version-1 sessions)."""
    return Path(env_path).with_suffix(SIDECAR_SUFFIX)


def psurf_root(env_path: Path) -> Path:
    """``NAME.env`` → ``NAME_psurf`` (the generated humans' surfaces)."""
    return Path(env_path).parent / f"{Path(env_path).stem}_psurf"


# ---------------------------------------------------------------------- the session's content
def _m(a: np.ndarray) -> list[float]:
    return [float(x) for x in np.asarray(a, float).reshape(-1)]


def session_dict(doc: Document, generation: str | None = None) -> dict[str, Any]:
    """The session content of the document's current state."""
    figs: dict[str, Any] = {}
    for name, fig in doc.env.figures.items():
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
    out = {
        "format": FORMAT, "version": VERSION, "psurf_generation": generation,
        "settings": asdict(doc.settings),
        "view": doc.view_state,
        "extras": doc.extras,
        "figures": figs,
        "behaviors": {name: {b.name: {"enabled": bool(b.enabled), "params": _params(b.params)}
                             for b in loop.behaviors} for name, loop in doc.loops.items()},
        "goals": [g.to_dict() for g in doc.goals],
    }
    if doc.timeline is not None:
        out["timeline"] = doc.timeline.to_dict()
        out["time"] = float(doc.time)
    return out


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


# ---------------------------------------------------------------------- save
def session_file(path: str | os.PathLike[str]) -> Path:
    """The ``.env`` file a session is saved as (``.env`` added when missing)."""
    path = Path(path)
    return path if path.suffix.lower() == ".env" else path.with_suffix(".env")


@dataclass(frozen=True)
class Snapshot:
    """What a save writes, taken from a document on its own thread: a private copy of the
    environment (surface meshes shared: nothing changes a mesh in place), the folder its included
    files are named relative to, and the session content (JSON-ready, private). Writing it
    (:func:`write`) reads nothing of the document, so it may run on another thread while the
    document is edited."""

    env: Environment
    scene_dir: Path | None
    data: dict[str, Any]


def snapshot(doc: Document, view: dict[str, Any] | None = None) -> Snapshot:
    """The document's state now, to be written by :func:`write` (about 30 ms for the default
    scene; the save's serialising and writing take 50 times that). ``view``: entries to add to the
    session's ``view`` (the autosave's ``autosave_of``)."""
    meshes = {id(seg.psurf.mesh): seg.psurf.mesh for fig in doc.env.figures.values()
              for seg in fig.segments.values() if seg.psurf is not None and seg.psurf.mesh is not None}
    env = copy.deepcopy(doc.env, meshes)
    data = copy.deepcopy(session_dict(doc))
    data["view"] = {**(data.get("view") or {}), **(view or {})}
    return Snapshot(env, Path(doc.scene_dir) if doc.scene_dir is not None else None, data)


def save(doc: Document, path: str | os.PathLike[str]) -> Path:
    """Write the document to ``path`` (``.env``) in one atomic step (module docstring); returns
    the file written. The document itself is not changed (see :meth:`Document.save`)."""
    return write(snapshot(doc), path)


def write(snap: Snapshot, path: str | os.PathLike[str]) -> Path:
    """Write a :class:`Snapshot` to ``path`` (``.env``) in one atomic step; returns the file."""
    path = session_file(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    known, current = _current_generation(path)
    clean_stale_temps(path)
    if known:
        remove_leftovers(path, keep=current)
    generation = "g" + uuid.uuid4().hex[:12]
    env, wrote_psurf = _writable(snap.env, path, snap.scene_dir, generation)
    out_dir = path.absolute().parent
    base = snap.scene_dir if snap.scene_dir is not None else out_dir
    text = environment_to_text(env, base, relocate=relocator(snap.scene_dir, out_dir))
    data = dict(snap.data, psurf_generation=generation if wrote_psurf else None)
    line = json.dumps(data, separators=(",", ":"), allow_nan=False).replace("/", "\\/")
    atomic_write_text(path, text.rstrip("\n") + "\n\n" + MARK + line + "\n")
    # committed: what the new file does not name is stale now
    sidecar_path(path).unlink(missing_ok=True)
    remove_leftovers(path, keep=generation if wrote_psurf else None, legacy_in_use=False)
    return path


def _writable(env: Environment, path: Path, source_dir: Path | None, generation: str) -> tuple[Environment, bool]:
    """``env`` as it can be written to ``path``: each generated human (a figure with a body
    specification) is replaced by its :func:`~jackpy.body.human.peabody_copy`, its surfaces written
    as ``NAME_psurf/GENERATION/FIGURE/SEGMENT.pss`` (names relative to ``source_dir``, where the
    writer expects them). Returns the environment and whether any surface was written."""
    from jackpy.body.human import peabody_copy
    from jackpy.peabody.psurf_io import write_psurf

    humans = [f for f in env.figures.values() if getattr(f, "body_spec", None) is not None]
    if not humans:
        return env, False
    out = Environment(dict(env.figures), list(env.includes))
    base = Path(source_dir) if source_dir is not None else path.parent
    for fig in humans:
        folder = psurf_root(path) / generation / fig.name
        folder.mkdir(parents=True, exist_ok=True)
        for seg in fig.segments.values():
            if seg.psurf is not None and seg.psurf.mesh is not None:
                write_psurf(folder / f"{seg.name}.pss", seg.psurf.mesh, f"{fig.name}.{seg.name}, generated by jackpy.body")
        rel = Path(os.path.relpath(folder.resolve(), base.resolve())).as_posix()
        out.figures[fig.name] = peabody_copy(fig, rel)
    return out, True


def remove_leftovers(path: Path, keep: str | None = None, legacy_in_use: bool = True) -> list[Path]:
    """Remove what interrupted saves of ``path`` left: temporary files of our naming beside it
    (:func:`jackpy.atomic.clean_stale_temps`: none a live writer holds) and surface folders ``NAME_psurf/gTOKEN`` other than
    ``keep`` (the one the file names). With ``legacy_in_use`` false, version-1 surface folders
    (``NAME_psurf/FIGURE``) go too. Returns what was removed."""
    removed = list(clean_stale_temps(path))
    root = psurf_root(path)
    if root.is_dir():
        for d in root.iterdir():
            if not d.is_dir():
                continue
            ours = PSURF_GENERATION.fullmatch(d.name) is not None
            if (ours and d.name != keep) or (not ours and not legacy_in_use):
                shutil.rmtree(d, ignore_errors=True)
                removed.append(d)
        if not any(root.iterdir()):
            root.rmdir()
    return removed


def _current_generation(path: Path) -> tuple[bool, str | None]:
    """(known, token): the surface folder the file at ``path`` names now; not known when the file
    exists but its session line cannot be read (then no folder is touched)."""
    if not path.is_file():
        return True, None
    try:
        found = _session_line(path)
        if found is None:
            return True, None
        data = json.loads(found[0])
        gen = data.get("psurf_generation") if isinstance(data, dict) else None
        return True, gen if isinstance(gen, str) else None
    except (JackpyError, ValueError):
        return False, None


# ---------------------------------------------------------------------- open
def _session_line(path: Path) -> tuple[str, int] | None:
    """The session comment's JSON text and its line number, if the file has one (version 2)."""
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise SessionError(f"{path}: cannot read the scene file ({exc.strerror or exc})") from None
    mark = MARK.encode()
    at = data.rfind(b"\n" + mark)
    if at < 0:
        if not data.startswith(mark):
            return None
        at = -1
    start = at + 1 + len(mark)
    end = data.find(b"\n", start)
    raw = data[start:] if end < 0 else data[start:end]
    line = data.count(b"\n", 0, at + 1) + 1
    return jsonfile.decode(raw, str(path), SessionError), line


def load_session(path: str | os.PathLike[str]) -> tuple[Environment, dict[str, Any] | None]:
    """Read a session: the environment, and its session data (version 2: the file's session line;
    version 1: the sidecar; None when neither). CAD objects are re-imported; exact postures applied."""
    path = Path(path)
    if not path.is_file():
        raise SessionError(f"{path}: no such scene file")
    found = _session_line(path)
    where = str(path)
    if found is not None:
        text, line = found
        data = jsonfile.loads(text, str(path), SessionError, line)
        if not isinstance(data, dict) or data.get("format") != FORMAT:
            raise SessionError(f"{path}:{line}: not a jackpy session line")
        try:
            _check(data)
        except jsonfile.Invalid as exc:
            raise jsonfile.schema_error(SessionError, f"{path}:{line}", exc) from None
    else:
        data = None
        side = sidecar_path(path)
        where = str(side)
        if side.is_file():
            try:
                data = jsonfile.load(side, SessionError)
            except OSError as exc:
                raise SessionError(f"{side}: not a readable session sidecar ({exc.strerror or exc})") from None
            if not isinstance(data, dict) or data.get("format") != FORMAT:
                raise SessionError(f"{side}: not a jackpy session sidecar")
            try:
                _check(data)
            except jsonfile.Invalid as exc:
                raise jsonfile.schema_error(SessionError, str(side), exc) from None
    figs = (data or {}).get("figures", {})
    standard = figures_dir()  # the standard objects (chair, table) are a library every session may include
    env = read_environment(path, require_geometry=not any("cad" in f for f in figs.values()),
                           library=[standard] if standard is not None else None)
    for name, entry in figs.items():
        if "cad" in entry and name in env.figures:
            cad = entry["cad"]
            obj = import_cad(cad["source"], cad.get("units", "m"), cad.get("up", "y"), name)
            env.figures[name] = obj
    for name, entry in figs.items():
        fig = env.figures.get(name)
        if fig is None:
            raise SessionError(f"{where}: figure {name!r} is not in {path.name}")
        root = entry.get("root")
        if root is not None and tuple(root) != fig.root:
            try:
                fig.reroot(*root)
            except JackpyError as exc:
                raise SessionError(f"{where}: figure {name!r} root: {exc}") from None
        fig.q = _matrix(entry["q"], (fig.ndof,), f"{where}: figure {name!r} q")
        fig.location = _matrix(entry["location"], (4, 4), f"{where}: figure {name!r} location")
        if "human" in entry:
            _restore_human(fig, entry, f"{where}: figure {name!r}")
    return env, data


def _restore_human(fig: Figure, entry: dict[str, Any], where: str) -> None:
    """A generated human read back: its spine and shoulder groups and its body specification."""
    from jackpy.body.human import attach_groups, build_spec

    h = entry["human"]
    q = fig.q.copy()
    try:
        if "spine" not in fig.groups:  # a reader that restores the groups from the file needs no help
            attach_groups(fig)
        fig.q = q  # the session's exact displacements (attaching re-derives them from the angles)
        fig.body_spec = build_spec(h["sex"], float(h["percentile"]), h.get("population", "ansur2"))  # type: ignore[attr-defined]
    except (JackpyError, KeyError, ValueError, TypeError) as exc:
        raise SessionError(f"{where}: cannot restore the human ({exc})") from None


def _check(data: dict[str, Any]) -> None:
    """The shape of a session's content, before anything uses it (raises :class:`jsonfile.Invalid`
    naming the key path; values are checked where they are applied)."""
    from jackpy.ik.goals import GOAL_TYPES
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
    jsonfile.obj(data.get("view") or {}, "view")
    for k, g in enumerate(jsonfile.arr(data.get("goals", []), "goals")):
        where = f"goals[{k}]"
        g = jsonfile.obj(g, where)
        for name in ("key", "figure"):
            jsonfile.string(jsonfile.required(g, name, where), f"{where}.{name}")
        if "goal" in g:  # version 2: the goal's own dictionary
            goal = jsonfile.obj(g["goal"], f"{where}.goal")
            jsonfile.string(jsonfile.required(goal, "kind", f"{where}.goal"), f"{where}.goal.kind", GOAL_TYPES)
            jsonfile.string(jsonfile.required(goal, "site", f"{where}.goal"), f"{where}.goal.site")
            jsonfile.num(jsonfile.required(goal, "weight", f"{where}.goal"), f"{where}.goal.weight", 0.0)
            if g.get("role") is not None:
                jsonfile.string(g["role"], f"{where}.role", ("eyes",))
        else:  # version 1: the workbench's goal fields
            for name in ("site", "kind"):
                jsonfile.string(jsonfile.required(g, name, where), f"{where}.{name}")
            jsonfile.string(g["kind"], f"{where}.kind", [*GOAL_TYPES, "eyes"])
            if "axis" in g:
                jsonfile.vector(g["axis"], f"{where}.axis", 3)
            jsonfile.vector(jsonfile.required(g, "target", where), f"{where}.target", 16)
            jsonfile.num(jsonfile.required(g, "weight", where), f"{where}.weight", 0.0)
        for name, n in (("manip", 16), ("offset", 9)):
            jsonfile.vector(jsonfile.required(g, name, where), f"{where}.{name}", n)
        jsonfile.boolean(jsonfile.required(g, "enabled", where), f"{where}.enabled")
        jsonfile.integer(jsonfile.required(g, "priority", where), f"{where}.priority", -2**31, 2**31 - 1)
    if "camera" in data:
        c = jsonfile.obj(data["camera"], "camera")
        jsonfile.vector(jsonfile.required(c, "target", "camera"), "camera.target", 3)
        for name in ("distance", "yaw", "pitch"):
            jsonfile.num(jsonfile.required(c, name, "camera"), f"camera.{name}")


def open_into(doc: Document, path: Path) -> None:
    """Replace ``doc``'s content with the session saved at ``path``."""
    from jackpy.document.goals import GoalEntry
    from jackpy.document.settings import Settings

    path = session_file(path) if not Path(path).is_file() else Path(path)
    env, data = load_session(path)
    goals = None
    if data is not None:
        known = {f.name for f in fields(Settings)}
        doc.settings = Settings(**{k: v for k, v in data.get("settings", {}).items() if k in known})
        goals = []
        for g in data.get("goals", []):
            where = f"{path}: goal {g.get('key')!r}"
            if g.get("figure") not in env.figures:
                raise SessionError(f"{where}: unknown figure {g.get('figure')!r}")
            try:
                goals.append(GoalEntry.from_dict(g))
            except SessionError:
                raise
            except (JackpyError, KeyError, ValueError, TypeError) as exc:
                raise SessionError(f"{where}: {exc}") from None
    doc.scene_dir = path.parent
    doc.set_environment(env, goals)
    for name, entries in ((data or {}).get("behaviors") or {}).items():
        loop = doc.loops.get(name)
        if loop is None or not isinstance(entries, dict):
            continue
        for b in loop.behaviors:
            e = entries.get(b.name)
            if isinstance(e, dict):
                set_behavior(b, bool(e.get("enabled", True)), e.get("params") or {})
    view = dict((data or {}).get("view") or {})
    if data is not None and "camera" in data:  # version 1
        view["camera"] = data["camera"]
    doc.view_state = view
    extras = (data or {}).get("extras")
    doc.extras = dict(extras) if isinstance(extras, dict) else {}
    doc.timeline, doc.time, doc.playing = None, 0.0, False
    if data is not None and "timeline" in data:
        from jackpy.motion.timeline import Timeline  # the motion package, only when a file has one

        try:
            doc.timeline = Timeline.from_dict(data["timeline"])
        except (JackpyError, KeyError, ValueError, TypeError) as exc:
            raise SessionError(f"{path}: timeline: {exc}") from None
        doc.time = float(data.get("time", 0.0))
    doc.path = path
    doc.dirty = False
    remove_leftovers(path, keep=(data or {}).get("psurf_generation"))
    doc.info(f"opened {path}")


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
