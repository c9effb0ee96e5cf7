"""The window's side of sessions: save, open, new scene, CAD import, autosave and recovery for an
:class:`~jackpy.ui.app.App`. The file format and everything headless are
:mod:`jackpy.document.session`'s (re-exported here); these add the camera and the log.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import TYPE_CHECKING

from jackpy.document import Document
from jackpy.errors import JackpyError
from jackpy.document.session import (  # noqa: F401  (re-exported)
    default_scene,
    discard_recovery,
    figures_dir,
    load_session,
    pending_recovery,
    recovery_path,
    session_file,
    sidecar_path,
    standard_human,
)
from jackpy.document import session as doc_session
from jackpy.scene.cad import CADObject

if TYPE_CHECKING:
    from jackpy.ui.app import App


def save_session(app: App, path: str | os.PathLike[str], *, remember: bool = True) -> Path:
    """Write the document (with the camera) to ``path`` (``.env``) atomically."""
    app.store_view()
    if not remember:
        return doc_session.save(app.doc, path)
    written = app.doc.save(path)
    _remember_recent(app, written)
    return written


def open_session(app: App, path: str | os.PathLike[str], *, remember: bool = True) -> None:
    """Replace the app's document with the one saved at ``path`` (``remember``: it goes first
    in File → Open Recent)."""
    doc = Document.open(path)
    doc.log[:0] = app.log
    app.set_document(doc)
    if remember:
        _remember_recent(app, Path(path))


def _remember_recent(app: App, path: Path) -> None:
    """Put ``path`` first in the user's recent files; a preferences file that cannot be written
    is a warning, never a failed save or open."""
    try:
        app.preferences.add_recent(path)
    except OSError as exc:
        app.info(f"warning: recent files not saved ({exc})")


def new_scene(app: App) -> None:
    """Replace the scene with the default one."""
    env, base = default_scene()
    app.set_environment(env)
    app.doc.scene_dir, app.doc.path = base, None


def import_cad_file(app: App, path: str | os.PathLike[str], units: str = "m", up: str = "y") -> CADObject:
    """Add a CAD file to the scene (drawn translucent; picked and moved like any object)."""
    from jackpy.scene.cad import add_cad

    obj = add_cad(app.env, path, units, up)
    app.info(f"imported {Path(path).name}: {obj.triangle_count} triangles")
    return obj


def autosave(app: App) -> None:
    """Write the recovery file (without changing the session's own path); it remembers which
    scene it is the autosave of."""
    app.doc.view_state["autosave_of"] = str(Path(app.session_path).resolve()) if app.session_path else None
    try:
        save_session(app, recovery_path(), remember=False)
    finally:
        app.doc.view_state.pop("autosave_of", None)


def recovery_scene(path: Path) -> Path | None:
    """The scene a recovery file is the autosave of (None: an unnamed scene, or unreadable)."""
    try:
        found = doc_session._session_line(Path(path))
        data = json.loads(found[0]) if found else {}
        of = (data.get("view") or {}).get("autosave_of")
    except (JackpyError, ValueError, AttributeError):
        return None
    return Path(of) if isinstance(of, str) else None


def recovery_offer(scene: str | os.PathLike[str] | None) -> Path | None:
    """The recovery file to offer when the workbench starts on ``scene`` (None: the default
    scene): one a crashed run left behind for that scene, or for an unnamed scene when no scene
    is given."""
    found = pending_recovery()
    if found is None:
        return None
    of = recovery_scene(found)
    if scene is None:
        return found
    return found if of is not None and of == Path(scene).resolve() else None


def recover(app: App, path: Path) -> None:
    """Open the recovery file as an unsaved scene (of the file it autosaved, if any), then delete it."""
    of = recovery_scene(path)
    open_session(app, path, remember=False)
    app.doc.view_state.pop("autosave_of", None)
    app.doc.path = of
    app.doc.dirty = True
    discard_recovery(path)
