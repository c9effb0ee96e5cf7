"""Recovery files: each scene's autosave, written on a background thread.

Every scene has its own recovery file in ``$JACKPY_HOME/recovery/`` (default ``~/.jackpy``):
``NAME-HASH.env`` for a scene with a file (``NAME`` its stem, ``HASH`` the first 12 hex digits of
the SHA-1 of its resolved path), ``untitled-PID.env`` for an unnamed scene of process ``PID``. The
file's session line names the scene it is the autosave of (``view.autosave_of``). While a run
autosaves a file it holds an ``flock`` on ``NAME.lock`` beside it (a second workbench on the same
scene writes ``NAME-HASH-PID.env``); a recovery file whose lock no live process holds is an
*orphan*: the work of a run that crashed or was killed. A clean exit deletes the run's recovery
files; so does a save (the scene's own file then holds the work).

The single ``recovery.env`` of earlier versions is read as one more orphan (its session line names
its scene) until it is recovered or discarded.

:class:`Autosaver` takes a :func:`~jackpy.document.session.snapshot` of the document on the
caller's thread (about 30 ms for the default scene) and serialises and writes it on its one worker
thread (about 0.3 s for the default scene once its surfaces' text is cached, 0.7 s the first time; see
docs/workbench.md), one write at a time, atomically (:func:`jackpy.document.session.write`).
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import re
from concurrent.futures import Future, ThreadPoolExecutor
from pathlib import Path
from typing import TYPE_CHECKING, Any

from jackpy.document import session
from jackpy.errors import JackpyError

try:
    import fcntl
except ImportError:  # (Windows: no locks, every recovery file counts as an orphan)
    fcntl = None  # type: ignore[assignment]

if TYPE_CHECKING:
    from jackpy.document.document import Document

LEGACY_NAME = "recovery.env"
"""The one recovery file of earlier versions, read once (migration)."""
_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")


def recovery_dir() -> Path:
    """``$JACKPY_HOME/recovery`` (default ``~/.jackpy/recovery``)."""
    return Path(os.environ.get("JACKPY_HOME", Path.home() / ".jackpy")) / "recovery"


def recovery_path(scene: str | os.PathLike[str] | None = None) -> Path:
    """The recovery file of ``scene`` (``NAME-HASH.env``), of this process's unnamed scene for None
    (``untitled-PID.env``)."""
    if scene is None:
        return recovery_dir() / f"untitled-{os.getpid()}.env"
    resolved = Path(scene).resolve()
    digest = hashlib.sha1(str(resolved).encode("utf-8", "surrogateescape")).hexdigest()[:12]
    name = _UNSAFE.sub("_", resolved.stem)[:40] or "scene"
    return recovery_dir() / f"{name}-{digest}.env"


def lock_path(path: Path) -> Path:
    """The lock a running autosaver of ``path`` holds: ``NAME.lock`` beside ``NAME.env``."""
    return Path(path).with_suffix(".lock")


def is_orphan(path: Path) -> bool:
    """Whether no live process holds the lock of recovery file ``path`` (its run is gone)."""
    lock = lock_path(path)
    if fcntl is None or not lock.is_file():
        return True
    try:
        fd = os.open(lock, os.O_RDONLY)
    except OSError:
        return True
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return True
    except BlockingIOError:
        return False
    finally:
        os.close(fd)  # (releases the probe's lock)


def orphans() -> list[Path]:
    """The recovery files of runs that are gone, newest first (the old single file included)."""
    folder = recovery_dir()
    try:
        found = [p for p in folder.glob("*.env") if p.is_file() and is_orphan(p)]
    except OSError:
        return []
    return sorted(found, key=lambda p: p.stat().st_mtime, reverse=True)


def recovery_scene(path: Path) -> Path | None:
    """The scene a recovery file is the autosave of (None: an unnamed scene, or unreadable)."""
    path = Path(path)
    try:
        return _scene_of(path, path.stat().st_mtime_ns)
    except OSError:
        return None


@functools.lru_cache(maxsize=64)
def _scene_of(path: Path, mtime_ns: int) -> Path | None:
    try:
        found = session._session_line(path)
        data = json.loads(found[0]) if found else {}
        of = (data.get("view") or {}).get("autosave_of")
    except (JackpyError, ValueError, AttributeError):
        return None
    return Path(of) if isinstance(of, str) else None


def offer_for(scene: str | os.PathLike[str] | None) -> Path | None:
    """The newest orphaned recovery of ``scene`` (None: of an unnamed scene), to offer when the
    workbench starts on it."""
    want = Path(scene).resolve() if scene is not None else None
    return next((p for p in orphans() if recovery_scene(p) == want), None)


def discard_recovery(path: Path) -> None:
    """Delete a recovery file and what it names (after recovering it, declining it, a clean exit)."""
    path = Path(path)
    for p in (path, session.sidecar_path(path)):
        p.unlink(missing_ok=True)
    session.remove_leftovers(path, legacy_in_use=False)


class Autosaver:
    """Writes one document's recovery file in the background: :meth:`save` snapshots on the
    caller's thread and returns at once; one worker thread writes, one write at a time."""

    def __init__(self) -> None:
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="jackpy-autosave")
        self._locks: dict[Path, int] = {}  # recovery file → the fd holding its lock
        self._target: Path | None = None
        self._scene: Path | None = None
        self._pending: Future[Any] | None = None
        self._done: list[Future[Any]] = []
        self.written: set[Path] = set()
        """Every recovery file this autosaver has written (and not deleted)."""

    @property
    def busy(self) -> bool:
        """A write is queued or running."""
        return self._pending is not None and not self._pending.done()

    def save(self, doc: Document, scene: Path | None) -> Future[Any]:
        """Autosave ``doc`` (the autosave of ``scene``, None: unnamed) in the background; returns
        the write's future (its result: the file). While the previous write (or drop) still runs,
        nothing new is taken: that one's future is returned."""
        if self._pending is not None and not self._pending.done():
            return self._pending
        scene = Path(scene).resolve() if scene is not None else None
        if self._target is None or scene != self._scene:
            self._target, self._scene = self._claim(scene), scene
        stale = [p for p in self.written if p != self._target]
        snap = session.snapshot(doc, {"autosave_of": str(scene) if scene is not None else None})
        self._pending = self._pool.submit(self._write, snap, self._target, stale)
        self._done.append(self._pending)
        return self._pending

    def _write(self, snap: session.Snapshot, target: Path, stale: list[Path]) -> Path:
        """(worker) The snapshot to ``target``, then the files of scenes left behind deleted."""
        written = session.write(snap, target)
        self.written.add(written)
        for old in stale:
            discard_recovery(old)
            self.written.discard(old)
        return written

    def _claim(self, scene: Path | None) -> Path:
        """The recovery file for ``scene``, locked: the scene's own name, or ``NAME-PID.env`` when
        a live run holds that one."""
        base = recovery_path(scene)
        for path in (base, base.with_name(f"{base.stem}-{os.getpid()}.env")):
            if path in self._locks or self._lock(path):
                return path
        return path  # (no lock to be had: write anyway, the file is still this run's work)

    def _lock(self, path: Path) -> bool:
        if fcntl is None:
            return True
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            fd = os.open(lock_path(path), os.O_RDWR | os.O_CREAT, 0o644)
        except OSError:
            return True  # no folder to be had: the write fails too, and reports it
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            return False
        self._locks[path] = fd
        return True

    def drop(self) -> Future[None]:
        """The work is saved: delete this autosaver's recovery files (after a pending write)."""
        def drop_all() -> None:
            for p in list(self.written):
                discard_recovery(p)
                self.written.discard(p)

        self._pending = self._pool.submit(drop_all)
        self._done.append(self._pending)
        return self._pending

    def failures(self) -> list[str]:
        """What went wrong in the writes finished since the last call (one line each)."""
        finished = [f for f in self._done if f.done()]
        self._done = [f for f in self._done if not f.done()]
        return [f"{exc}" for f in finished if (exc := f.exception()) is not None]

    def close(self, discard: bool = True) -> None:
        """Wait for a pending write; with ``discard`` (a clean exit) delete the recovery files;
        then release the locks (without ``discard`` the files stay as orphans for the next run)."""
        self._pool.shutdown(wait=True)
        if discard:
            for p in list(self.written):
                discard_recovery(p)
            self.written.clear()
        for path, fd in self._locks.items():
            if discard or path not in self.written:
                lock_path(path).unlink(missing_ok=True)
            os.close(fd)
        self._locks.clear()
