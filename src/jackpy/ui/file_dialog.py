"""File dialogs: the desktop's own where it has one, else the workbench's file browser.

:class:`FileDialog` takes a :class:`FileRequest` (what is asked: open or save, which extensions,
the folder to start in) and, drawn every frame, gives back the chosen absolute path once.

- **Native**: portable-file-dialogs (imgui-bundle's ``portable_file_dialogs``) runs the desktop's
  dialog (zenity, which also talks to the xdg desktop portal, matedialog, qarma or kdialog) in a
  separate process; the window keeps drawing and shows a small "waiting" box with *Cancel* until
  it answers. Used when :func:`native_available` finds one of those programs and the user's
  preference (Edit → Preferences, *Desktop file dialogs*) allows it.
- **In-app browser** otherwise (no desktop dialog installed, as on a bare Xvfb): a modal with the
  folder (editable; *Up*, *Home*), its folders and the files with the asked extensions (*All
  files* shows every file), a *File name* field, and *Open*/*Save* and *Cancel*. A click on a
  folder enters it, a click on a file takes its name, a double click opens it. Saving adds the
  extension when the name has none, and asks *Replace* before overwriting a file.

Folders start absolute: the document's folder, else the user's home (:func:`start_folder`).
"""

from __future__ import annotations

import shutil
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from imgui_bundle import imgui

NATIVE_PROGRAMS = ("zenity", "matedialog", "qarma", "kdialog")
"""What portable-file-dialogs runs on Linux, in its order of preference."""
BROWSER_TITLE = "##jackpy file browser"
"""The in-app browser's popup ID suffix; its visible title is the request's title."""
WAITING_TITLE = "Waiting for the file dialog##native"


def native_available() -> bool:
    """Whether a desktop file dialog program is installed (then portable-file-dialogs can run it)."""
    return any(shutil.which(p) for p in NATIVE_PROGRAMS)


def start_folder(document_path: str | Path | None) -> Path:
    """Where a dialog starts: the document's folder when it has a path, else the user's home; absolute."""
    if document_path:
        folder = Path(document_path).expanduser().absolute().parent
        if folder.is_dir():
            return folder
    return Path.home().absolute()


@dataclass
class FileRequest:
    """One question to the user: ``title``; ``save`` (else open an existing file); the accepted
    ``extensions`` (lower case with the dot, the first is added to a saved name without one; empty:
    any file); the ``folder`` to start in (absolute) and the proposed file ``name``; ``options``
    draws extra widgets under the list (Import CAD's units and up axis)."""

    kind: str
    title: str
    save: bool
    extensions: tuple[str, ...] = ()
    folder: Path = field(default_factory=lambda: Path.home().absolute())
    name: str = ""
    options: Callable[[], None] | None = None


@dataclass
class Entry:
    """A row of the browser: a folder or a file of the shown folder."""

    name: str
    is_dir: bool


def list_folder(folder: Path, extensions: tuple[str, ...], show_all: bool) -> list[Entry]:
    """The folder's sub-folders, then its files with one of ``extensions`` (every file when
    ``show_all`` or no extension is asked), each sorted by name ignoring case; hidden names
    (``.name``) left out. An unreadable folder lists nothing."""
    try:
        children = list(folder.iterdir())
    except OSError:
        return []
    dirs, files = [], []
    for c in children:
        if c.name.startswith("."):
            continue
        try:
            is_dir = c.is_dir()
        except OSError:
            continue
        if is_dir:
            dirs.append(Entry(c.name, True))
        elif show_all or not extensions or c.suffix.lower() in extensions:
            files.append(Entry(c.name, False))
    key = lambda e: e.name.lower()  # noqa: E731
    return sorted(dirs, key=key) + sorted(files, key=key)


