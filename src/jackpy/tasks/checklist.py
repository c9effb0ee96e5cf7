"""The checklist grammar of [SH6] §6.1.2 (Esakov), one sentence per line, ``#`` comments:

```
John is a 50 percentile male [with pace 1.5].
John, look at [switch] twf-1.
John, turn [switch] twf-1 to state 4.      | ... on. | ... off. | ... by 30 degrees.
John, reach [for] twf-2 [with the left hand].
John, grasp the block [for carry].
John, put the block on the table [at table.corner].   | ... in the box.
John, release [the block].
John, ratchet the wrench by 30 degrees 7 times.
John, walk to the door.
If that fails, John, ...      If that succeeds, John, ...   (hooks of the line before)
```

Each agent's lines run in order; different agents act at the same time (a crew checklist). The
parser makes the same calls as the Python API; errors are ``FILE:LINE:COL: expected ...``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

from jackpy.errors import ParseError
from jackpy.tasks import commands as c
from jackpy.tasks.schedule import After, At, Entry
from jackpy.tasks.script import Script

TOKEN = re.compile(r"[A-Za-z0-9_\-]+(?:\.[A-Za-z0-9_\-]+)*|[,.]|\S")
NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_\-.]*$")
NUMBER = re.compile(r"-?[0-9]+(\.[0-9]+)?(th|st|nd|rd)?$", re.IGNORECASE)


@dataclass
class Tok:
    text: str
    col: int


class _Line:
    def __init__(self, text: str, file: str, line: int) -> None:
        self.file, self.line = file, line
        self.toks = [Tok(m.group(), m.start() + 1) for m in TOKEN.finditer(text)]
        self.i = 0
        self.end_col = len(text.rstrip()) + 1

    def peek(self, k: int = 0) -> str:
        j = self.i + k
        return self.toks[j].text.lower() if j < len(self.toks) else ""

    def fail(self, what: str) -> ParseError:
        if self.i < len(self.toks):
            t = self.toks[self.i]
            return ParseError(f"expected {what}, found {t.text!r}", self.file, self.line, t.col)
        return ParseError(f"expected {what}, found the end of the line", self.file, self.line, self.end_col)

    def word(self, *words: str) -> str:
        if self.peek() in words:
            self.i += 1
            return self.toks[self.i - 1].text.lower()
        raise self.fail(" or ".join(repr(w) for w in words))

    def opt(self, *words: str) -> str | None:
        if self.peek() in words:
            self.i += 1
            return self.toks[self.i - 1].text.lower()
        return None

    def name(self, what: str = "a name") -> str:
        self.opt("the")
        if self.i < len(self.toks) and NAME.match(self.toks[self.i].text) and not self.toks[self.i].text.endswith("."):
            self.i += 1
            return self.toks[self.i - 1].text
        raise self.fail(what)

    def number(self, what: str = "a number") -> float:
        if self.i < len(self.toks) and NUMBER.match(self.toks[self.i].text):
            self.i += 1
            return float(re.sub(r"(?i)(th|st|nd|rd)$", "", self.toks[self.i - 1].text))
        raise self.fail(what)

    def end(self) -> None:
        self.word(".")
        if self.i < len(self.toks):
            raise self.fail("the end of the sentence")

    @property
    def col(self) -> int:
        return self.toks[self.i].col if self.i < len(self.toks) else self.end_col


def _hand(ln: _Line) -> str:
    if ln.opt("with"):
        ln.opt("the")
        side = ln.word("left", "right")
        ln.word("hand")
        return side
    return "right"


def _command(ln: _Line, agent: str) -> c.Command:
    verb = ln.word("look", "turn", "reach", "grasp", "put", "release", "ratchet", "walk")
    if verb == "look":
        ln.word("at")
        ln.opt("switch")
        return c.LookAt(agent, ln.name("what to look at"))
    if verb == "turn":
        ln.opt("switch")
        ctl = ln.name("a control")
        how = ln.word("on", "off", "to", "by")
        if how in ("on", "off"):
            return c.Turn(agent, ctl, state=how, hand=_hand(ln))
        if how == "to":
            ln.word("state")
            k = ln.toks[ln.i].text if ln.i < len(ln.toks) and ln.toks[ln.i].text not in ".," else None
            if k is None:
                raise ln.fail("a state")
            ln.i += 1
            return c.Turn(agent, ctl, state=k, hand=_hand(ln))
        d = ln.number("degrees")
        ln.word("degrees", "degree")
        return c.Turn(agent, ctl, degrees=d, hand=_hand(ln))
    if verb == "reach":
        ln.opt("for")
        return c.Reach(agent, ln.name("what to reach"), hand=_hand(ln))
    if verb == "grasp":
        obj = ln.name("what to grasp")
        purpose = ln.name("a purpose") if ln.opt("for", "to") else None
        return c.Grasp(agent, obj, hand=_hand(ln), purpose=purpose)
    if verb == "put":
        obj = ln.name("what to put")
        prep = ln.word("on", "in")
        dest = ln.name("where to put it")
        at = ln.name("a site") if ln.opt("at") else None
        hand = _hand(ln)
        return c.Put(agent, obj, on=dest if prep == "on" else None, in_=dest if prep == "in" else None, at=at, hand=hand)
    if verb == "release":
        if ln.peek() not in (".", "with"):
            ln.name("what to release")
        return c.Release(agent, hand=_hand(ln))
    if verb == "ratchet":
        tool = ln.name("what to ratchet")
        ln.word("by")
        d = ln.number("degrees")
        ln.word("degrees", "degree")
        n = ln.number("how many times")
        if n != int(n) or n < 1:
            ln.i -= 1
            raise ln.fail("a whole number of times ≥ 1")
        ln.word("times", "time")
        return c.Ratchet(agent, tool, degrees=d, iterations=int(n), hand=_hand(ln))
    ln.word("to")
    return c.WalkTo(agent, ln.name("where to walk"))


def parse(text: str, file: str = "<script>") -> Script:
    """A :class:`Script` from checklist text; ParseError ``file:line:col: expected ...``."""
    s = Script()
    last: dict[str, str] = {}
    prev: Entry | None = None
    for lineno, raw in enumerate(text.splitlines(), 1):
        body = raw.split("#", 1)[0]
        if not body.strip():
            continue
        ln = _Line(body, file, lineno)
        origin = f"{file}:{lineno}"
        hook = None
        if ln.opt("if"):
            ln.word("that")
            hook = ln.word("fails", "succeeds")
            ln.word(",")
            if prev is None:
                raise ParseError("expected a command before 'If that ...'", file, lineno, ln.toks[0].col)
        agent_col = ln.col
        agent = ln.name("an agent's name")
        if ln.peek() == "is" and hook is None:
            ln.word("is")
            ln.word("a", "an")
            pct = ln.number("a percentile")
            if not 0 < pct < 100:
                ln.i -= 1
                raise ln.fail("a percentile between 0 and 100")
            ln.opt("percentile")
            sex = ln.word("male", "female", "man", "woman")
            sex = {"man": "male", "woman": "female"}.get(sex, sex)
            pace = None
            if ln.opt("with"):
                ln.word("pace")
                pace = ln.number("a pace factor")
            ln.end()
            s.agent(agent, sex, pct, pace)
            continue
        ln.word(",")
        if agent not in s.agents:
            raise ParseError(f"expected a declared agent ({', '.join(s.agents) or 'none yet'}), found {agent!r}",
                             file, lineno, agent_col)
        cmd = _command(ln, agent)
        ln.end()
        if hook is not None:
            e = s.entry(cmd, origin=origin)
            e.hook = True
            (prev.on_failure if hook == "fails" else prev.on_success).append(e)
            continue
        start = After(last[agent]) if agent in last else At(0.0)
        prev = s.add(cmd, start=start, origin=origin)
        last[agent] = prev.name
    return s


def load(path: str | Path) -> Script:
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except UnicodeDecodeError as e:
        raise ParseError(f"expected UTF-8 text ({e.reason})", str(p), 1, 1) from None
    return parse(text, str(p))
