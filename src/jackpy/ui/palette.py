"""The command palette (imgui-bundle's ``imgui_command_palette``, as in VS Code): Ctrl+Shift+P or
Help → Command palette, type a few letters of any menu command (``"View: Side (3)"``), Enter or a
click runs it. Its commands are exactly :func:`jackpy.ui.commands.commands`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from imgui_bundle import imgui
from imgui_bundle import imgui_command_palette as imcmd

if TYPE_CHECKING:
    from jackpy.ui.app import App
    from jackpy.ui.commands import Command
    from jackpy.ui.panels import UiState

WINDOW = "Command palette"


class CommandPalette:
    """The palette's context and its registered commands (made at the first draw: imgui must exist)."""

    def __init__(self) -> None:
        self._context: object | None = None
        self._names: list[str] = []
        self._run: dict[str, Command] = {}
        self._app: App | None = None
        self._ui: UiState | None = None
        self._was_open = False
        self.ran: list[str] = []
        """Names of the commands run from the palette, in order (the log says the same)."""

    @property
    def names(self) -> list[str]:
        """The registered commands' names."""
        return list(self._names)

    def _register(self, table: list[Command]) -> None:
        if self._context is None:
            self._context = imcmd.ContextWrapper()
        for name in self._names:
            imcmd.remove_command(name)
        self._names, self._run = [c.name for c in table], {c.name: c for c in table}
        for c in table:
            command = imcmd.Command()
            command.name = c.name
            command.initial_callback = lambda name=c.name: self._execute(name)
            command.subsequent_callback = lambda option: None
            command.terminating_callback = lambda: None
            imcmd.add_command(command)

    def _execute(self, name: str) -> None:
        command, app, ui = self._run[name], self._app, self._ui
        assert app is not None and ui is not None
        self.ran.append(name)
        command.run(app, ui)

    def draw(self, app: App, ui: UiState, table: list[Command]) -> None:
        """Register ``table`` when it changed; draw the palette while ``ui.palette_open``."""
        if [c.name for c in table] != self._names:
            self._register(table)
        self._app, self._ui = app, ui
        if not ui.palette_open:
            self._was_open = False
            return
        if not self._was_open:
            imcmd.set_next_command_palette_search("")
            imcmd.set_next_command_palette_search_box_focused()
            self._was_open = True
        vp = imgui.get_main_viewport()
        imgui.set_next_window_size((min(560.0, vp.size.x - 40), 0.0), imgui.Cond_.always)
        imgui.set_next_window_pos((vp.pos.x + vp.size.x / 2, vp.pos.y + 60.0), imgui.Cond_.always, (0.5, 0.0))
        ui.palette_open = imcmd.command_palette_window(WINDOW, True)
