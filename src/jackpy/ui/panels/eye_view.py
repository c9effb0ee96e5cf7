"""Eye view: the figure's view from its eyes (the window is :func:`jackpy.ui.eye_view.draw_window`;
drawn every frame, since it also tells the app whether to render the eye view)."""

from __future__ import annotations

from jackpy.ui.eye_view import draw_window
from jackpy.ui.panels import Panel

PANEL = Panel("Eye view", draw_window, order=65, always=True)
