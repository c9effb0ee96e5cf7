"""The docked layout: the 3-D view in the central node, panels docked around it (imgui docking).

Default layout (:func:`build_default`), the one designers know from 3-D editors: the scene tree on
the left; figure properties, goals, joints and the other editing panels on the right as tabs; the
timeline, log and ergonomics at the bottom as tabs; the 3-D view fills the central node, which no
panel covers. Every panel title gets its place when the layout is built, so a panel opened later
docks into its tab there, never over the figure.

A saved layout from before a panel existed does not know that panel (imgui would float it over
the figure): on the first frame each panel the saved file does not name is docked into its default
area, as a tab beside a panel of that area the file has docked, else into a new node split off the
central one on that side (:meth:`Layout.begin`). A panel the user floated is named (undocked) and
stays where the user left it.

The layout is saved per user in ``$JACKPY_HOME/layout.ini`` (default ``~/.jackpy/layout.ini``,
imgui's own ini format, written by imgui every few seconds and at exit), never in the working
folder; View → Reset layout rebuilds the default.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

from imgui_bundle import imgui

DOCKSPACE = "jackpy dockspace"
LEFT, RIGHT, BOTTOM = "left", "right", "bottom"
AREAS: dict[str, str] = {
    "Scene": LEFT,
    "Timeline": BOTTOM, "Log": BOTTOM, "Ergonomics": BOTTOM,
}
"""Where a panel (by title) docks in the default layout; any other panel docks on the right."""
RIGHT_FIRST = ("Figure", "Goals", "Joints")
"""The right area's first tabs, in this order (properties, goals, joints)."""
LEFT_FRACTION, RIGHT_FRACTION, BOTTOM_FRACTION = 0.18, 0.26, 0.24
"""Default sizes, fractions of the main viewport's work area."""


def layout_path() -> Path:
    """The per-user layout file, ``$JACKPY_HOME/layout.ini`` (default ``~/.jackpy``)."""
    return Path(os.environ.get("JACKPY_HOME", Path.home() / ".jackpy")) / "layout.ini"


@dataclass
class Rect:
    """A rectangle in imgui (window) coordinates: top-left ``x, y`` and size ``w, h``."""

    x: float
    y: float
    w: float
    h: float


class Layout:
    """The window's dockspace: load/save of the user's layout, the default, the central rect."""

    def __init__(self, path: Path | None = None) -> None:
        self.path = path or layout_path()
        self.reset_requested = not self.path.exists()
        self.saved = {} if self.reset_requested else saved_windows(self.path)
        """The windows the saved layout names, each with its dock node id (None: floating)."""
        self._placed = False
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._ini = str(self.path)  # imgui keeps the pointer: the string must live as long as the context
        io = imgui.get_io()
        io.config_flags |= imgui.ConfigFlags_.docking_enable
        io.set_ini_filename(self._ini)
        self.central = Rect(0.0, 0.0, 1.0, 1.0)

    def request_reset(self) -> None:
        """Rebuild the default layout at the next frame (View → Reset layout)."""
        self.reset_requested = True

    def begin(self, titles: list[str]) -> Rect:
        """Make the dockspace over the main viewport (after the menu and status bars); build the
        default layout when asked (first start, Reset layout); return the central node's rect."""
        vp = imgui.get_main_viewport()
        dock_id = imgui.get_id(DOCKSPACE)
        if self.reset_requested:
            build_default(dock_id, titles)
            self.reset_requested = False
            self._placed = True
        imgui.dock_space_over_viewport(dock_id, vp, imgui.DockNodeFlags_.passthru_central_node)
        if not self._placed:  # (after the dockspace: its central node is known then)
            dock_unknown(dock_id, [t for t in titles if t not in self.saved], self.saved)
            self._placed = True
        node = imgui.internal.dock_builder_get_central_node(dock_id)
        if node is not None:
            self.central = Rect(node.pos.x, node.pos.y, node.size.x, node.size.y)
        else:
            self.central = Rect(vp.work_pos.x, vp.work_pos.y, vp.work_size.x, vp.work_size.y)
        return self.central

    def save(self) -> None:
        """Write the layout now (imgui also writes it by itself)."""
        imgui.save_ini_settings_to_disk(self._ini)


