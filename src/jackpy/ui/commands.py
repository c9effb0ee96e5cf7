"""Every menu command of the workbench, once, as data: the menu bar draws them, the command
palette (:mod:`jackpy.ui.palette`) offers them, Help → Keyboard shortcuts lists their keys.

A :class:`Command` has its menu, label, shortcut text, what it does (``run(app, ui)``), for a
switch its state (``checked(app, ui)``; running it flips it), and whether it can run now
(``enabled(app, ui)``; the menu greys it out). The file commands open the window's
:class:`~jackpy.ui.file_dialog.FileDialog`; :func:`file_chosen` carries out the answer.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from jackpy.errors import JackpyError
from jackpy.ui.file_dialog import FileRequest, start_folder

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.panels import UiState

Action = Callable[["App", "UiState"], None]

CAD_EXTENSIONS = (".stl", ".obj", ".ply", ".off", ".glb", ".gltf", ".3mf", ".dae", ".step", ".stp")
"""What Import CAD lists (trimesh's formats; STEP through cascadio)."""


@dataclass(frozen=True)
class Command:
    """One menu command: ``menu`` and ``label`` (the palette shows ``"Menu: label"``), the
    ``shortcut`` shown beside it, ``run``; a switch also has ``checked``."""

    menu: str
    label: str
    run: Action
    shortcut: str = ""
    checked: Callable[["App", "UiState"], bool] | None = None
    separator_before: bool = False
    enabled: Callable[["App", "UiState"], bool] | None = None

    @property
    def name(self) -> str:
        """The palette's name: ``"View: Side"``, with the shortcut in brackets when it has one."""
        return f"{self.menu}: {self.label}" + (f" ({self.shortcut})" if self.shortcut else "")


def run_reporting(app: "App", action: Callable[[], object]) -> bool:
    """Run ``action``; a user-facing error goes to the log (and a toast). True when it worked."""
    try:
        action()
    except (JackpyError, OSError, ValueError) as exc:
        app.info(f"error: {exc}")
        return False
    return True


# ---------------------------------------------------------------------- files
def default_save_path(app: "App") -> str:
    """Absolute Save-as default: the document's own path, else ``scene.env`` in the user's home."""
    return str(Path(app.session_path).absolute() if app.session_path else Path.home().absolute() / "scene.env")


def file_request(app: "App", ui: "UiState", kind: str) -> FileRequest:
    """What the file dialog asks for ``kind`` (``open``, ``save_as``, ``import``, ``screenshot``, ``terrain``),
    starting in the document's folder, else the user's home."""
    folder = start_folder(app.session_path)
    if kind == "open":
        return FileRequest(kind, "Open scene", False, (".env", ".fig"), folder)
    if kind == "save_as":
        return FileRequest(kind, "Save scene as", True, (".env",), folder, Path(default_save_path(app)).name)
    if kind == "import":
        from jackpy.ui.panels.menu_bar import import_options

        return FileRequest(kind, "Import CAD", False, CAD_EXTENSIONS, folder, options=lambda: import_options(ui))
    if kind == "screenshot":
        return FileRequest(kind, "Save screenshot", True, (".png",), folder, "screenshot.png")
    if kind == "terrain":
        from jackpy.document.terrain import MESH_EXTENSIONS

        return FileRequest(kind, "Load terrain", False, (".json", ".png", *MESH_EXTENSIONS), folder)
    raise ValueError(f"no file dialog for {kind!r}")


def ask_file(app: "App", ui: "UiState", kind: str) -> None:
    """Open the file dialog for ``kind`` (native when the user's preference and the desktop allow)."""
    ui.files.ask(file_request(app, ui, kind), native=app.preferences.native_dialogs)


def file_chosen(app: "App", ui: "UiState", request: FileRequest, path: Path) -> bool:
    """Carry out the file dialog's answer; True when it worked (a failure is in the log)."""
    from jackpy.document.terrain import load_terrain
    from jackpy.ui import screenshot, session

    actions = {
        "open": lambda: session.open_session(app, path),
        "save_as": lambda: session.save_session(app, path),
        "import": lambda: app.import_cad(path, ui.import_units, ui.import_up),
        "screenshot": lambda: screenshot.save_view(app, path),
        "terrain": lambda: app.info(f"terrain {load_terrain(app.doc, path).name} loaded from {path}"),
    }
    ok = run_reporting(app, actions[request.kind])
    if request.kind == "save_as" and ui.quit_after_save and ok and not app.dirty:
        ui.quit_confirmed = ui.quit_requested = True
    ui.quit_after_save = False
    then, ui.after_save = ui.after_save, None
    if request.kind == "save_as" and then is not None and ok and not app.dirty:
        then()
    return ok


def unless_unsaved(app: "App", ui: "UiState", words: str, action: Callable[[], None]) -> None:
    """Run ``action`` now when nothing is unsaved, else ask Save / Discard / Cancel first
    (``words`` say what the action does: "opening another scene")."""
    if not app.dirty:
        action()
        return
    ui.pending, ui.confirm = (words, action), "unsaved"


def unsaved_choice(app: "App", ui: "UiState", choice: str) -> None:
    """The answer to the ``"unsaved"`` prompt: ``"save"`` (save, then go on; Save-as first for an
    unnamed document), ``"discard"`` (go on without saving), ``"cancel"`` (keep working)."""
    from jackpy.ui import session

    pending, ui.pending, ui.confirm = ui.pending, None, None
    if pending is None or choice == "cancel":
        return
    action = pending[1]
    if choice == "save":
        if app.session_path is None:
            ui.after_save = action
            ask_file(app, ui, "save_as")
            return
        run_reporting(app, lambda: session.save_session(app, app.session_path))
        if app.dirty:  # the save failed (reported): keep the work, do nothing else
            return
    action()


def save(app: "App", ui: "UiState") -> None:
    """Save to the document's path; Save-as when it has none."""
    from jackpy.ui import session

    if app.session_path is None:
        ask_file(app, ui, "save_as")
    else:
        run_reporting(app, lambda: session.save_session(app, app.session_path))


def open_recent(app: "App", ui: "UiState", path: str) -> None:
    """Open a recent file; one that is gone is reported and dropped from the list."""
    from jackpy.ui import session

    if not Path(path).is_file():
        app.info(f"error: {path} no longer exists; removed from the recent files")
        app.preferences.forget_recent(path)
        return
    unless_unsaved(app, ui, f"opening {Path(path).name}",
                   lambda: run_reporting(app, lambda: session.open_session(app, Path(path))))


def recover_orphan(app: "App", ui: "UiState", path: Path) -> None:
    """File → Recover: open a crashed run's recovery file as unsaved work (asking first when the
    current scene has unsaved changes)."""
    from jackpy.ui import session

    unless_unsaved(app, ui, f"recovering {path.name}",
                   lambda: run_reporting(app, lambda: session.recover(app, path)))


# ---------------------------------------------------------------------- the table
def _new(app: "App", ui: "UiState") -> None:
    from jackpy.ui import session

    def new() -> None:
        app.command("new scene", lambda: session.new_scene(app), structural=True)
        app.doc.dirty = False  # the default scene holds nothing to save (Undo brings the old one back)

    unless_unsaved(app, ui, "starting a new scene", new)


def _open(app: "App", ui: "UiState") -> None:
    unless_unsaved(app, ui, "opening another scene", lambda: ask_file(app, ui, "open"))


def _quit(app: "App", ui: "UiState") -> None:
    ui.quit_requested = True


def _setting(name: str) -> tuple[Action, Callable[["App", "UiState"], bool]]:
    def flip(app: "App", ui: "UiState") -> None:
        setattr(app.settings, name, not getattr(app.settings, name))

    return flip, lambda app, ui: bool(getattr(app.settings, name))


def _view(preset: str) -> Action:
    return lambda app, ui: app.camera.set_preset(preset)


def _flip_ortho(app: "App", ui: "UiState") -> None:
    app.camera.orthographic = not app.camera.orthographic


def _flip_manip(app: "App", ui: "UiState") -> None:
    app.manipulation_mode = not app.manipulation_mode


def _panel(title: str) -> tuple[Action, Callable[["App", "UiState"], bool]]:
    def flip(app: "App", ui: "UiState") -> None:
        ui.open_panels[title] = not ui.open_panels.get(title, False)

    return flip, lambda app, ui: bool(ui.open_panels.get(title, False))


def _show_panel(title: str) -> Action:
    def show(app: "App", ui: "UiState") -> None:
        ui.open_panels[title] = True

    return show


def _reset_layout(app: "App", ui: "UiState") -> None:
    ui.reset_layout = True


def _example_terrain(app: "App", ui: "UiState") -> None:
    from jackpy.document.terrain import example_terrain, set_terrain

    set_terrain(app.doc, example_terrain(), "example terrain")


def _remove_terrain(app: "App", ui: "UiState") -> None:
    from jackpy.document.terrain import set_terrain

    if _has_terrain(app, ui):
        set_terrain(app.doc, None)


def _has_terrain(app: "App", ui: "UiState") -> bool:
    from jackpy.document.terrain import terrain_of

    return terrain_of(app.doc) is not None


def _palette(app: "App", ui: "UiState") -> None:
    ui.palette_open = True


def commands(panel_titles: list[str]) -> list[Command]:
    """Every menu command, in menu order (the View menu ends with one switch per panel)."""
    skeleton, floor = _setting("skeleton"), _setting("show_floor")
    literal, gizmo = _setting("literal_grab"), _setting("gizmo_local")
    table = [
        Command("File", "New", _new),
        Command("File", "Open...", _open, "Ctrl+O"),
        Command("File", "Save", save, "Ctrl+S"),
        Command("File", "Save as...", lambda app, ui: ask_file(app, ui, "save_as"), "Ctrl+Shift+S"),
        Command("File", "Import CAD...", lambda app, ui: ask_file(app, ui, "import"), separator_before=True),
        Command("File", "Screenshot...", lambda app, ui: ask_file(app, ui, "screenshot")),
        Command("File", "Quit", _quit, "Ctrl+Q", separator_before=True),
        Command("Edit", "Undo", lambda app, ui: app.undo(), "Ctrl+Z"),
        Command("Edit", "Redo", lambda app, ui: app.redo(), "Ctrl+Y"),
        Command("Edit", "Preferences...", _show_panel("Preferences"), separator_before=True),
        Command("View", "Front", _view("front"), "1"),
        Command("View", "Side", _view("side"), "3"),
        Command("View", "Top", _view("top"), "7"),
        Command("View", "Iso", _view("iso"), "9"),
        Command("View", "Frame all", lambda app, ui: app.frame_all(), "F"),
        Command("View", "Skeleton", skeleton[0], "K", skeleton[1]),
        Command("View", "Floor", floor[0], "", floor[1]),
        Command("View", "Orthographic", _flip_ortho, "", lambda app, ui: app.camera.orthographic),
        Command("View", "Literal Jack grab (jump)", literal[0], "", literal[1]),
        Command("View", "Gizmo in local frame", gizmo[0], "", gizmo[1]),
        Command("View", "Manipulation mode", _flip_manip, "M", lambda app, ui: app.manipulation_mode),
        Command("View", "Reset layout", _reset_layout),
    ]
    for i, title in enumerate(panel_titles):
        flip, shown = _panel(title)
        table.append(Command("View", title, flip, "", shown, separator_before=i == 0))
    table += [
        Command("Scene", "Load terrain...", lambda app, ui: ask_file(app, ui, "terrain")),
        Command("Scene", "Example terrain", _example_terrain),
        Command("Scene", "Remove terrain", _remove_terrain, enabled=_has_terrain),
        Command("Help", "Command palette", _palette, "Ctrl+Shift+P"),
        Command("Help", "Keyboard shortcuts", _show_panel("Keyboard shortcuts")),
    ]
    return table


OTHER_KEYS = (
    ("Ctrl+Shift+Z", "redo"),
    ("Escape", "leave manipulation mode, clear the selection"),
    ("Delete", "remove the selected goal"),
    ("T / R", "gizmo: translate / rotate"),
    ("Ctrl (while dragging the gizmo)", "snap (5 cm, 15 degrees)"),
)
"""Keys that are not menu commands, for Help → Keyboard shortcuts."""
