"""Where files named inside a scene may be read from: containment and size limits.

A Peabody file names other files (``include "chair.fig";``, ``psurf = "leg.pss";``). By default they
must resolve (symbolic links followed) inside the folder of the file the user opened, or inside a
*library* folder: the ``JACKPY_LIBRARY`` environment variable (folders separated by ``os.pathsep``)
or the ``library`` argument of the readers. Anything else is refused with the position of the
name, without reading the file; ``allow_outside=True`` (the command-line ``--allow-outside``, or
``JACKPY_ALLOW_OUTSIDE=1``) reads it and records it in :attr:`PathPolicy.outside`, which the
commands report.

Every file read must be a regular file (never a FIFO, device or folder) of at most a size limit.
"""

from __future__ import annotations

import errno
import os
import stat
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path

#: largest Peabody text file (.fig, .env) read, bytes
MAX_TEXT_BYTES = 16 * 2**20
#: largest psurf/mesh file read, bytes
MAX_MESH_BYTES = 256 * 2**20


def env_flag(name: str) -> bool:
    """True when environment variable ``name`` is set to 1, true, yes or on."""
    return os.environ.get(name, "").strip().lower() in ("1", "true", "yes", "on")


def library_folders(extra: Iterable[str | os.PathLike[str]] | None = None) -> list[Path]:
    """The library folders: ``extra`` then those of ``JACKPY_LIBRARY``."""
    names = [str(p) for p in (extra or [])]
    names += [p for p in os.environ.get("JACKPY_LIBRARY", "").split(os.pathsep) if p.strip()]
    return [Path(n).expanduser() for n in names]


@dataclass
class PathPolicy:
    """The folders referenced files may come from, and whether others are allowed (and noted)."""

    roots: list[Path]
    allow_outside: bool = False
    outside: list[str] = field(default_factory=list)

    @classmethod
    def for_file(cls, path: str | os.PathLike[str], *, allow_outside: bool | None = None,
                 library: Iterable[str | os.PathLike[str]] | None = None) -> PathPolicy:
        """The policy for a scene opened at ``path``: its folder and the library folders;
        ``allow_outside`` defaults to ``JACKPY_ALLOW_OUTSIDE``."""
        return cls.for_folder(Path(path).parent, allow_outside=allow_outside, library=library)

    @classmethod
    def for_folder(cls, folder: str | os.PathLike[str], *, allow_outside: bool | None = None,
                   library: Iterable[str | os.PathLike[str]] | None = None) -> PathPolicy:
        allow = env_flag("JACKPY_ALLOW_OUTSIDE") if allow_outside is None else allow_outside
        roots = [Path(folder or ".")] + library_folders(library)
        return cls([_resolved(r) for r in roots], allow)

    def inside(self, path: str | os.PathLike[str]) -> bool:
        """True when ``path`` (resolved) lies in one of the roots."""
        real = _resolved(Path(path))
        return any(real == r or r in real.parents for r in self.roots)

    def permit(self, path: str | os.PathLike[str]) -> str | None:
        """``None`` when ``path`` may be read (noting it when it lies outside), else the reason."""
        if self.inside(path):
            return None
        if self.allow_outside:
            note = str(_resolved(Path(path)))
            if note not in self.outside:
                self.outside.append(note)
            return None
        return ("outside the scene's folder and the library path (JACKPY_LIBRARY); "
                "use --allow-outside to read it")


def _resolved(p: Path) -> Path:
    try:
        return p.resolve()
    except (OSError, RuntimeError, ValueError):
        return Path(os.path.abspath(p))


def regular_file_size(path: str | os.PathLike[str], limit: int) -> int:
    """The size of ``path`` if it is a regular file of at most ``limit`` bytes; otherwise OSError
    (a FIFO or device is refused without opening it, so nothing blocks)."""
    try:
        info = os.stat(path)
    except ValueError:  # an embedded NUL byte
        raise OSError(errno.EINVAL, "not a valid file name") from None
    if stat.S_ISDIR(info.st_mode):
        raise IsADirectoryError(errno.EISDIR, "a folder, not a file", str(path))
    if not stat.S_ISREG(info.st_mode):
        raise OSError(errno.EINVAL, "not a regular file (a FIFO, device or socket)", str(path))
    if info.st_size > limit:
        raise OSError(errno.EFBIG, f"file too large ({info.st_size / 2**20:.1f} MB; at most "
                                   f"{limit / 2**20:g} MB)", str(path))
    return info.st_size


def read_limited(path: str | os.PathLike[str], limit: int) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes (see :func:`regular_file_size`);
    a file that grows past the limit while it is read is refused too."""
    regular_file_size(path, limit)
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):  # swapped for a FIFO after the check
            raise OSError(errno.EINVAL, "not a regular file", str(path))
        data = f.read(limit + 1)
    if len(data) > limit:
        raise OSError(errno.EFBIG, f"file too large (at most {limit / 2**20:g} MB)", str(path))
    return data
