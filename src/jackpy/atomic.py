"""Atomic file writes: write a temporary file in the target's directory, then ``os.replace`` it.

A reader never sees a half-written file, and an error while writing leaves the old file intact.

Temporary files are named ``.NAME.XXXXXXXX.tmp`` beside ``NAME`` and held under an exclusive
``flock`` while they are written. A process killed mid-write leaves its temporary file behind, but
its lock dies with it, so :func:`clean_stale_temps` (run by every write, and by openers such as
the session loader) removes exactly the leftovers of dead writers and never a file another
process is still writing. Where ``flock`` does not exist, leftovers older than
:data:`STALE_SECONDS` are removed instead.
"""

from __future__ import annotations

import os
import re
import tempfile
import time
from pathlib import Path

try:
    import fcntl
except ImportError:  # (Windows)
    fcntl = None  # type: ignore[assignment]

#: without flock: age (s) after which a temporary file of ours is taken as a dead writer's
STALE_SECONDS = 600.0


def _default_mode() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


_NEW_FILE_MODE = _default_mode()


def _temp_pattern(name: str) -> re.Pattern[str]:
    """Names :func:`tempfile.mkstemp` gives our temporary files of ``name`` (8 random characters)."""
    return re.compile(re.escape(f".{name}.") + r"[a-z0-9_]{8}" + re.escape(".tmp") + r"\Z")


def clean_stale_temps(path: str | os.PathLike[str]) -> list[Path]:
    """Remove the temporary files an interrupted write of ``path`` left (only ours: the exact
    naming of :func:`atomic_write_bytes`, no live writer holding it); returns those removed."""
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    pattern = _temp_pattern(target.name)
    removed = []
    try:
        names = [n for n in os.listdir(directory) if pattern.match(n)]
    except OSError:
        return removed
    for name in names:
        tmp = directory / name
        try:
            if fcntl is None:
                if time.time() - tmp.stat().st_mtime < STALE_SECONDS:
                    continue
                tmp.unlink()
            else:
                fd = os.open(tmp, os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0))
                try:
                    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    tmp.unlink()
                except BlockingIOError:
                    continue  # a live writer holds it
                finally:
                    os.close(fd)
        except OSError:
            continue
        removed.append(tmp)
    return removed


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> None:
    """Write ``data`` to ``path`` atomically (temp file in the same directory + ``os.replace``).

    An existing file keeps its permission bits; a new one gets the usual ``0o666 & ~umask``.
    Leftover temporary files of earlier interrupted writes of ``path`` are removed first.
    """
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    clean_stale_temps(target)
    mode = target.stat().st_mode & 0o7777 if target.exists() else _NEW_FILE_MODE
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=directory)
    try:
        if fcntl is not None:
            fcntl.flock(fd, fcntl.LOCK_EX)  # (released when the file is closed or we die)
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
            os.chmod(tmp, mode)
            os.replace(tmp, target)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise


def atomic_write_text(path: str | os.PathLike[str], text: str, encoding: str = "utf-8") -> None:
    """Write ``text`` to ``path`` atomically (see :func:`atomic_write_bytes`); ``\\n`` line ends."""
    atomic_write_bytes(path, text.encode(encoding))
