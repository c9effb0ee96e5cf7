"""Tokenizer for Peabody text (``.fig``, ``.env``) with 1-based line and column positions.

Tokens: identifiers, numbers (unsigned; the parser handles signs), double-quoted strings and the
punctuation ``{ } ( ) ; , = * . -> + - <= >=``. Comments run from ``#`` or ``//`` to the end of the
line, or between ``/*`` and ``*/``. A number directly followed by letters (``5.00cm``) gives a
number token and an identifier token (the unit). Only ``\\n`` ends a line.

Speed: one compiled regular expression splits the whole text in C (``re.findall``), one match per
token (the whitespace and comments before a token are skipped inside its match, possessively, so
nothing is tried twice); tokens are plain strings, classified by their first character, and
positions are computed only when an error needs one (:meth:`TokenStream.position`). A 2 MB file
tokenizes in about 0.1 s.
"""

from __future__ import annotations

import math
import re

from jackpy.errors import ParseError

IDENT, NUMBER, STRING, PUNCT, EOF, BAD = "identifier", "number", "string", "punctuation", "end of file", "bad"

#: magnitude bound of every number in a Peabody file, after its unit is converted to cm or degrees
#: (10^7 km; far beyond any model, and small enough that sums and products of transforms stay finite)
MAX_MAGNITUDE = 1e12
MAX_TEXT = "1e12"
#: how far past the end a parser may look without a bounds check (:class:`TokenStream` pads)
LOOKAHEAD = 8
#: relative slack on :data:`MAX_MAGNITUDE` for values the writer recomputed (cm -> m -> cm)
_SLACK = 1.0 + 1e-9

_WS = r"[ \t\r\n\f\v]*+"
_SKIP = rf"{_WS}(?:(?:#[^\n]*|//[^\n]*|/\*.*?\*/){_WS})*+"   # possessive: never given back
_TOKEN = (r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"   # number
          r"|[A-Za-z_][A-Za-z0-9_]*"                                # identifier
          r'|"(?:[^"\\\n]|\\.)*"'                                  # string (escapes \" and \\)
          r"|->|<=|>=|/\*|.")                                       # punctuation, or a bad character
#: one match per token: the whitespace and comments before it, then the token in group 1; the end of
#: the text matches with an empty group (the end-of-file token)
_SPLIT = re.compile(rf"{_SKIP}({_TOKEN}|\Z)", re.S)
_PUNCT = frozenset(["->", "<=", ">=", *"{}();,=*.+-"])
_DIGITS = frozenset("0123456789")
_IDSTART = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_")


def kind_of(tok: str) -> str:
    """The kind of a token string (EOF for the empty string that ends every token list)."""
    if not tok:
        return EOF
    c = tok[0]
    if c in _DIGITS or (c == "." and len(tok) > 1):
        return NUMBER
    if c in _IDSTART:
        return IDENT
    if c == '"' and len(tok) > 1:
        return STRING
    return PUNCT if tok in _PUNCT else BAD


def describe(tok: str) -> str:
    """How an error message names a token (``'foo'``, ``end of file``; at most 40 characters)."""
    return EOF if not tok else repr(tok if len(tok) <= 40 else tok[:37] + "...")


def split(text: str) -> list[str]:
    """The token strings of ``text`` followed by ``""`` (the end-of-file token)."""
    if "/*" in text and text.find("/*", text.rfind("*/") + 1) >= 0:
        # a comment may be unterminated: scan token by token and stop at it (scanning on after it
        # would try every later "/*" to the end of the text: quadratic time on a hostile file)
        tokens = []
        for m in _SPLIT.finditer(text):
            tok = m.group(1)
            if tok:
                tokens.append(tok)
                if tok == "/*":
                    break
        tokens.append("")
        return tokens
    tokens = _SPLIT.findall(text)
    if len(tokens) > 1 and not tokens[-2]:  # (trailing space or comment: the end matched twice)
        tokens.pop()
    return tokens


def string_value(tok: str) -> str:
    """The text inside a string token, escapes resolved."""
    return re.sub(r'\\(["\\])', r"\1", tok[1:-1]) if "\\" in tok else tok[1:-1]


def token_position(text: str, index: int) -> tuple[int, int]:
    """1-based (line, column) of token ``index`` of ``text`` (the end of the text past the last)."""
    start = len(text)
    n = 0
    for m in _SPLIT.finditer(text):
        if m.group(1):
            if n == index:
                start = m.start(1)
                break
            n += 1
    return offset_position(text, start)