def resolve_choice(folder: Path, name: str, request: FileRequest) -> tuple[Path | None, str | None]:
    """The path that ``name`` (relative to ``folder``, or absolute, ``~`` expanded) means for
    ``request``, or an error to show: ``(path, None)`` or ``(None, message)``. A saved name
    without an extension gets the request's first one."""
    name = name.strip()
    if not name:
        return None, "type a file name or pick a file"
    path = Path(name).expanduser()
    path = path if path.is_absolute() else folder / path
    path = Path(*path.parts)  # normalised, still absolute
    if path.is_dir():
        return None, f"{path} is a folder"
    if request.save:
        if request.extensions and not path.suffix:
            path = path.with_name(path.name + request.extensions[0])
        if not path.parent.is_dir():
            return None, f"no folder {path.parent}"
        return path, None
    if not path.is_file():
        return None, f"no file {path}"
    return path, None


class FileDialog:
    """The window's one file dialog (at most one question at a time)."""

    def __init__(self) -> None:
        self.request: FileRequest | None = None
        self.native = False
        self._native_dialog: object | None = None
        self.folder = Path.home().absolute()
        self.name = ""
        self.folder_text = str(self.folder)
        self.show_all = False
        self.error: str | None = None
        self.replace: Path | None = None
        """A save that would overwrite this file, waiting for *Replace*."""

    @property
    def active(self) -> bool:
        return self.request is not None

    def ask(self, request: FileRequest, native: bool = False) -> None:
        """Start asking ``request``: through the desktop's dialog when ``native`` (and one is
        installed), else in the browser."""
        self.request = request
        self.folder = request.folder if request.folder.is_dir() else Path.home().absolute()
        self.folder_text, self.name = str(self.folder), request.name
        self.error, self.replace, self.show_all = None, None, False
        self.native = native and native_available()
        self._native_dialog = self._start_native(request) if self.native else None

    def cancel(self) -> None:
        """Drop the question (a native dialog's process is killed)."""
        if self._native_dialog is not None:
            self._native_dialog.kill()  # type: ignore[attr-defined]
        self.request, self._native_dialog = None, None

    def enter(self, folder: Path) -> None:
        """Show ``folder`` in the browser."""
        if folder.is_dir():
            self.folder = Path(*folder.absolute().parts)
            self.error = None
        else:
            self.error = f"no folder {folder}"
        self.folder_text = str(self.folder)

    def accept(self, name: str | None = None) -> Path | None:
        """*Open*/*Save* on ``name`` (default: the name field): the chosen path, or None with
        :attr:`error` (or :attr:`replace`, for a save over an existing file, until confirmed)."""
        assert self.request is not None
        path, self.error = resolve_choice(self.folder, self.name if name is None else name, self.request)
        if path is None:
            return None
        if path.is_dir():
            self.enter(path)
            return None
        if self.request.save and path.exists() and self.replace != path:
            self.replace = path
            return None
        self.request, self.replace = None, None
        return path

    # ------------------------------------------------------------------ native
    @staticmethod
    def _start_native(request: FileRequest) -> object:
        from imgui_bundle import portable_file_dialogs as pfd

        pattern = " ".join(f"*{e}" for e in request.extensions) or "*"
        filters = [f"{request.title} ({pattern})", pattern, "All files", "*"]
        start = str(request.folder / request.name) if request.name else str(request.folder) + "/"
        if request.save:
            return pfd.save_file(request.title, start, filters)  # the desktop asks before replacing
        return pfd.open_file(request.title, start, filters)

    def _poll_native(self) -> Path | None:
        dialog = self._native_dialog
        assert dialog is not None and self.request is not None
        if not dialog.ready(0):  # type: ignore[attr-defined]
            imgui.open_popup(WAITING_TITLE)
            if imgui.begin_popup_modal(WAITING_TITLE, None, imgui.WindowFlags_.always_auto_resize)[0]:
                imgui.text(f"{self.request.title}: answer the desktop's file dialog.")
                if imgui.button("Cancel##native"):
                    self.cancel()
                    imgui.close_current_popup()
                imgui.end_popup()
            return None
        result = dialog.result()  # type: ignore[attr-defined]
        chosen = result[0] if isinstance(result, list) and result else result
        request, self.request, self._native_dialog = self.request, None, None
        if not chosen:
            return None  # the user cancelled
        path = Path(str(chosen)).absolute()
        if request.save and request.extensions and not path.suffix:
            path = path.with_name(path.name + request.extensions[0])
        return path

    # ------------------------------------------------------------------ drawing
    def draw(self) -> tuple[FileRequest, Path] | None:
        """Draw the open question (call every frame); once answered, the request and the chosen
        absolute path, else None."""
        request = self.request
        if request is None:
            return None
        path = self._poll_native() if self._native_dialog is not None else self._draw_browser()
        return (request, path) if path is not None else None

    def _draw_browser(self) -> Path | None:
        request = self.request
        assert request is not None
        popup = request.title + BROWSER_TITLE
        imgui.open_popup(popup)
        vp = imgui.get_main_viewport()
        imgui.set_next_window_pos((vp.pos.x + vp.size.x / 2, vp.pos.y + vp.size.y / 2), imgui.Cond_.appearing,
                                  (0.5, 0.5))
        imgui.set_next_window_size((min(640.0, vp.size.x - 40), min(480.0, vp.size.y - 60)), imgui.Cond_.appearing)
        chosen: Path | None = None
        if not imgui.begin_popup_modal(popup, None)[0]:
            return None
        if imgui.button("Up"):
            self.enter(self.folder.parent)
        imgui.same_line()
        if imgui.button("Home"):
            self.enter(Path.home())
        imgui.same_line()
        imgui.set_next_item_width(-1)
        entered, self.folder_text = imgui.input_text("##folder", self.folder_text,
                                                     imgui.InputTextFlags_.enter_returns_true)
        if entered:
            self.enter(Path(self.folder_text).expanduser())
        footer = imgui.get_frame_height_with_spacing() * (3 if request.options else 2) + imgui.get_style().item_spacing.y
        if imgui.begin_child("entries", (0, -footer), imgui.ChildFlags_.borders):
            for entry in list_folder(self.folder, request.extensions, self.show_all):
                label = entry.name + ("/" if entry.is_dir else "")
                picked = imgui.selectable(label, not entry.is_dir and entry.name == self.name,
                                          imgui.SelectableFlags_.allow_double_click)[0]
                if not picked:
                    continue
                if entry.is_dir:
                    self.enter(self.folder / entry.name)
                else:
                    self.name, self.replace = entry.name, None
                    if imgui.is_mouse_double_clicked(imgui.MouseButton_.left):
                        chosen = self.accept()
        imgui.end_child()
        imgui.align_text_to_frame_padding()
        imgui.text("File name")
        imgui.same_line()
        imgui.set_next_item_width(-130)
        if imgui.is_window_appearing():
            imgui.set_keyboard_focus_here()
        typed, name = imgui.input_text("##name", self.name, imgui.InputTextFlags_.enter_returns_true)
        if name != self.name:
            self.name, self.replace = name, None
        imgui.same_line()
        if request.extensions:
            self.show_all = imgui.checkbox("All files", self.show_all)[1]
        if request.options is not None:
            request.options()
        ok_label = "Replace" if self.replace is not None else ("Save" if request.save else "Open")
        if (imgui.button(ok_label) or typed) and chosen is None:
            chosen = self.accept()
        imgui.same_line()
        if imgui.button("Cancel") or imgui.is_key_pressed(imgui.Key.escape, False):
            self.request = None  # Escape is Cancel
        if self.replace is not None:
            imgui.same_line()
            imgui.text_colored((1.0, 0.8, 0.3, 1.0), f"{self.replace.name} exists: Replace overwrites it")
        elif self.error:
            imgui.same_line()
            imgui.text_colored((1.0, 0.4, 0.4, 1.0), self.error)
        if self.request is None:
            imgui.close_current_popup()
        imgui.end_popup()
        return chosen