def area_of(title: str) -> str:
    """The default area of a panel."""
    return AREAS.get(title, RIGHT)


_WINDOW = re.compile(r"^\[Window\]\[(.*)\]\s*$")
_DOCK_ID = re.compile(r"^DockId=0x([0-9A-Fa-f]+)")


def saved_windows(path: Path) -> dict[str, int | None]:
    """The windows a saved imgui ini names (``[Window][TITLE]``), each with the dock node it is
    docked in (``DockId=0x...``), None for a floating one; {} for an unreadable file."""
    try:
        lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError:
        return {}
    out: dict[str, int | None] = {}
    current: str | None = None
    for line in lines:
        if line.startswith("["):
            m = _WINDOW.match(line)
            current = m.group(1) if m else None
            if current is not None:
                out[current] = None
        elif current is not None and (d := _DOCK_ID.match(line)):
            out[current] = int(d.group(1), 16)
    return out


_SIDE = {LEFT: (imgui.Dir.left, LEFT_FRACTION), RIGHT: (imgui.Dir.right, RIGHT_FRACTION),
         BOTTOM: (imgui.Dir.down, BOTTOM_FRACTION)}


def dock_unknown(dock_id: int, titles: list[str], saved: dict[str, int | None]) -> None:
    """Dock each window of ``titles`` (which the saved layout ``saved`` does not know) into its
    default area of the live dockspace ``dock_id``: beside a window of the same area that
    ``saved`` docks, else in a node split off the central node towards that area (made once per
    area, shared by the area's other new windows). Call before the windows' first ``begin``."""
    internal = imgui.internal
    made: dict[str, int] = {}
    for title in titles:
        area = area_of(title)
        node = next((n for t, n in saved.items() if n is not None and area_of(t) == area
                     and t not in titles and internal.dock_builder_get_node(n) is not None), None)
        if node is None:
            node = made.get(area)
        if node is None:
            central = internal.dock_builder_get_central_node(dock_id)
            if central is None:
                continue  # no dockspace yet (nothing was saved): the default layout docks it
            direction, fraction = _SIDE[area]
            node, _rest = _split(central.id_, direction, fraction)
            made[area] = node
        internal.dock_builder_dock_window(title, node)
    if titles:
        internal.dock_builder_finish(dock_id)


def build_default(dock_id: int, titles: list[str]) -> None:
    """Rebuild the dockspace ``dock_id`` as the default layout with every panel in ``titles``."""
    internal = imgui.internal
    vp = imgui.get_main_viewport()
    internal.dock_builder_remove_node(dock_id)
    internal.dock_builder_add_node(dock_id, imgui.DockNodeFlags_.passthru_central_node
                                   | internal.DockNodeFlagsPrivate_.dock_space)
    internal.dock_builder_set_node_pos(dock_id, vp.work_pos)
    internal.dock_builder_set_node_size(dock_id, vp.work_size)
    bottom, rest = _split(dock_id, imgui.Dir.down, BOTTOM_FRACTION)
    left, rest = _split(rest, imgui.Dir.left, LEFT_FRACTION)
    right, _centre = _split(rest, imgui.Dir.right, RIGHT_FRACTION / (1.0 - LEFT_FRACTION))
    nodes = {LEFT: left, RIGHT: right, BOTTOM: bottom}
    ordered = [t for t in RIGHT_FIRST if t in titles] + [t for t in titles if t not in RIGHT_FIRST]
    for title in ordered:
        internal.dock_builder_dock_window(title, nodes[area_of(title)])
    internal.dock_builder_finish(dock_id)


def _split(node: int, direction: "imgui.Dir", fraction: float) -> tuple[int, int]:
    """Split ``node``: (the new node at ``direction`` taking ``fraction``, the rest)."""
    _, at_dir, opposite = imgui.internal.dock_builder_split_node_py(node, direction, fraction)
    return int(at_dir), int(opposite)