def offset_position(text: str, offset: int) -> tuple[int, int]:
    """1-based (line, column) of character ``offset`` (0-based) of ``text``."""
    return text.count("\n", 0, offset) + 1, offset - (text.rfind("\n", 0, offset) + 1) + 1


class TokenStream:
    """A cursor over the tokens of one text with ``expect``/``accept`` helpers; token ``k`` is the
    string ``tokens[k]``, its position found on demand."""

    def __init__(self, text: str, filename: str) -> None:
        self.text = text
        self.filename = filename
        self.tokens = split(text)
        self.last = len(self.tokens) - 1
        self.tokens += [""] * LOOKAHEAD  # (end-of-file sentinels: fast paths look ahead unchecked)
        self.pos = 0

    # ----- looking --------------------------------------------------------------------------------
    def peek(self, ahead: int = 0) -> str:
        k = self.pos + ahead
        return self.tokens[k if k < self.last else self.last]

    def kind(self, ahead: int = 0) -> str:
        return kind_of(self.peek(ahead))

    def at(self, text: str, ahead: int = 0) -> bool:
        """True when the token ``ahead`` is spelled ``text`` (punctuation or identifier)."""
        return self.peek(ahead) == text

    # ----- consuming ------------------------------------------------------------------------------
    def next(self) -> int:
        """Consume the next token; returns its index (an EOF token is not consumed)."""
        k = self.pos
        if k < self.last:
            self.pos = k + 1
        return k

    def accept(self, text: str) -> bool:
        """Consume the next token if it is spelled ``text``."""
        if self.tokens[self.pos] == text:
            self.pos += 1
            return True
        return False

    def expect(self, text: str, what: str | None = None) -> int:
        """Consume the next token, which must be spelled ``text``; returns its index."""
        k = self.pos
        if self.tokens[k] == text:
            self.pos = k + 1
            return k
        raise self.error(f"expected {what or repr(text)}")

    def expect_kind(self, kind: str, what: str) -> int:
        """Consume the next token, which must be of ``kind``; returns its index."""
        if kind_of(self.tokens[self.pos]) == kind:
            return self.next()
        raise self.error(f"expected {what}")

    def number(self) -> float:
        """``["+"|"-"] NUMBER`` as a float within :data:`MAX_MAGNITUDE`."""
        tokens, k = self.tokens, self.pos
        sign = 1.0
        if tokens[k] == "-":
            sign, k = -1.0, k + 1
        elif tokens[k] == "+":
            k += 1
        tok = tokens[k]
        if not tok or not (tok[0] in _DIGITS or (tok[0] == "." and len(tok) > 1)):
            self.pos = k
            raise self.error("expected a number")
        value = float(tok)
        if value > MAX_MAGNITUDE:
            raise ParseError(f"number {tok} is out of range (magnitude at most {MAX_TEXT})",
                             self.filename, *self.position(k))
        self.pos = k + 1
        return sign * value

    # ----- positions and errors -------------------------------------------------------------------
    def position(self, index: int) -> tuple[int, int]:
        """1-based (line, column) of token ``index``."""
        return token_position(self.text, index)

    def check_range(self, value: float, index: int, what: str) -> float:
        """``value`` (file units) if finite and within :data:`MAX_MAGNITUDE`, else a ParseError at
        token ``index``."""
        if not (math.isfinite(value) and abs(value) <= MAX_MAGNITUDE * _SLACK):
            raise ParseError(f"{what}: value out of range (magnitude at most {MAX_TEXT} cm or deg)",
                             self.filename, *self.position(index))
        return value

    def error(self, expected: str, index: int | None = None) -> ParseError:
        """A ParseError at token ``index`` (default: the next one): ``expected ..., found ...``;
        a bad character, unterminated string or comment is reported as such."""
        k = self.pos if index is None else index
        tok = self.tokens[min(k, self.last)]
        line, col = self.position(k)
        if kind_of(tok) == BAD:
            if tok == "/*":
                return ParseError("unterminated comment: expected '*/'", self.filename, line, col)
            if tok == '"':
                return ParseError("unterminated string: expected '\"'", self.filename, line, col)
            return ParseError(f"unexpected character {tok!r}", self.filename, line, col)
        return ParseError(f"{expected}, found {describe(tok)}", self.filename, line, col)
