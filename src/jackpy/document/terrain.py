"""The scene's terrain (Sims 1987, Ch. 8): kept in the document, saved with it, undone with it.

A document has at most one terrain (:class:`jackpy.locomotion.terrain.Terrain`). It lives in
:attr:`Document.extras` under ``"terrain"`` as its JSON form (:meth:`Terrain.to_dict`), so the
session file carries it (every height exactly: JSON floats round-trip), undo and redo restore it,
and nothing else in the document needs to know about it. :func:`terrain_of` gives the object,
rebuilt only when the stored data changed (a load, an undo, an open).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from jackpy.locomotion.terrain import Terrain
from jackpy.locomotion.terrain import load as load_terrain_file

if TYPE_CHECKING:
    from jackpy.document.document import Document

KEY = "terrain"
_CACHE = "_terrain_cache"


def terrain_of(doc: "Document") -> Terrain | None:
    """The document's terrain, or None."""
    data = getattr(doc, "extras", {}).get(KEY)  # (extras: Document's tool data, saved and undone)
    if data is None:
        return None
    cached = doc.__dict__.get(_CACHE)
    if cached is not None and cached[0] is data:
        return cached[1]
    terrain = Terrain.from_dict(data, f"{doc.path or 'document'}: extras.terrain")
    doc.__dict__[_CACHE] = (data, terrain)
    return terrain


def set_terrain(doc: "Document", terrain: Terrain | None, label: str | None = None) -> None:
    """Give the document ``terrain`` (None removes it) as one undoable command."""

    def act() -> None:
        if terrain is None:
            doc.extras.pop(KEY, None)
            doc.__dict__.pop(_CACHE, None)
            return
        data = terrain.to_dict()
        doc.extras[KEY] = data
        doc.__dict__[_CACHE] = (data, terrain)

    doc.command(label or ("remove terrain" if terrain is None else f"set terrain {terrain.name}"), act)
    doc.changed = True


def load_terrain(doc: "Document", path: str | os.PathLike[str]) -> Terrain:
    """Read a terrain file (``.json`` grid or ``.png`` heightmap, see
    :func:`jackpy.locomotion.terrain.load`) into the document (undoable); ParseError for a bad file."""
    terrain = load_terrain_file(path)
    set_terrain(doc, terrain, f"load terrain {os.path.basename(str(path))}")
    return terrain
