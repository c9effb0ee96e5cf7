"""Script: edit a task script (the checklist grammar of docs/tasks.md) in a colour text editor, run
it on a scene (the document's file when it is a scene) in the background, and load the resulting
timeline into the document (the Timeline panel then plays it; the document should be that scene). Parse errors and failed commands are listed; clicking one moves the editor
to its line, and the line is marked in the editor's margin."""

from __future__ import annotations

import tempfile
import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from imgui_bundle import imgui
from imgui_bundle import imgui_color_text_edit as ed

from jackpy.ui.panels import Panel

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

TITLE = "Script"
ERROR_COLOUR = 0xFF4040FF


@dataclass
class Problem:
    """A line to show: ``line`` 1-based (0: none) and the one-line message."""

    line: int
    message: str


@dataclass
class ScriptState:
    editor: Any
    scene: str = ""
    problems: list[Problem] = field(default_factory=list)
    running: threading.Thread | None = None
    result: Any = None
    status: str = ""


def state_of(ui: "UiState") -> ScriptState:
    st = getattr(ui, "_script_panel", None)
    if st is None:
        editor = ed.TextEditor()
        editor.set_text("John is a 50 percentile male.\nJohn, look at twf-1.\nJohn, turn twf-1 to state 4.\n")
        st = ScriptState(editor)
        ui._script_panel = st
    return st


def check(text: str, name: str = "script") -> tuple[Any, list[Problem]]:
    """Parse ``text``: (the Script, []) or (None, [the parse error with its line])."""
    from jackpy.errors import ParseError
    from jackpy.tasks import checklist

    try:
        return checklist.parse(text, name), []
    except ParseError as e:
        return None, [Problem(e.line, str(e))]


def run_script(st: ScriptState, text: str) -> None:
    """Parse and start the run in a thread (the window keeps drawing); failed commands become
    problems at their lines when it ends."""
    script, st.problems = check(text)
    if script is None:
        st.status = "parse error"
        return

    def work() -> None:
        try:
            st.result = script.run(st.scene or None)
            st.problems = [Problem(int(r.origin.rsplit(":", 1)[-1]) if r.origin else 0,
                                   f"{r.actor}: {r.command}: {r.status}: {r.reason}")
                           for r in st.result.reports if r.status != "done"]
            st.status = f"done: {len(st.result.reports)} commands, {len(st.problems)} failed"
        except Exception as e:  # a bad scene or name: shown, never kills the window
            st.result, st.problems, st.status = None, [Problem(0, str(e))], "error"

    st.status = "running"
    st.running = threading.Thread(target=work, daemon=True)
    st.running.start()


def load_result(app: "App", st: ScriptState) -> None:
    """Put the finished run's timeline into the document (through a motion file, as ``--motion``)."""
    from jackpy.motion import motion_file
    from jackpy.motion.player import load_into

    refs = {m.target.get("relative_to") for m in st.result.timeline.motions if isinstance(getattr(m, "target", None), dict)}
    missing = sorted(r for r in refs if r and r.split(".")[0] not in app.doc.env.figures
                     and r.split(".")[0] not in st.result.timeline.figures())
    if missing:
        app.doc.info(f"task script: this document lacks {', '.join(missing)}; open the script's scene to play it")
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "task.motion.json"
        motion_file.save(motion_file.MotionFile(st.result.timeline), p)
        load_into(app.doc, str(p))
    app.doc.info(f"task script: timeline of {st.result.timeline.duration:.2f} s loaded")


def mark(st: ScriptState) -> None:
    st.editor.clear_markers()
    for p in st.problems:
        if p.line > 0:
            st.editor.add_marker(p.line - 1, ERROR_COLOUR, ERROR_COLOUR, p.message, p.message)


def draw(app: "App", ui: "UiState") -> None:
    visible, ui.open_panels[TITLE] = imgui.begin(TITLE, ui.open_panels[TITLE])
    if visible:
        st = state_of(ui)
        if not st.scene and app.doc.path is not None and app.doc.path.suffix == ".json":
            st.scene = str(app.doc.path)
        _, st.scene = imgui.input_text("scene", st.scene)
        busy = st.running is not None and st.running.is_alive()
        if st.running is not None and not busy:
            st.running = None
            mark(st)
            if st.result is not None:
                load_result(app, st)
        imgui.begin_disabled(busy)
        if imgui.button("Run"):
            run_script(st, st.editor.get_text())
            mark(st)
        imgui.end_disabled()
        imgui.same_line()
        imgui.text(st.status)
        for k, p in enumerate(st.problems):
            if imgui.selectable(f"{p.message}##problem{k}", False)[0] and p.line > 0:
                st.editor.set_cursor(ed.TextEditor.DocPos(p.line - 1, 0))
                st.editor.scroll_to_line(p.line - 1, ed.TextEditor.Scroll.align_middle)
        st.editor.render("##script", imgui.ImVec2(-1, -1))
    imgui.end()


PANEL = Panel(TITLE, draw, open=False, order=65)
