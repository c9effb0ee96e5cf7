"""The workbench's imgui panels, one per module; each is a ``draw(app, ui)`` function of the state
it shows. :func:`draw_all` draws the menu bar and every open panel."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from jackpy.ui.app import App


@dataclass
class UiState:
    """Window-level UI state: which panels are open and the pending path prompt."""

    open_panels: dict[str, bool] = field(default_factory=lambda: {
        "Scene": True, "Joints": True, "Goals": True, "Figure": False, "Log": True,
        "Analysis": False, "Eye view": False,
        "Behaviors": False, "Devices": False})
    prompt: str | None = None
    """Which path prompt is open: ``"open"``, ``"save_as"``, ``"import"``, ``"screenshot"``."""
    prompt_text: str = ""
    quit_requested: bool = False
    recovery_offer: str | None = None
    """A recovery file found at start-up, offered once."""
    import_units: str = "m"
    """Units and up axis chosen in the Import CAD dialog."""
    import_up: str = "y"


def draw_all(app: "App", ui: UiState) -> None:
    """Draw the menu bar, the open panels and any prompt."""
    from jackpy.ui.panels import (
        behaviors,
        devices,
        figure_properties,
        goals,
        joint_inspector,
        log,
        menu_bar,
        scene_tree,
    )

    menu_bar.draw(app, ui)
    panels = {"Scene": scene_tree.draw, "Joints": joint_inspector.draw, "Goals": goals.draw,
              "Figure": figure_properties.draw, "Log": log.draw, "Behaviors": behaviors.draw,
              "Devices": devices.draw}
    for name, fn in panels.items():
        if ui.open_panels.get(name):
            fn(app, ui)
    from jackpy.ui import eye_view
    from jackpy.ui.panels import analysis

    if ui.open_panels.get("Analysis"):
        analysis.draw(app, ui)
    eye_view.draw_window(app, ui)  # also tells the app whether to render the eye view
