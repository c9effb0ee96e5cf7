"""Reading a user's JSON file (workplace scenes, session sidecars, sensor configurations, Flock
recordings) with errors a user can act on.

- bytes that are not UTF-8, JSON syntax errors, nesting too deep for Python's decoder and
  integers too long to convert all raise the caller's error class naming the file, line and
  column (``scene.json:3:15: expected ',' or '}'``);
- a value of the wrong shape raises it naming the file and the key path
  (``scene.json: objects[2].units: expected one of mm, cm, m, in, found 'km'``).

The checkers (:func:`obj`, :func:`num`, :func:`vector` ...) raise :class:`Invalid` with the key
path; :func:`schema_error` turns that into the caller's error class.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from jackpy.errors import JackpyError, ParseError


class Invalid(Exception):
    """A JSON value of the wrong shape at key path ``where`` (internal; see :func:`schema_error`)."""

    def __init__(self, where: str, message: str) -> None:
        self.where = where or "the top level"
        self.message = message
        super().__init__(f"{self.where}: {message}")


def schema_error(cls: type[JackpyError], file: str, exc: Invalid) -> JackpyError:
    """``file: key.path: message`` as an error of class ``cls`` (a ParseError without a position)."""
    if issubclass(cls, ParseError):
        return cls(f"{exc.where}: {exc.message}", file)
    return cls(f"{file}: {exc.where}: {exc.message}")


def position_error(cls: type[JackpyError], message: str, file: str, line: int, column: int) -> JackpyError:
    """``file:line:column: message`` as an error of class ``cls``."""
    if issubclass(cls, ParseError):
        return cls(message, file, line, column)
    return cls(f"{file}:{line}:{column}: {message}")


def decode(data: bytes, file: str, cls: type[JackpyError] = ParseError) -> str:
    """UTF-8 text of ``data``; the first byte that is not UTF-8 is an error at its line and column."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        before = data[:exc.start]
        raise position_error(cls, "expected UTF-8 text", file, before.count(b"\n") + 1,
                             exc.start - (before.rfind(b"\n") + 1) + 1) from None


def loads(text: str, file: str, cls: type[JackpyError] = ParseError, line: int = 1) -> Any:
    """Parse JSON ``text`` (found at ``line`` of ``file``); errors carry line and column."""
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise position_error(cls, f"expected JSON: {exc.msg}", file, line + exc.lineno - 1, exc.colno) from None
    except RecursionError:
        raise position_error(cls, "JSON nested too deeply", file, line, 1) from None
    except ValueError as exc:  # e.g. an integer of more than 4300 digits
        raise position_error(cls, f"expected JSON: {exc}", file, line, 1) from None


def load(path: str | os.PathLike[str], cls: type[JackpyError] = ParseError) -> Any:
    """Read and parse a JSON file (OSError, as raised, for a missing or unreadable file)."""
    file = str(path)
    return loads(decode(Path(path).read_bytes(), file, cls), file, cls)


# ------------------------------------------------------------------------- checkers
def key(where: str, name: str | int) -> str:
    """The key path of member ``name`` (a key, or an index) of the value at ``where``."""
    if isinstance(name, int):
        return f"{where}[{name}]"
    return f"{where}.{name}" if where else str(name)


def obj(v: Any, where: str) -> dict[str, Any]:
    if not isinstance(v, dict):
        raise Invalid(where, f"expected an object {{...}}, found {_kind(v)}")
    return v


def arr(v: Any, where: str) -> list[Any]:
    if not isinstance(v, list):
        raise Invalid(where, f"expected a list [...], found {_kind(v)}")
    return v


def required(d: dict[str, Any], name: str, where: str) -> Any:
    if name not in d:
        raise Invalid(key(where, name), "missing")
    return d[name]


def num(v: Any, where: str, lo: float | None = None, hi: float | None = None) -> float:
    """A finite number (not a boolean) within ``lo..hi``."""
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise Invalid(where, f"expected a number, found {_kind(v)}")
    try:
        x = float(v)
    except OverflowError:
        x = math.inf
    if not math.isfinite(x):
        raise Invalid(where, f"expected a finite number, found {_short(v)}")
    if (lo is not None and x < lo) or (hi is not None and x > hi):
        raise Invalid(where, f"expected a number in {_range(lo, hi)}, found {_short(v)}")
    return x


def integer(v: Any, where: str, lo: int | None = None, hi: int | None = None) -> int:
    """An integer (``3`` or ``3.0``, not a boolean) within ``lo..hi``."""
    if isinstance(v, bool) or not isinstance(v, (int, float)) or (isinstance(v, float) and not v.is_integer()):
        raise Invalid(where, f"expected an integer, found {_kind(v)}")
    n = int(v)
    if (lo is not None and n < lo) or (hi is not None and n > hi):
        raise Invalid(where, f"expected an integer in {_range(lo, hi)}, found {_short(v)}")
    return n


def string(v: Any, where: str, choices: Iterable[str] | None = None) -> str:
    if not isinstance(v, str):
        raise Invalid(where, f"expected a string, found {_kind(v)}")
    if choices is not None:
        choices = list(choices)
        if v not in choices:
            raise Invalid(where, f"expected one of {', '.join(choices)}, found {_short(v)}")
    return v


def boolean(v: Any, where: str) -> bool:
    if not isinstance(v, bool):
        raise Invalid(where, f"expected true or false, found {_kind(v)}")
    return v


def vector(v: Any, where: str, n: int) -> np.ndarray:
    """A list of ``n`` finite numbers."""
    items = arr(v, where)
    if len(items) != n:
        raise Invalid(where, f"expected {n} numbers, found {len(items)} values")
    return np.array([num(x, key(where, i)) for i, x in enumerate(items)], dtype=float)


def matrix(v: Any, where: str, rows: int, cols: int) -> np.ndarray:
    """A list of ``rows`` lists of ``cols`` finite numbers."""
    items = arr(v, where)
    if len(items) != rows:
        raise Invalid(where, f"expected {rows} rows of {cols} numbers, found {len(items)} values")
    return np.array([vector(r, key(where, i), cols) for i, r in enumerate(items)])


def _kind(v: Any) -> str:
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, dict):
        return "an object"
    if isinstance(v, list):
        return "a list"
    return _short(v)


def _short(v: Any) -> str:
    text = repr(v) if isinstance(v, str) else str(v) if isinstance(v, (int, float)) else type(v).__name__
    if isinstance(v, int) and not isinstance(v, bool) and abs(v) > 10**20:
        text = "a very long integer"
    return text if len(text) <= 40 else text[:37] + "..."


def _range(lo: float | None, hi: float | None) -> str:
    if lo is None:
        return f"..{hi:g}"
    if hi is None:
        return f"{lo:g}.."
    return f"{lo:g}..{hi:g}"
