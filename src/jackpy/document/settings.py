"""The user's settings, saved with a document."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class Settings:
    """User settings, saved with a session."""

    literal_grab: bool = False
    """Jack's literal operator: the grabbed origin jumps to the closest point at button-down."""
    skeleton: bool = False
    show_floor: bool = True
    ik_time_budget_s: float = 0.03
    """Time box of the per-frame IK solve (s)."""
    mouse_mapping: str = "default"
    autosave_s: float = 60.0
    gizmo_local: bool = False
    snap_translate_m: float = 0.05
    snap_rotate_deg: float = 15.0
    behaviors: bool = True
    """Drags of a human's hands, feet, pelvis and head go through the behaviors (balance, planted
    feet, stepping, as in Jack); off: plain IK on the workbench goals."""
    hand_lean: bool = True
    """A dragged hand beyond the arm's reach bends the body and shifts the weight (then steps)."""
    head_drag: str = "head"
    """What a head drag moves: ``"head"`` (neck fixates the point ahead) or ``"eyes"`` (eyes, then head)."""
    feet_hold: bool = True
    """Planted feet hold their full orientation (Jack's "hold"); off: they may pivot about the ball."""
    settle_frames: int = 60
    """Behavior frames after a release before the solve stops even if the posture still creeps (a
    frame the time box cut short counts ``document.CUT_FRAME_SHARE``, a quarter)."""
