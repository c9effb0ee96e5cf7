"""Helpers the foot and heel motions share (not a motion kind)."""

from __future__ import annotations

import numpy as np

from jackpy.motion.base import Context

UP = np.array([0.0, 1.0, 0.0])
OTHER = {"left": "right", "right": "left"}


def free_foot(ctx: Context, side: str) -> None:
    """Let foot ``side`` move: a foot that roots the figure cannot (the IK never moves the root),
    so the support moves to the other foot, and the choice is claimed for the motion."""
    loop = ctx.loop
    if loop.state.root == side:
        loop.set_root(OTHER[side])
    loop.state.root_claimed = True


def level(loop, side: str, target: np.ndarray) -> np.ndarray:
    """Ball-site pose ``target`` of foot ``side`` turned (least rotation) so the sole is level."""
    spec = loop.anatomy.feet[side]
    up_w = target[:3, :3] @ (loop.figure.site_location(*spec.ball)[:3, :3].T @ spec.up)
    axis = np.cross(up_w, UP)
    n = np.linalg.norm(axis)
    out = target.copy()
    if n > 1e-12:
        from jackpy.peabody.transforms import rotation_matrix

        angle = float(np.arctan2(n, up_w @ UP))
        out[:3, :3] = rotation_matrix(axis / n, angle)[:3, :3] @ target[:3, :3]
    return out
