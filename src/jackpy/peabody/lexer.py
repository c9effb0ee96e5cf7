"""Tokenizer for Peabody text (``.fig``, ``.env``) with 1-based line and column tracking.

Tokens: identifiers, numbers (unsigned; the parser handles signs), double-quoted strings and the
punctuation ``{ } ( ) ; , = * . -> + - <= >=``. Comments run from ``#`` or ``//`` to the end of the
line, or between ``/*`` and ``*/``. A number directly followed by letters (``5.00cm``) gives a
number token and an identifier token (the unit).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from jackpy.errors import ParseError

IDENT, NUMBER, STRING, PUNCT, EOF = "identifier", "number", "string", "punctuation", "end of file"

_NUMBER = re.compile(r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_PUNCT2 = ("->", "<=", ">=")
_PUNCT1 = "{}();,=*.+-"
_DIGITS = frozenset("0123456789")


@dataclass(frozen=True)
class Token:
    """One token: ``kind`` (IDENT, NUMBER, STRING, PUNCT or EOF), its text, value and position."""

    kind: str
    text: str
    line: int
    column: int
    value: float | str | None = None

    def describe(self) -> str:
        """How an error message names this token (``'foo'``, ``end of file``)."""
        return EOF if self.kind == EOF else repr(self.text)


def tokenize(text: str, filename: str = "<string>") -> list[Token]:
    """Split ``text`` into tokens ending with an EOF token; raise ParseError on a bad character."""
    tokens: list[Token] = []
    i, line, line_start, n = 0, 1, 0, len(text)
    while i < n:
        c = text[i]
        col = i - line_start + 1
        if c == "\n":
            i += 1
            line, line_start = line + 1, i
        elif c in " \t\r\f\v":
            i += 1
        elif c == "#" or text.startswith("//", i):
            end = text.find("\n", i)
            i = n if end < 0 else end
        elif text.startswith("/*", i):
            end = text.find("*/", i + 2)
            if end < 0:
                raise ParseError("unterminated comment: expected '*/'", filename, line, col)
            for k in range(i, end):
                if text[k] == "\n":
                    line, line_start = line + 1, k + 1
            i = end + 2
        elif c == '"':
            j, chars = i + 1, []
            while True:
                if j >= n or text[j] == "\n":
                    raise ParseError("unterminated string: expected '\"'", filename, line, col)
                if text[j] == "\\" and j + 1 < n and text[j + 1] in '"\\':
                    chars.append(text[j + 1])
                    j += 2
                elif text[j] == '"':
                    break
                else:
                    chars.append(text[j])
                    j += 1
            tokens.append(Token(STRING, text[i:j + 1], line, col, "".join(chars)))
            i = j + 1
        elif c in _DIGITS or (c == "." and i + 1 < n and text[i + 1] in _DIGITS):
            m = _NUMBER.match(text, i)
            assert m is not None
            value = float(m.group())
            if not math.isfinite(value):
                raise ParseError(f"number {m.group()} is out of range", filename, line, col)
            tokens.append(Token(NUMBER, m.group(), line, col, value))
            i = m.end()
        elif c.isascii() and (c.isalpha() or c == "_"):
            m = _IDENT.match(text, i)
            assert m is not None
            tokens.append(Token(IDENT, m.group(), line, col, m.group()))
            i = m.end()
        elif text[i:i + 2] in _PUNCT2:
            tokens.append(Token(PUNCT, text[i:i + 2], line, col))
            i += 2
        elif c in _PUNCT1:
            tokens.append(Token(PUNCT, c, line, col))
            i += 1
        else:
            raise ParseError(f"unexpected character {c!r}", filename, line, col)
    tokens.append(Token(EOF, "", line, n - line_start + 1))
    return tokens


class TokenStream:
    """A cursor over tokens with the ``expect``/``accept`` helpers of a recursive-descent parser."""

    def __init__(self, tokens: list[Token], filename: str) -> None:
        self.tokens = tokens
        self.filename = filename
        self.pos = 0

    def peek(self, ahead: int = 0) -> Token:
        return self.tokens[min(self.pos + ahead, len(self.tokens) - 1)]

    def next(self) -> Token:
        tok = self.peek()
        if tok.kind != EOF:
            self.pos += 1
        return tok

    def at(self, text: str, ahead: int = 0) -> bool:
        """True when the token ``ahead`` is punctuation or an identifier spelled ``text``."""
        tok = self.peek(ahead)
        return tok.kind in (PUNCT, IDENT) and tok.text == text

    def accept(self, text: str) -> Token | None:
        """Consume and return the next token if it is spelled ``text``."""
        return self.next() if self.at(text) else None

    def expect(self, text: str, what: str | None = None) -> Token:
        """Consume the next token, which must be spelled ``text``; else raise ParseError."""
        if self.at(text):
            return self.next()
        raise self.error(f"expected {what or repr(text)}")

    def expect_kind(self, kind: str, what: str) -> Token:
        """Consume the next token, which must be of ``kind``; else raise ParseError naming ``what``."""
        if self.peek().kind == kind:
            return self.next()
        raise self.error(f"expected {what}")

    def error(self, expected: str, tok: Token | None = None) -> ParseError:
        """A ParseError at ``tok`` (default: the next token): ``expected ..., found ...``."""
        tok = tok or self.peek()
        return ParseError(f"{expected}, found {tok.describe()}", self.filename, tok.line, tok.column)
