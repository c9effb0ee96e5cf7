"""Undo stack: one step per command, redo cleared by a new command, bounded."""

from jackpy.document.undo import UndoStack


def test_undo_redo_round_trip():
    s = UndoStack()
    s.push("a", 0)
    s.push("b", 1)
    assert s.undo_label == "b"
    assert s.undo(2) == 1 and s.redo_label == "b"
    assert s.undo(1) == 0
    assert s.undo(0) is None
    assert s.redo(0) == 1 and s.redo(1) == 2 and s.redo(2) is None


def test_new_command_clears_redo_and_limit_holds():
    s = UndoStack(limit=3)
    for k in range(5):
        s.push(str(k), k)
    s.undo(5)
    s.push("x", 9)
    assert s.redo_label is None
    got = []
    while (v := s.undo(-1)) is not None:
        got.append(v)
    assert got == [9, 3, 2]
