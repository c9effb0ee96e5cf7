"""Benchmark: reading Peabody text. A generated 2 MB ``.fig`` (a 5,000-segment chain: three sites,
mass and centre of mass per segment, a 3-DOF joint with limits and displacement between each
pair) and the standard human's ``.fig`` (74 segments, 72 psurfs) as ``jackpy human`` writes it.

``peabody-read-2mb``: the reader (its fast path, :mod:`jackpy.peabody.fastread`) against the token
parser it falls back to (``parse_figures(..., fast=False)``), same file, same process. History:
the token parser replaced a reader with a token object per character (12.5 s here, 8x slower).

``peabody-write-2mb``: the writer's text of the same chain (no in-process baseline: the writer it
replaced asked ``np.allclose`` four times per site; measured with that code checked out, CPU time
at a load average near 9 on the shared 2-core machine: 14.2 s before, 9.1 s after, same bytes).
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
    from jackpy.peabody.fastread import parse_fast
    from jackpy.peabody.reader import parse_figures, read_figures, read_text

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "chain.fig"
        path.write_text(chain_fig_text())
        t = time_calls(lambda: read_figures(path), repeat=3 if quick else 5, warmup=1)
        base = time_calls(lambda: parse_figures(read_text(path), str(path), fast=False), repeat=3 if quick else 5)
        fast = parse_fast(read_text(path), str(path)) is not None
        return Result("peabody-read-2mb", t.median_ms, t.p90_ms, base.median_ms,
                      {"bytes": path.stat().st_size, "segments": 5000, "fast_path": fast})


def _write_chain(quick: bool) -> Result:
    from jackpy.peabody.reader import parse_figures
    from jackpy.peabody.writer import figures_to_text

    figures = parse_figures(chain_fig_text())
    t = time_calls(lambda: figures_to_text(figures), repeat=1 if quick else 3, warmup=0)
    return Result("peabody-write-2mb", t.median_ms, t.p90_ms, None, {"segments": 5000})


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


CASES = [Case("peabody-read-2mb", _read_chain, "read a generated 2 MB .fig (5,000-segment chain) vs the token parser"),
         Case("peabody-write-2mb", _write_chain, "write the 2 MB chain's .fig text"),
         Case("peabody-read-human", _read_human, "read the standard human's .fig (+ 72 psurfs) and restore it")]
