"""Benchmark: reading Peabody text. A generated 2 MB ``.fig`` (a 5,000-segment chain: three sites,
mass and centre of mass per segment, a 3-DOF joint with limits and displacement between each
pair) and the standard human's ``.fig`` (74 segments, 72 psurfs) as ``jackpy human`` writes it.

No in-process baseline: the reader it replaced (a token object per character, numpy ``allclose``
per site) is gone. Measured with the old code checked out, same file, same process kind, CPU time
on the shared 2-core machine at a load average near 10: old 12.5 s, new 1.5 s (8x).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from jackpy.bench.runner import Case, Result, time_calls


def chain_fig_text(segments: int = 5000) -> str:
    """A long chain figure, about 400 bytes per segment (2.0 MB at 5,000 segments)."""
    lines = ["figure big {"]
    for i in range(segments):
        lines.append(f"    segment s{i} {{ mass = 1.5kg; com = (1.25, 2.5, 3.75)cm; site base->location = "
                     "trans(0cm,0cm,0cm); site tip->location = rotx(12.5) * trans(10.123456cm,2.5cm,0.5cm); "
                     "site extra->location = rot(0.267261,0.534522,0.801784,33) * trans(1cm,2cm,3cm); }")
    for i in range(segments - 1):
        lines.append(f"    joint j{i} {{ connect s{i}.tip to s{i + 1}.base; type = R(z) * R(y) * R(x); "
                     "lower = (-90, -45, -30); upper = (90, 45, 30); displacement = (10, 5, 2.5); }")
    return "\n".join(lines + ["}"]) + "\n"


def _read_chain(quick: bool) -> Result:
    from jackpy.peabody.reader import read_figures

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "chain.fig"
        path.write_text(chain_fig_text())
        t = time_calls(lambda: read_figures(path), repeat=2 if quick else 5, warmup=1)
        return Result("peabody-read-2mb", t.median_ms, t.p90_ms, None,
                      {"bytes": path.stat().st_size, "segments": 5000})


def _read_human(quick: bool) -> Result:
    from jackpy.body.human import make_human
    from jackpy.body.saved import restore_human
    from jackpy.commands.human import write_human
    from jackpy.peabody.reader import read_figures

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "f5.fig"
        write_human(path, make_human("female", 5))

        def read() -> None:
            restore_human(read_figures(path)[0])

        t = time_calls(read, repeat=3 if quick else 20, warmup=1)
        return Result("peabody-read-human", t.median_ms, t.p90_ms, None, {"bytes": path.stat().st_size})


CASES = [Case("peabody-read-2mb", _read_chain, "read a generated 2 MB .fig (5,000-segment chain)"),
         Case("peabody-read-human", _read_human, "read the standard human's .fig (+ 72 psurfs) and restore it")]
