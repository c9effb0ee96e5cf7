"""RULA, the Rapid Upper Limb Assessment (McAtamney & Corlett 1993).

Group A (upper arm, lower arm, wrist, wrist twist) -> Table A; group B (neck, trunk, legs) -> Table
B; each plus the muscle-use and force/load scores gives scores C and D; Table C gives the grand
score 1-7 and its action level 1-4. Bands and tables: :mod:`jackpy.ergonomics.constants`. Every
adjustment (shoulder raised, arm abducted, arm supported, working across the midline or out to the
side, wrist deviated, neck/trunk twisted or side-bent) is measured from the posture and overridable
by ``task.overrides``; with ``task.side == "worst"`` both arms are scored and the higher Table A
score is reported. The worst contributor is the part whose return to its lowest score would lower
the grand score most (ties: the part nearest its own top score).
"""

from __future__ import annotations

from typing import Any

from jackpy.ergonomics import constants as C
from jackpy.ergonomics.base import Assessment, Method, Task, adjustment, band, register
from jackpy.ergonomics.posture import Posture
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

VALIDITY = ("standing or seated static postures; RULA scores the posture held for most of the cycle or "
            "the worst one; upper arm flexion -60..180°, trunk -30..120°, neck -45..90°")


def upper_arm_score(flexion: float) -> int:
    """Upper arm base score 1-4 from its flexion (degrees, + forward)."""
    if flexion <= -C.RULA_UPPER_ARM_EXTENSION_DEG:
        return 2
    return band(flexion, C.RULA_UPPER_ARM_FLEXION_DEG, True)


def lower_arm_score(elbow_flexion: float) -> int:
    lo, hi = C.RULA_LOWER_ARM_DEG
    return 1 if lo <= elbow_flexion < hi else 2


def wrist_score(flexion: float) -> int:
    a = abs(flexion)
    return 1 if a <= C.NEUTRAL_BAND_DEG else (2 if a < C.RULA_WRIST_DEG else 3)


def neck_score(flexion: float) -> int:
    if flexion < -C.NEUTRAL_BAND_DEG:
        return 4
    return band(flexion, C.RULA_NECK_DEG, True)


def trunk_score(flexion: float) -> int:
    if abs(flexion) <= C.NEUTRAL_BAND_DEG:
        return 1
    if flexion < 0:
        return 2  # extension: RULA gives no band; scored as the 0-20° band (flagged)
    return band(flexion, C.RULA_TRUNK_DEG, True) + 1


def load_score(task: Task) -> int:
    kg = task.load_kg
    lo, hi = C.RULA_LOAD_KG
    held = task.static or task.repeated
    if task.shock or (kg >= hi and held):
        return 3
    if kg >= lo and held or kg >= hi:
        return 2
    if kg >= lo:
        return 1
    return 0


def action_level(score: int) -> tuple[int, str]:
    for top, level, text in C.RULA_ACTION:
        if score <= top:
            return level, text
    return C.RULA_ACTION[-1][1], C.RULA_ACTION[-1][2]


#: the highest score of each part (base plus adjustments)
_TOP = {"upper_arm": 6, "lower_arm": 3, "wrist": 4, "wrist_twist": 2, "neck": 6, "trunk": 6, "legs": 2}


def grand_score(upper_arm: int, lower_arm: int, wrist: int, wrist_twist: int, neck: int, trunk: int, legs: int,
                extra: int) -> int:
    """Tables A, B and C for the part scores; ``extra`` = muscle use + force/load (added to C and D)."""
    a = int(C.RULA_TABLE_A[upper_arm - 1, lower_arm - 1, wrist - 1, wrist_twist - 1]) + extra
    b = int(C.RULA_TABLE_B[neck - 1, trunk - 1, legs - 1]) + extra
    return int(C.RULA_TABLE_C[min(a, 8) - 1, min(b, 7) - 1])


def _arm(p: Posture, side: str, task: Task) -> dict[str, Any]:
    a = p.arms[side]
    adj: dict[str, Any] = {}
    ua = upper_arm_score(a.upper_arm_flexion)
    ua += adjustment(task, "shoulder_raised", a.shoulder_elevation > C.SHOULDER_RAISED_DEG, adj)
    ua += adjustment(task, "arm_abducted", a.upper_arm_abduction > C.ARM_ABDUCTED_DEG, adj)
    ua -= adjustment(task, "arm_supported", task.arm_supported, adj)
    ua = min(max(ua, 1), 6)
    la = lower_arm_score(a.elbow_flexion)
    la += adjustment(task, "across_midline_or_out",
                     a.hand_across_midline_m > 0.0 or a.forearm_out > C.FOREARM_OUT_DEG, adj)
    la = min(la, 3)
    wr = wrist_score(a.wrist_flexion)
    wr += adjustment(task, "wrist_deviated", abs(a.wrist_deviation) > C.WRIST_DEVIATION_DEG, adj)
    wr = min(wr, 4)
    tw = 1 + adjustment(task, "wrist_twist_end", abs(a.forearm_pronation) > C.WRIST_TWIST_END_DEG, adj)
    table_a = int(C.RULA_TABLE_A[ua - 1, la - 1, wr - 1, tw - 1])
    return {"upper_arm": ua, "lower_arm": la, "wrist": wr, "wrist_twist": tw, "table_a": table_a,
            "adjustments": adj}


