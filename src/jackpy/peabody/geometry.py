"""Polygon meshes attached to segments (psurf geometry), in metres in the segment's base frame."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Mesh:
    """A triangle mesh: ``vertices`` (n,3) metres, ``faces`` (m,3) vertex indices."""

    vertices: np.ndarray
    faces: np.ndarray

    def __post_init__(self) -> None:
        self.vertices = np.asarray(self.vertices, dtype=float).reshape(-1, 3)
        self.faces = np.asarray(self.faces, dtype=np.int64).reshape(-1, 3)

    def transformed(self, t: np.ndarray) -> "Mesh":
        """This mesh with every vertex mapped by the 4x4 transform ``t``."""
        v = self.vertices @ t[:3, :3].T + t[:3, 3]
        faces = self.faces if np.linalg.det(t[:3, :3]) > 0 else self.faces[:, ::-1]
        return Mesh(v, faces.copy())

    def vertex_normals(self) -> np.ndarray:
        """Area-weighted unit vertex normals (n,3)."""
        v, f = self.vertices, self.faces
        fn = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
        vn = np.zeros_like(v)
        for k in range(3):
            np.add.at(vn, f[:, k], fn)
        n = np.linalg.norm(vn, axis=1, keepdims=True)
        return vn / np.where(n > 0, n, 1.0)

    def bounds(self) -> np.ndarray:
        """(2,3) array of min and max corners; zeros for an empty mesh."""
        if len(self.vertices) == 0:
            return np.zeros((2, 3))
        return np.stack([self.vertices.min(axis=0), self.vertices.max(axis=0)])


class SourcePosition:
    """Where a name was written in a text file: ``file:line:column``, computed when asked (so a
    reader pays nothing for positions no error needs). Copies share it (it is immutable).
    ``index`` counts tokens; :meth:`at_offset` makes one from a character offset instead."""

    __slots__ = ("file", "_text", "_index", "_offset", "_where")

    def __init__(self, file: str, text: str, index: int) -> None:
        self.file, self._text, self._index = file, text, index
        self._offset = -1
        self._where: str | None = None

    @classmethod
    def at_offset(cls, file: str, text: str, offset: int) -> SourcePosition:
        """The position of character ``offset`` (0-based) of ``text``."""
        pos = cls(file, text, -1)
        pos._offset = offset
        return pos

    def text(self) -> str:
        """``file:line:column`` of the name."""
        if self._where is None:
            from jackpy.peabody.lexer import offset_position, token_position

            t = self._text
            line, col = offset_position(t, self._offset) if self._offset >= 0 else token_position(t, self._index)
            self._where, self._text = f"{self.file}:{line}:{col}", ""
        return self._where

    def __deepcopy__(self, memo: dict) -> SourcePosition:
        return self

    def __copy__(self) -> SourcePosition:
        return self


@dataclass
class Psurf:
    """A segment's geometry reference: a file name times a transform (``"leg.pss" * scale(...)``).

    ``source`` is the file name as written in the Peabody file (relative to that file), ``transform``
    the product of the transforms that follow it (metres), ``mesh`` the loaded mesh in the psurf's
    own frame, before ``transform`` (``None`` until loaded, or when the file was not found).
    """

    source: str
    transform: np.ndarray = field(default_factory=lambda: np.eye(4))
    mesh: Mesh | None = None
    scale_text: list[tuple[str, tuple[float, ...]]] = field(default_factory=list)
    #: where the file name was written (for errors about that file), when read from text
    origin: SourcePosition | None = field(default=None, compare=False, repr=False)

    def posed_mesh(self) -> Mesh | None:
        """The mesh in the segment frame (``transform`` applied), or ``None``."""
        return None if self.mesh is None else self.mesh.transformed(self.transform)
