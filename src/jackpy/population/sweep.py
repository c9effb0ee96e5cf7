"""Run a study over many bodies: on a local process pool (default: every core) or a Dask cluster.

Bodies travel as parameters (:class:`~jackpy.population.generate.Body`: sex, targets, SASS
overrides, a few hundred bytes); every worker builds the figures itself. The scene and the study
travel once per worker (a pickled :class:`~jackpy.population.evaluate.SweepContext`: the pool's
initializer, or one broadcast ``scatter`` on Dask). Rows are appended to the output folder as their
chunk finishes (:mod:`jackpy.population.journal`), so Ctrl+C keeps every finished row (the chunks
already running finish and are kept too; a second Ctrl+C stops at once) and ``resume=True``
evaluates only the missing bodies. Each body's row depends on nothing but the body and the context,
so every executor, worker count and chunking gives the same table.
"""

from __future__ import annotations

import math
import os
import signal
import sys
import time
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from jackpy.population.evaluate import SweepContext, columns, evaluate_chunk, init_worker
from jackpy.population.generate import Body
from jackpy.population.journal import Journal, SweepError


@dataclass
class SweepResult:
    """The rows (index order), the columns, whether the sweep ran to the end, and the folder."""

    rows: list[dict[str, Any]]
    columns: list[str]
    complete: bool
    folder: Path
    seconds: float = 0.0
    evaluated: int = 0


class Progress:
    """A one-line progress bar with rate and ETA on a stream (default stderr), at most 5 updates/s."""

    def __init__(self, total: int, done: int = 0, stream=None, enabled: bool = True) -> None:
        self.total, self.done, self.start_done = total, done, done
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.t0 = time.perf_counter()
        self._last = 0.0

    def update(self, n: int) -> None:
        self.done += n
        now = time.perf_counter()
        if self.enabled and (now - self._last > 0.2 or self.done >= self.total):
            self._last = now
            self.stream.write("\r" + self.line(now) + ("\n" if self.done >= self.total else ""))
            self.stream.flush()

    def line(self, now: float | None = None) -> str:
        elapsed = (now or time.perf_counter()) - self.t0
        rate = (self.done - self.start_done) / elapsed if elapsed > 0 else 0.0
        left = (self.total - self.done) / rate if rate > 0 else math.inf
        eta = "--:--" if not math.isfinite(left) else f"{int(left // 60):d}:{int(left % 60):02d}"
        width = 30
        filled = int(width * self.done / max(self.total, 1))
        return (f"[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} bodies "
                f"{rate:.1f}/s ETA {eta}")


def chunks(bodies: list[Body], size: int) -> Iterator[list[dict]]:
    for k in range(0, len(bodies), size):
        yield [b.to_dict() for b in bodies[k:k + size]]


def chunk_size(n: int, workers: int) -> int:
    """Small enough to balance and to lose little on Ctrl+C, large enough to amortise dispatch."""
    return max(1, min(16, math.ceil(n / max(workers * 8, 1))))


def run_sweep(ctx: SweepContext, bodies: list[Body], folder: str | os.PathLike, *, manifest: dict | None = None,
              workers: int | None = None, client: Any = None, scheduler: str | None = None, resume: bool = False,
              progress: bool = True, on_rows: Callable[[list[dict]], None] | None = None) -> SweepResult:
    """Evaluate ``bodies`` (or, with ``resume``, the bodies of ``folder`` not yet done) and write the
    per-body table. ``client`` (a ``dask.distributed.Client``) or ``scheduler`` (``tcp://HOST:8786``)
    runs on Dask; else a local pool of ``workers`` processes (default: every core; 0 = in this
    process). Raises KeyboardInterrupt after keeping the finished rows when interrupted."""
    journal = Journal(folder)
    cols = columns(ctx.study)
    if resume:
        saved = journal.manifest()
        if saved.get("columns") != cols:
            raise SweepError(f"{folder}: the sweep there has other criteria; resume it with its own study")
        bodies = journal.bodies()
        done = journal.finished(cols)
    else:
        journal.start({**(manifest or {}), "columns": cols, "bodies": len(bodies)}, bodies)
        done = {}
    todo = [b for b in bodies if b.index not in done]
    t0 = time.perf_counter()
    bar = Progress(len(bodies), len(done), enabled=progress)

    def keep(rows: list[dict]) -> None:
        journal.append(cols, rows)
        done.update({r["index"]: r for r in rows})
        bar.update(len(rows))
        if on_rows is not None:
            on_rows(rows)

    if todo:
        if client is not None or scheduler is not None:
            _run_dask(ctx, todo, keep, client, scheduler)
        else:
            _run_local(ctx, todo, keep, (os.cpu_count() or 1) if workers is None else workers)
    rows = [done[i] for i in sorted(done)]
    journal.write_table(cols, rows)
    return SweepResult(rows, cols, len(rows) == len(bodies), journal.folder, time.perf_counter() - t0, len(todo))


def _ignore_sigint(payload: bytes) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    init_worker(payload)


def _run_local(ctx: SweepContext, todo: list[Body], keep: Callable[[list[dict]], None], workers: int) -> None:
    if workers <= 0:
        for chunk in chunks(todo, 1):
            keep(evaluate_chunk(ctx, chunk))
        return
    payload = ctx.to_bytes()
    pool = ProcessPoolExecutor(max_workers=workers, initializer=_ignore_sigint, initargs=(payload,))
    pending = {pool.submit(evaluate_chunk, None, c) for c in chunks(todo, chunk_size(len(todo), workers))}
    try:
        while pending:
            finished, pending = wait(pending, return_when=FIRST_COMPLETED)
            for f in finished:
                keep(f.result())
    except KeyboardInterrupt:
        for f in pending:
            f.cancel()
        running = [f for f in pending if not f.cancelled()]
        try:  # the chunks already running finish and are kept
            for f in running:
                keep(f.result())
        except KeyboardInterrupt:
            pass
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown(wait=True)


def _run_dask(ctx: SweepContext, todo: list[Body], keep: Callable[[list[dict]], None], client: Any,
              scheduler: str | None) -> None:
    try:
        from dask.distributed import Client, as_completed
    except ImportError:
        raise SweepError("Dask is not installed: pip install 'jackpy[cluster]' (dask distributed)") from None
    own = client is None
    if own:
        try:
            client = Client(scheduler, timeout="20s")
        except OSError as exc:
            raise SweepError(f"cannot reach the Dask scheduler at {scheduler}: {exc}") from None
    try:
        workers = max(len(client.scheduler_info().get("workers", {})), 1)
        payload = client.scatter(ctx.to_bytes(), broadcast=True)
        futures = [client.submit(evaluate_chunk, payload, c, pure=False)
                   for c in chunks(todo, chunk_size(len(todo), workers))]
        try:
            for f in as_completed(futures):
                keep(f.result())
        except KeyboardInterrupt:  # finished chunks are kept already
            client.cancel([f for f in futures if not f.done()])
            raise
    finally:
        if own:
            client.close()
