"""Run in a child process by test_hostile_limits.py: read each hostile file given on the command
line, print one JSON line per file: the error (or None), seconds taken, and the process's peak
resident memory growth so far (MB) above the baseline after imports."""

from __future__ import annotations

import json
import resource
import sys
import time

import jackpy.body  # noqa: F401  (registers the human's drivers, imports what a real run has)
import trimesh  # noqa: F401
from jackpy.errors import JackpyError
from jackpy.peabody.reader import load
from jackpy.scene.cad import import_cad


def peak_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


base = peak_mb()
for path in sys.argv[1:]:
    start = time.perf_counter()
    try:
        if path.endswith((".fig", ".env")):
            load(path)
        else:
            import_cad(path)
        error = None
    except (JackpyError, OSError) as exc:
        error = f"{type(exc).__name__}: {exc}"
    print(json.dumps({"path": path, "error": error, "seconds": time.perf_counter() - start,
                      "grown_mb": peak_mb() - base}), flush=True)
