"""The window's side of sessions: save, open, new scene, CAD import, autosave and recovery for an
:class:`~jackpy.ui.app.App`. The file format and everything headless are
:mod:`jackpy.document.session`'s (re-exported here); these add the camera and the log.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

from jackpy.document import Document
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
    if remember:
        return app.doc.save(path)
    return doc_session.save(app.doc, path)


def open_session(app: App, path: str | os.PathLike[str]) -> None:
    """Replace the app's document with the one saved at ``path``."""
    doc = Document.open(path)
    doc.log[:0] = app.log
    app.set_document(doc)


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
    """Write the recovery file (without changing the session's own path)."""
    save_session(app, recovery_path(), remember=False)


def recover(app: App, path: Path) -> None:
    """Open the recovery file as an unsaved scene, then delete it."""
    open_session(app, path)
    app.doc.path = None
    app.doc.dirty = True
    discard_recovery(path)
