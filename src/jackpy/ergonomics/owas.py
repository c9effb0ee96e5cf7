"""OWAS, the Ovako Working posture Analysing System (Karhu, Kansi & Kuorinka 1977).

The posture gets four codes — back 1-4, arms 1-3, legs 1-7, load 1-3 — and the action-category table
gives 1 (no action) to 4 (corrective measures immediately). Measured: back bent (|trunk flexion| or
|side bend| beyond :data:`~jackpy.ergonomics.constants.OWAS_BENT_DEG`) and twisted (|trunk twist|
beyond ``OWAS_TWIST_DEG``); an arm at or above shoulder level (its elbow or wrist at or above its
shoulder joint centre's height); legs from the feet bearing weight, the knee flexion and a knee near
the floor. Sitting and walking come from the task (``seated``, ``walking``).
"""

from __future__ import annotations

from jackpy.ergonomics import constants as C
from jackpy.ergonomics.base import Assessment, Method, Task, adjustment, band, register
from jackpy.ergonomics.posture import SIDES, Posture
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

VALIDITY = "whole-body postures sampled at intervals over the work; each sample coded on its own"


def back_code(bent: bool, twisted: bool) -> int:
    return 4 if bent and twisted else 3 if twisted else 2 if bent else 1


def load_code(kg: float) -> int:
    return band(kg, C.OWAS_LOAD_KG, False)


def legs_code(p: Posture, task: Task) -> int:
    if task.seated:
        return 1
    if task.walking:
        return 7
    if any(p.knee_height_m[s] <= C.KNEE_FLOOR_M for s in SIDES):
        return 6
    bearing = p.feet_bearing() or list(SIDES)
    bent = [p.knee_flexion[s] > C.OWAS_KNEE_BENT_DEG for s in bearing]
    if len(bearing) == 2:
        return 4 if all(bent) else 2 if not any(bent) else 4
    return 5 if bent[0] else 3


def assess(figure: Figure, task: Task, posture: Posture, fk: FKResult | None = None) -> Assessment:
    """OWAS codes and action category of ``posture`` under ``task``."""
    p = posture
    adj: dict = {}
    bent = adjustment(task, "back_bent", max(abs(p.trunk_flexion), abs(p.trunk_side_bend)) > C.OWAS_BENT_DEG, adj)
    twisted = adjustment(task, "back_twisted", abs(p.trunk_twist) > C.OWAS_TWIST_DEG, adj)
    back = back_code(bent, twisted)
    up = {s: max(p.arms[s].elbow_height_m, p.arms[s].wrist_height_m) >= p.arms[s].shoulder_height_m for s in SIDES}
    arms = 1 + sum(up.values())
    legs = legs_code(p, task)
    load = load_code(task.load_kg)
    category = int(C.OWAS_TABLE[back - 1, arms - 1, legs - 1, load - 1])
    flags = []
    if len(p.feet_bearing()) == 2 and sum(p.knee_flexion[s] > C.OWAS_KNEE_BENT_DEG for s in SIDES) == 1:
        flags.append("one knee bent while both feet bear weight: coded as both knees bent (4)")
    ws = {"back": back, "back_text": C.OWAS_BACK[back], "arms": arms, "arms_text": C.OWAS_ARMS[arms],
          "legs": legs, "legs_text": C.OWAS_LEGS[legs], "load": load, "load_text": C.OWAS_LOAD[load],
          "code": f"{back}{arms}{legs}{load}", "action_category": category, "adjustments": adj,
          "arm_at_or_above_shoulder": up}
    measured = {"trunk_flexion": p.trunk_flexion, "trunk_side_bend": p.trunk_side_bend, "trunk_twist": p.trunk_twist,
                "knee_flexion": dict(p.knee_flexion), "knee_height_m": dict(p.knee_height_m),
                "feet_bearing": p.feet_bearing(),
                **{f"{s}_{k}": getattr(p.arms[s], k) for s in SIDES
                   for k in ("elbow_height_m", "wrist_height_m", "shoulder_height_m")}}
    codes = {"back": back / 4, "arms": arms / 3, "legs": legs / 7}
    return Assessment("owas", category, category, C.OWAS_ACTION[category], ws, measured, p.FRAME, flags,
                      max(codes, key=lambda k: codes[k]))


METHOD = register(Method("owas", "OWAS (Ovako Working posture Analysing System)",
                         "Karhu O., Kansi P. & Kuorinka I. (1977) Applied Ergonomics 8(4):199-201", VALIDITY, assess))
