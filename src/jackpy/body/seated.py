"""Seated support: put a standard human on a seat, resting on its ischial tuberosities, feet on the
floor or a footrest.

The pelvis's ``left_ischium``/``right_ischium`` sites are the seat contact (``seat.hip_height`` below the
hip joint centres, ANSUR II; docs/body.md). :func:`sit` flexes the hips 90° (thighs horizontal), bends
the knees so the soles reach the footrest, sets the ankles so the soles are flat, and moves the figure
vertically so the ischia rest on the seat. A seat higher than the legs reach leaves the feet hanging
(knees at 90°). Heights are world metres (y up).
"""

from __future__ import annotations

import numpy as np

from jackpy.body.measure import SIDES, _dof_index, _set_dof, _zero_posture, site_point
from jackpy.peabody.model import Figure


def seat_contact_points(fig: Figure) -> np.ndarray:
    """World positions (2, 3) of the ischial seat-contact sites, left then right."""
    return np.array([site_point(fig, "pelvis", f"{s}_ischium") for s in SIDES])


def _sole_tilt(fig: Figure, side: str) -> float:
    heel, ball = site_point(fig, f"{side}_foot", "heel"), site_point(fig, f"{side}_foot", "ball")
    d = ball - heel
    return float(np.arctan2(d[1], np.hypot(d[0], d[2])))


def sit(fig: Figure, seat_height: float, footrest_height: float = 0.0) -> bool:
    """Seat ``fig`` erect with its ischia at ``seat_height`` and its soles flat at ``footrest_height``
    where the lower legs reach; returns whether both feet rest on the footrest (within 2 mm)."""
    _zero_posture(fig)
    for side in SIDES:
        _set_dof(fig, f"{side}_hip", _dof_index(fig, f"{side}_hip", "flexion"), np.pi / 2)
    fig.location = fig.location.copy()
    fig.location[1, 3] += seat_height - seat_contact_points(fig)[:, 1].mean()
    resting = True
    for side in SIDES:
        knee_joint = fig.joint(f"{side}_knee")
        ankle = fig.joint(f"{side}_ankle")
        k_ankle = _dof_index(fig, f"{side}_ankle", "flexion")
        lo, hi = knee_joint.dofs[0].lower, knee_joint.dofs[0].upper
        _set_dof(fig, f"{side}_knee", 0, np.pi / 2)
        knee_y = site_point(fig, f"{side}_shank", "base")[1]
        reach = knee_y - site_point(fig, f"{side}_foot", "heel")[1]  # straight-down shank: knee 90°
        drop = knee_y - footrest_height
        if drop < reach:  # low seat: the shank leans forward (knee opens) until the heel is on the rest
            shank = knee_y - site_point(fig, f"{side}_foot", "base")[1]
            heel_below_ankle = reach - shank
            lean = np.arccos(np.clip((drop - heel_below_ankle) / shank, -1.0, 1.0))
            _set_dof(fig, f"{side}_knee", 0, float(np.clip(np.pi / 2 - lean, lo, hi)))
        for _ in range(4):  # sole flat: the ankle undoes the shank's lean (exact after one step)
            d = ankle.displacement.copy()
            d[k_ankle] = np.clip(d[k_ankle] - _sole_tilt(fig, side), ankle.dofs[k_ankle].lower,
                                 ankle.dofs[k_ankle].upper)
            ankle.displacement = d
        heel_y = site_point(fig, f"{side}_foot", "heel")[1]
        resting &= abs(heel_y - footrest_height) < 0.002
    return bool(resting)
