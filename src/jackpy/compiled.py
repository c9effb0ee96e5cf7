"""The one numba switch, the registry of compiled kernels, and their compilation ahead of use.

jackpy's hot loops (forward kinematics, the goals' rows, the chain rule through the joint groups, the
spine driver, the bounded step's subproblems) are compiled by numba and cached on disk
(``__pycache__`` beside the source, or ``NUMBA_CACHE_DIR``). A numba dispatcher compiles on its first
call: on a fresh install that is seconds (a priority problem's first bound group row compiled the
row step inside a solve: 9.5 s), and even from a warm cache a kernel's first call loads it (tens
of ms), either of which would land inside a workbench frame or a live sensor frame. So every kernel
is declared here with the one signature the hot path calls it with (C-contiguous float64, int64
and bool arrays), and :func:`warm` compiles or loads them all before the first frame: ``jackpy
open`` (whose frames also run the live sensor drive) and ``jackpy bench`` call it, a script may too.
A call with other types still works: numba compiles that signature when it is met.

``JACKPY_NO_JIT=1`` in the environment (or numba not installed) turns every kernel off: each
module then runs its numpy reference, and :func:`warm` does nothing.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

try:
    if os.environ.get("JACKPY_NO_JIT"):
        raise ImportError("disabled by JACKPY_NO_JIT")
    import numba
except ImportError:  # pragma: no cover - numba is optional
    numba = None

AVAILABLE = numba is not None

#: (qualified name, dispatcher, signature or None for a callee compiled inline into its callers)
KERNELS: list[tuple[str, Any, str | None]] = []

#: the modules that declare kernels (imported by :func:`warm`, so each registers its own)
KERNEL_MODULES = ("jackpy.peabody.kinematics_jit", "jackpy.body.spine_kernel", "jackpy.ik.goals.kernels",
                  "jackpy.ik.goals.base", "jackpy.ik.chain_rule", "jackpy.ik.bounded_step")

#: after this long a :func:`warm` that is still compiling says so (on a warm cache it takes less)
ANNOUNCE_AFTER_S = 1.0


def kernel(func: Callable, signature: str | None) -> Any:
    """``func`` compiled by numba (cached on disk, the GIL released), or None without numba.

    ``signature``: its argument types as numba writes them, e.g. ``"(float64[:, ::1], int64)"``,
    the one the hot path calls (compiled ahead by :func:`warm`); None for a helper called only
    from other kernels (numba compiles it into them)."""
    if numba is None:
        return None
    dispatcher = numba.njit(cache=True, nogil=True)(func)
    KERNELS.append((f"{func.__module__}.{func.__name__}", dispatcher, signature))
    return dispatcher


@dataclass
class WarmReport:
    """What :func:`warm` did: kernels compiled afresh and loaded from the disk cache, and seconds."""

    compiled: int = 0
    loaded: int = 0
    seconds: float = 0.0

    def __str__(self) -> str:
        return f"{self.compiled} kernels compiled, {self.loaded} loaded from the cache in {self.seconds:.2f} s"


def warm(announce: Callable[[str], None] | None = None) -> WarmReport:
    """Compile (first run) or load (later runs) every declared kernel for its signature.

    ``announce`` is called once with a line for the user if this is still going after
    :data:`ANNOUNCE_AFTER_S` seconds (a fresh install's first run); a second call costs nothing."""
    import importlib

    report = WarmReport()
    if numba is None:
        return report
    for name in KERNEL_MODULES:
        importlib.import_module(name)
    start = time.perf_counter()
    timer = None
    if announce is not None:
        timer = threading.Timer(ANNOUNCE_AFTER_S, announce,
                                ("compiling jackpy's numerical kernels (first run only, about a minute at most)",))
        timer.daemon = True
        timer.start()
    try:
        for _, dispatcher, signature in KERNELS:
            if signature is None or dispatcher.signatures:
                continue
            dispatcher.compile(signature)
            stats = dispatcher.stats
            if sum(stats.cache_hits.values()):
                report.loaded += 1
            else:
                report.compiled += 1
    finally:
        if timer is not None:
            timer.cancel()
    report.seconds = time.perf_counter() - start
    return report


def announce_on_stderr(line: str) -> None:
    """An ``announce`` for :func:`warm` on the command line."""
    print(f"jackpy: {line}", file=sys.stderr, flush=True)
