"""Shared mutation strategies for the parser fuzz tests (tests/fuzz/test_fuzz_*.py).

A seed file is split into pieces (whitespace, words, numbers, single characters); a mutation
inserts, deletes, replaces or duplicates pieces, or truncates the text; a byte mutation flips,
inserts or deletes raw bytes (so the result may not be UTF-8). The property every test checks is
the same: reading the mutated file either succeeds or raises a :class:`jackpy.errors.JackpyError`
whose message is one line naming the file -- never another exception, never a hang.
"""

from __future__ import annotations

import re

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from jackpy.errors import JackpyError, ParseError

#: bounded settings for every fuzz test: no deadline (first calls import trimesh...), no database
FUZZ = settings(max_examples=150, deadline=None, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])

#: characters and tokens that tend to break parsers
NASTY = ["\x00", "\\", '"', "'", "\n", "\r", "\t", "\x0b", "\x0c", "\x1c", "\x85", "\u2028", "\ufeff", "é", "٣",
         "{", "}", "[", "]", "(", ")", ",", ":", ";", "=", "*", ".", "-", "+", "/*", "*/", "//", "#",
         "0", "-0", "1e308", "1e999", "-1e999", "NaN", "Infinity", "-Infinity", "nan", "inf", "null", "true",
         "false", "[]", "{}", '""', "9" * 5000, "1." + "0" * 400, "-1", "65536", "32768", "1.5"]

_PIECES = re.compile(r"\s+|[A-Za-z_][A-Za-z0-9_]*|[0-9.]+(?:[eE][+-]?[0-9]+)?|\S")


def pieces(text: str) -> list[str]:
    return _PIECES.findall(text)


def mutations(text: str, extra: list[str] | None = None):
    """Strategy: a list of (op, index, payload) edits of ``text``'s pieces."""
    n = max(1, len(pieces(text)))
    payload = st.one_of(st.sampled_from(NASTY + (extra or [])), st.text(max_size=4))
    op = st.tuples(st.sampled_from(["insert", "delete", "replace", "dup", "truncate"]),
                   st.integers(0, n - 1), payload)
    return st.lists(op, min_size=1, max_size=5)


def mutate(text: str, ops) -> str:
    ps = pieces(text) or [""]
    for op, k, payload in ops:
        k = min(k, len(ps) - 1)
        if op == "insert":
            ps.insert(k, payload)
        elif op == "delete":
            del ps[k]
        elif op == "replace":
            ps[k] = payload
        elif op == "dup":
            ps.insert(k, ps[k])
        else:
            ps = ps[:k]
        if not ps:
            ps = [""]
    return "".join(ps)


def byte_mutations(data: bytes):
    """Strategy: a list of raw byte edits of ``data`` (results are often not UTF-8)."""
    n = max(1, len(data))
    op = st.tuples(st.sampled_from(["set", "insert", "delete", "truncate"]), st.integers(0, n - 1),
                   st.binary(min_size=1, max_size=3))
    return st.lists(op, min_size=1, max_size=4)


def mutate_bytes(data: bytes, ops) -> bytes:
    b = bytearray(data)
    for op, k, payload in ops:
        k = min(k, max(0, len(b) - 1))
        if op == "set":
            b[k:k + len(payload)] = payload
        elif op == "insert":
            b[k:k] = payload
        elif op == "delete":
            del b[k:k + len(payload)]
        else:
            del b[k:]
    return bytes(b)


def check_error(exc: BaseException, filename: str, *, position: bool = False) -> None:
    """A user-facing error: a JackpyError with a one-line message naming ``filename``; with
    ``position`` a ParseError must carry a 1-based line and column."""
    assert isinstance(exc, JackpyError), f"{type(exc).__name__}: {exc}"
    message = str(exc)
    assert message and "\n" not in message and "\r" not in message, repr(message)
    assert filename in message, message
    if position and isinstance(exc, ParseError):
        assert exc.line >= 1 and exc.column >= 1, message
        assert f"{exc.file}:{exc.line}:{exc.column}: " in message, message


def expect_only_project_errors(read, filename: str, *, position: bool = False):
    """Call ``read()``; a non-project exception fails the test with its type and message."""
    try:
        return read()
    except JackpyError as exc:
        check_error(exc, filename, position=position)
        return None
