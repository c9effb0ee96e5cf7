"""The window's side of sessions: save, open, new scene, CAD import, autosave and recovery for an
:class:`~jackpy.ui.app.App`. The file format and everything headless are
:mod:`jackpy.document.session`'s and :mod:`jackpy.document.recovery`'s (re-exported here); these
add the camera and the log. Autosave writes in the background (:class:`~jackpy.document.recovery.Autosaver`,
one per app): :func:`autosave` returns at once, :func:`report_autosave` puts a failed write in the
log, :func:`finish_autosave` (a clean exit) waits for a pending write and deletes the run's
recovery files.
"""

from __future__ import annotations

import os
from concurrent.futures import Future
from pathlib import Path
from typing import TYPE_CHECKING, Any

from jackpy.document import Document
from jackpy.document.recovery import (  # noqa: F401  (re-exported)
    Autosaver,
    discard_recovery,
    offer_for,
    orphans,
    recovery_path,
    recovery_scene,
)
from jackpy.document.session import (  # noqa: F401  (re-exported)
    default_scene,
    figures_dir,
    load_session,
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


def autosaver(app: App) -> Autosaver:
    """The app's autosaver (made on first use)."""
    saver = getattr(app, "autosaver", None)
    if saver is None:
        saver = Autosaver()
        app.autosaver = saver  # type: ignore[attr-defined]
    return saver


def autosave(app: App) -> Future[Any]:
    """Write the app's recovery file in the background (the session's own path and dirty flag are
    left alone); it remembers which scene it is the autosave of. Returns the write's future."""
    app.store_view()
    return autosaver(app).save(app.doc, app.session_path)


def drop_autosave(app: App) -> None:
    """Nothing is unsaved (the scene's file holds the work): delete the app's recovery files."""
    saver = getattr(app, "autosaver", None)
    if saver is not None and saver.written:
        saver.drop()


def report_autosave(app: App) -> None:
    """Put each failed background write in the log (``error: autosave failed: ...``, a toast)."""
    saver = getattr(app, "autosaver", None)
    if saver is not None:
        for message in saver.failures():
            app.info(f"error: autosave failed: {message}")


def finish_autosave(app: App, clean: bool = True) -> None:
    """The end of a run: wait for a pending write; a ``clean`` exit deletes the recovery files."""
    saver = getattr(app, "autosaver", None)
    if saver is not None:
        saver.close(discard=clean)
        report_autosave(app)
        app.autosaver = None  # type: ignore[attr-defined]


def recovery_offer(scene: str | os.PathLike[str] | None) -> Path | None:
    """The recovery file to offer when the workbench starts on ``scene`` (None: the default
    scene): the newest one a crashed run left behind for that scene (for an unnamed scene when
    none is given); the others are in File → Recover."""
    return offer_for(scene)


def recover(app: App, path: Path) -> None:
    """Open the recovery file as an unsaved scene (of the file it autosaved, if any), then delete it."""
    of = recovery_scene(path)
    open_session(app, path, remember=False)
    app.doc.view_state.pop("autosave_of", None)
    app.doc.path = of
    app.doc.dirty = True
    discard_recovery(path)
