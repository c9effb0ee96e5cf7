"""An ImGuizmo transform gizmo on the selected goal or object (alternative to the Jack operator).

Translate or rotate in the world or the local frame (``Settings.gizmo_local``); hold Ctrl while
dragging to snap (``snap_translate_m`` metres, ``snap_rotate_deg`` degrees). One gizmo drag is one
undo step. While the gizmo is hovered or in use, the viewport does not start a camera move.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from imgui_bundle import imgui, imguizmo

from jackpy.ui.app import FigureTarget, GoalTarget
from jackpy.ui.scene_view import GoalPick, SegmentPick, is_object

if TYPE_CHECKING:
    from jackpy.ui.app import App

gz = imguizmo.im_guizmo


def _m16(m: np.ndarray) -> "gz.Matrix16":
    return gz.Matrix16(list(np.asarray(m, np.float32).T.reshape(16)))


def _from_m16(m: "gz.Matrix16") -> np.ndarray:
    return np.asarray(m.values, float).reshape(4, 4).T


class Gizmo:
    """Per-window gizmo state: the operation and the drag in progress."""

    def __init__(self) -> None:
        self.rotate = False
        self.enabled = True
        self._using = False

    def wants_mouse(self) -> bool:
        """Whether a mouse press belongs to the gizmo rather than the viewport."""
        return self.enabled and (gz.is_over() or gz.is_using())

    def _target(self, app: "App") -> GoalTarget | FigureTarget | None:
        sel = app.selection
        if isinstance(sel, GoalPick):
            g = app.goal(sel.key)
            return GoalTarget(app, g) if g is not None else None
        if isinstance(sel, SegmentPick):
            fig = app.env.figures.get(sel.figure)
            if fig is not None and is_object(fig):
                return FigureTarget(app, fig)
        return None

    def draw(self, app: "App", width: float, height: float, x: float = 0.0, y: float = 0.0) -> None:
        """Draw and run the gizmo over the 3-D view, ``width`` x ``height`` at (``x``, ``y``) in
        window coordinates (call between imgui frame begin/end)."""
        gz.begin_frame()
        target = self._target(app) if self.enabled else None
        if target is None:
            return
        gz.set_orthographic(app.camera.orthographic)
        gz.set_rect(x, y, width, height)
        aspect = width / max(height, 1.0)
        s = app.settings
        op = gz.OPERATION.rotate if self.rotate else gz.OPERATION.translate
        mode = gz.MODE.local if s.gizmo_local else gz.MODE.world
        snap = None
        if imgui.get_io().key_ctrl:
            v = s.snap_rotate_deg if self.rotate else s.snap_translate_m
            snap = gz.Matrix3([v, v, v])
        m = _m16(target.transform())
        changed = gz.manipulate(_m16(app.camera.view_matrix()), _m16(app.camera.projection_matrix(aspect)),
                                op, mode, m, None, snap)
        using = gz.is_using()
        if using and not self._using:
            app.begin_edit()
        if changed:
            target.apply(_from_m16(m))
        if self._using and not using:
            target.end_primitive()
            app.end_edit("gizmo " + ("rotate" if self.rotate else "move"))
        self._using = using
