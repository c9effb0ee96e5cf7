"""The checklist grammar: the book's script parses to the Python API's calls; malformed lines give
FILE:LINE:COL: expected ...; fuzzed text never raises anything but ParseError."""

import pytest
from hypothesis import given, settings, strategies as hs

from jackpy.errors import ParseError
from jackpy.tasks import checklist, commands as c
from jackpy.tasks.schedule import After, At


def test_book_script(panel_scene):
    s = checklist.load(panel_scene.parent / "panel.task")
    assert {n: (a.sex, a.percentile) for n, a in s.agents.items()} == {"John": ("male", 50), "Jane": ("female", 50)}
    acts = [e.action for e in s.entries]
    assert len(acts) == 11
    assert acts[0] == c.LookAt("John", "twf-1")
    assert acts[1] == c.Turn("John", "twf-1", state="4")
    assert acts[4] == c.Turn("Jane", "tglJ-1", state="on")
    # each agent's lines in order, the agents at the same time
    assert s.entries[0].start == At(0.0) and s.entries[2].start == At(0.0)
    assert s.entries[1].start == After(s.entries[0].name)
    assert s.entries[5].start == After(s.entries[1].name)


def test_other_sentences():
    s = checklist.parse("Ann is a 5th percentile woman with pace 2.\n"
                        "Ann, put the block on the table at table.near_corner with the left hand.\n"
                        "If that fails, Ann, walk to the door.\n"
                        "Ann, ratchet the wrench by 30 degrees 7 times.\n"
                        "Ann, turn twf-1 by -36 degrees.\n")
    assert s.agents["Ann"].pace == 2.0 and s.agents["Ann"].sex == "female"
    put = s.entries[0]
    assert put.action == c.Put("Ann", "block", on="table", at="table.near_corner", hand="left")
    assert put.on_failure[0].action == c.WalkTo("Ann", "door")
    assert s.entries[1].action == c.Ratchet("Ann", "wrench", degrees=30.0, iterations=7)
    assert s.entries[2].action == c.Turn("Ann", "twf-1", degrees=-36.0)


@pytest.mark.parametrize("text,where,expected", [
    ("John is a 50 percentile male\n", "1:29", "expected '.', found the end of the line"),
    ("John is a 50 percentile robot.\n", "1:25", "expected 'male' or 'female' or 'man' or 'woman', found 'robot'"),
    ("John is a 50 percentile male.\nJohn, jump over twf-1.\n", "2:7", "expected 'look' or 'turn'"),
    ("John is a 50 percentile male.\nJohn, turn twf-1 sideways.\n", "2:18", "expected 'on' or 'off' or 'to' or 'by'"),
    ("Jane, look at twf-1.\n", "1:1", "expected a declared agent (none yet), found 'Jane'"),
    ("John is a 150 percentile male.\n", "1:11", "expected a percentile between 0 and 100"),
    ("John is a 50 percentile male.\nJohn, look at twf-1. now\n", "2:22", "expected the end of the sentence"),
])
def test_errors(text, where, expected):
    with pytest.raises(ParseError) as ei:
        checklist.parse(text, "s.task")
    msg = str(ei.value)
    assert msg.startswith(f"s.task:{where}: "), msg
    assert expected in msg and "\n" not in msg


@settings(max_examples=300, deadline=None)
@given(hs.text(alphabet="Johnis a50percentilemale.,lookatturnonoffJane-1tgl\n #", max_size=80))
def test_fuzz_only_parse_errors(text):
    try:
        checklist.parse("John is a 50 percentile male.\n" + text, "f.task")
    except ParseError as e:
        assert str(e).startswith("f.task:")
