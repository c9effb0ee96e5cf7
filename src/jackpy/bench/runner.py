"""Benchmark cases and their timing: medians, p90 and ratios against an in-process baseline."""

from __future__ import annotations

import importlib
import json
import pkgutil
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np


@dataclass
class Timing:
    """Per-call wall times in milliseconds."""

    samples_ms: np.ndarray

    @property
    def median_ms(self) -> float:
        return float(np.median(self.samples_ms))

    @property
    def p90_ms(self) -> float:
        return float(np.percentile(self.samples_ms, 90))


def time_calls(fn: Callable[[], Any], repeat: int = 200, warmup: int = 5) -> Timing:
    """Call ``fn`` ``warmup`` times untimed, then ``repeat`` times timed one by one."""
    for _ in range(warmup):
        fn()
    out = np.empty(repeat)
    for i in range(repeat):
        t0 = time.perf_counter()
        fn()
        out[i] = (time.perf_counter() - t0) * 1e3
    return Timing(out)


@dataclass
class Result:
    """One row of the benchmark table."""

    name: str
    median_ms: float
    p90_ms: float
    baseline_ms: float | None = None
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def ratio(self) -> float | None:
        """Baseline median over case median: >1 means faster than the baseline."""
        if self.baseline_ms is None or self.median_ms <= 0:
            return None
        return self.baseline_ms / self.median_ms

    def as_json(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "median_ms": self.median_ms,
            "p90_ms": self.p90_ms,
            "baseline_ms": self.baseline_ms,
            "ratio": self.ratio,
            "extra": self.extra,
        }


@dataclass
class Case:
    """A named benchmark: ``run(quick)`` returns its :class:`Result`."""

    name: str
    run: Callable[[bool], Result]
    description: str = ""


def all_cases() -> list[Case]:
    """Every case from every ``jackpy.bench.cases_*`` module, in module order."""
    import jackpy.bench as pkg

    cases: list[Case] = []
    for info in sorted(pkgutil.iter_modules(pkg.__path__), key=lambda m: m.name):
        if info.name.startswith("cases_"):
            module = importlib.import_module(f"jackpy.bench.{info.name}")
            cases.extend(getattr(module, "CASES", []))
    return cases


def format_row(r: Result) -> str:
    base = f"{r.baseline_ms:10.3f}" if r.baseline_ms is not None else f"{'-':>10}"
    ratio = f"{r.ratio:7.1f}x" if r.ratio is not None else f"{'-':>8}"
    extra = " ".join(f"{k}={_fmt(v)}" for k, v in r.extra.items())
    return f"{r.name:<22}{r.median_ms:10.3f}{r.p90_ms:10.3f}{base}{ratio}  {extra}"


def header() -> str:
    return f"{'case':<22}{'median ms':>10}{'p90 ms':>10}{'base ms':>10}{'ratio':>8}  extra"


def _fmt(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def print_json(r: Result) -> None:
    print(json.dumps(r.as_json()), flush=True)