def _parts_sum(arm: dict[str, Any]) -> int:
    return sum(v for k, v in arm.items() if k in ("upper_arm", "lower_arm", "wrist", "wrist_twist"))


def assess(figure: Figure, task: Task, posture: Posture, fk: FKResult | None = None) -> Assessment:
    """RULA of ``posture`` under ``task``; see the module docstring."""
    p = posture
    flags: list[str] = []
    muscle = 1 if (task.static or task.repeated) else 0
    force = load_score(task)
    sides = ("left", "right") if task.side == "worst" else (task.side,)
    arms = {s: _arm(p, s, task) for s in sides}
    side = max(sides, key=lambda s: (arms[s]["table_a"], _parts_sum(arms[s])))  # ties: the more loaded arm
    arm = arms[side]
    adj: dict[str, Any] = {}
    neck = neck_score(p.neck_flexion)
    neck += adjustment(task, "neck_twisted", abs(p.neck_twist) > C.TWIST_DEG, adj)
    neck += adjustment(task, "neck_side_bent", abs(p.neck_side_bend) > C.SIDE_BEND_DEG, adj)
    neck = min(neck, 6)
    trunk = 1 if task.seated_supported else trunk_score(p.trunk_flexion)
    trunk += adjustment(task, "trunk_twisted", abs(p.trunk_twist) > C.TWIST_DEG, adj)
    trunk += adjustment(task, "trunk_side_bent", abs(p.trunk_side_bend) > C.SIDE_BEND_DEG, adj)
    trunk = min(trunk, 6)
    balanced = task.seated or len(p.feet_bearing()) == 2
    legs = 1 if adjustment(task, "legs_supported", balanced, adj) else 2
    table_b = int(C.RULA_TABLE_B[neck - 1, trunk - 1, legs - 1])
    score_c = arm["table_a"] + muscle + force
    score_d = table_b + muscle + force
    grand = int(C.RULA_TABLE_C[min(score_c, 8) - 1, min(score_d, 7) - 1])
    level, text = action_level(grand)
    if p.trunk_flexion < -C.NEUTRAL_BAND_DEG and not task.seated_supported:
        flags.append(f"trunk extended {-p.trunk_flexion:.0f}°: RULA has no extension band; scored 2 (0-20°)")
    if p.arms[side].upper_arm_flexion > 180 or p.trunk_flexion > 120:
        flags.append("posture outside the range RULA's figures show")
    scores = {"upper_arm": arm["upper_arm"], "lower_arm": arm["lower_arm"], "wrist": arm["wrist"],
              "wrist_twist": arm["wrist_twist"], "neck": neck, "trunk": trunk, "legs": legs}
    drops = {k: grand - grand_score(**{**scores, k: 1}, extra=muscle + force) for k in scores}
    worst = max(scores, key=lambda k: (drops[k], (scores[k] - 1) / (_TOP[k] - 1)))
    ws = {"side": side, "upper_arm": arm["upper_arm"], "lower_arm": arm["lower_arm"], "wrist": arm["wrist"],
          "wrist_twist": arm["wrist_twist"], "table_a": arm["table_a"], "muscle_use": muscle,
          "force_load": force, "score_c": score_c, "neck": neck, "trunk": trunk, "legs": legs,
          "table_b": table_b, "score_d": score_d, "grand_score": grand, "action_level": level,
          "adjustments": {**arm["adjustments"], **adj},
          "arms": {s: {k: v for k, v in a.items() if k != "adjustments"} for s, a in arms.items()}}
    a = p.arms[side]
    measured = {"upper_arm_flexion": a.upper_arm_flexion, "upper_arm_abduction": a.upper_arm_abduction,
                "shoulder_elevation": a.shoulder_elevation, "elbow_flexion": a.elbow_flexion,
                "forearm_out": a.forearm_out, "hand_across_midline_m": a.hand_across_midline_m,
                "wrist_flexion": a.wrist_flexion, "wrist_deviation": a.wrist_deviation,
                "forearm_pronation": a.forearm_pronation, "neck_flexion": p.neck_flexion,
                "neck_side_bend": p.neck_side_bend, "neck_twist": p.neck_twist, "trunk_flexion": p.trunk_flexion,
                "trunk_side_bend": p.trunk_side_bend, "trunk_twist": p.trunk_twist,
                "feet_bearing": p.feet_bearing()}
    return Assessment("rula", grand, level, text, ws, measured, p.FRAME, flags, worst)


METHOD = register(Method("rula", "RULA (Rapid Upper Limb Assessment)",
                         "McAtamney L. & Corlett E.N. (1993) Applied Ergonomics 24(2):91-99", VALIDITY, assess))
