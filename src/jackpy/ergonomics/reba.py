"""REBA, the Rapid Entire Body Assessment (Hignett & McAtamney 2000).

Group A (trunk, neck, legs) -> Table A, plus the load/force score = score A; group B (upper arm,
lower arm, wrist) -> Table B, plus the coupling score = score B; Table C, plus the activity score,
gives the REBA score 1-15 and its action level 0-4. Adjustments are measured from the posture and
overridable by ``task.overrides``; with ``task.side == "worst"`` the arm with the higher Table B
score is reported. The worst contributor is the part whose return to its lowest score would lower
Table C most (ties: the part nearest its own top score).
"""

from __future__ import annotations

from typing import Any

from jackpy.ergonomics import constants as C
from jackpy.ergonomics.base import Assessment, Method, Task, adjustment, band, register
from jackpy.ergonomics.posture import Posture
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

VALIDITY = ("whole-body static or dynamic postures; upper arm flexion -60..180°, trunk -30..120°, "
            "knee flexion 0..150°")


def trunk_score(flexion: float) -> int:
    """Trunk base score 1-4 (degrees, + flexion, - extension)."""
    if abs(flexion) <= C.NEUTRAL_BAND_DEG:
        return 1
    lo, hi = C.REBA_TRUNK_DEG
    if flexion < 0:
        return 2 if -flexion <= lo else 3
    return band(flexion, C.REBA_TRUNK_DEG, False) + 1


def neck_score(flexion: float) -> int:
    return 2 if (flexion > C.REBA_NECK_DEG or flexion < -C.NEUTRAL_BAND_DEG) else 1


def upper_arm_score(flexion: float) -> int:
    if flexion < -C.REBA_UPPER_ARM_EXTENSION_DEG:
        return 2
    return band(flexion, C.REBA_UPPER_ARM_FLEXION_DEG, False)


def lower_arm_score(elbow_flexion: float) -> int:
    lo, hi = C.REBA_LOWER_ARM_DEG
    return 1 if lo <= elbow_flexion <= hi else 2


def wrist_score(flexion: float) -> int:
    return 1 if abs(flexion) <= C.REBA_WRIST_DEG else 2


def load_score(task: Task) -> int:
    lo, hi = C.REBA_LOAD_KG
    kg = task.load_kg
    s = 0 if kg < lo else (1 if kg <= hi else 2)
    return s + (1 if task.shock else 0)


def action_level(score: int) -> tuple[int, str, str]:
    for top, level, risk, text in C.REBA_ACTION:
        if score <= top:
            return level, risk, text
    return C.REBA_ACTION[-1][1:]


#: the highest score of each part (base plus adjustments)
_TOP = {"trunk": 5, "neck": 3, "legs": 4, "upper_arm": 6, "lower_arm": 2, "wrist": 3}


def table_c_of(trunk: int, neck: int, legs: int, upper_arm: int, lower_arm: int, wrist: int, load: int,
               coupling: int) -> int:
    """Tables A, B and C for the part scores plus the load and coupling scores."""
    a = int(C.REBA_TABLE_A[neck - 1, trunk - 1, legs - 1]) + load
    b = int(C.REBA_TABLE_B[lower_arm - 1, upper_arm - 1, wrist - 1]) + coupling
    return int(C.REBA_TABLE_C[min(a, 12) - 1, min(b, 12) - 1])


def _arm(p: Posture, side: str, task: Task) -> dict[str, Any]:
    a = p.arms[side]
    adj: dict[str, Any] = {}
    ua = upper_arm_score(a.upper_arm_flexion)
    ua += adjustment(task, "arm_abducted", a.upper_arm_abduction > C.ARM_ABDUCTED_DEG, adj)
    ua += adjustment(task, "shoulder_raised", a.shoulder_elevation > C.SHOULDER_RAISED_DEG, adj)
    ua -= adjustment(task, "arm_supported", task.arm_supported, adj)
    ua = min(max(ua, 1), 6)
    la = lower_arm_score(a.elbow_flexion)
    wr = wrist_score(a.wrist_flexion)
    wr += adjustment(task, "wrist_deviated_or_twisted",
                     abs(a.wrist_deviation) > C.WRIST_DEVIATION_DEG or abs(a.forearm_pronation) > C.WRIST_TWIST_END_DEG,
                     adj)
    wr = min(wr, 3)
    return {"upper_arm": ua, "lower_arm": la, "wrist": wr, "table_b": int(C.REBA_TABLE_B[la - 1, ua - 1, wr - 1]),
            "adjustments": adj}


def _parts_sum(arm: dict[str, Any]) -> int:
    return sum(v for k, v in arm.items() if k in ("upper_arm", "lower_arm", "wrist", "wrist_twist"))


def assess(figure: Figure, task: Task, posture: Posture, fk: FKResult | None = None) -> Assessment:
    """REBA of ``posture`` under ``task``; see the module docstring."""
    p = posture
    adj: dict[str, Any] = {}
    flags: list[str] = []
    trunk = trunk_score(p.trunk_flexion)
    trunk += adjustment(task, "trunk_twisted_or_side_bent",
                        abs(p.trunk_twist) > C.TWIST_DEG or abs(p.trunk_side_bend) > C.SIDE_BEND_DEG, adj)
    neck = neck_score(p.neck_flexion)
    neck += adjustment(task, "neck_twisted_or_side_bent",
                       abs(p.neck_twist) > C.TWIST_DEG or abs(p.neck_side_bend) > C.SIDE_BEND_DEG, adj)
    bearing = p.feet_bearing()
    bilateral = task.seated or task.walking or len(bearing) == 2
    legs = 1 if adjustment(task, "bilateral_weight_bearing", bilateral, adj) else 2
    knee = max((p.knee_flexion[s] for s in (bearing or ("left", "right"))), default=0.0)
    knee_add = 0 if task.seated else band(knee, C.REBA_KNEE_DEG, False) - 1
    legs += knee_add
    table_a = int(C.REBA_TABLE_A[neck - 1, trunk - 1, legs - 1])
    load = load_score(task)
    score_a = table_a + load
    sides = ("left", "right") if task.side == "worst" else (task.side,)
    arms = {s: _arm(p, s, task) for s in sides}
    side = max(sides, key=lambda s: (arms[s]["table_b"], _parts_sum(arms[s])))  # ties: the more loaded arm
    arm = arms[side]
    coupling = C.REBA_COUPLING[task.coupling]
    score_b = arm["table_b"] + coupling
    table_c = int(C.REBA_TABLE_C[min(score_a, 12) - 1, min(score_b, 12) - 1])
    activity = int(task.static) + int(task.repeated) + int(task.rapid_change)
    score = table_c + activity
    level, risk, text = action_level(score)
    if p.trunk_flexion > 120 or p.arms[side].upper_arm_flexion > 180:
        flags.append("posture outside the range REBA's figures show")
    scores = {"trunk": trunk, "neck": neck, "legs": legs, "upper_arm": arm["upper_arm"],
              "lower_arm": arm["lower_arm"], "wrist": arm["wrist"]}
    drops = {k: table_c - table_c_of(**{**scores, k: 1}, load=load, coupling=coupling) for k in scores}
    worst = max(scores, key=lambda k: (drops[k], (scores[k] - 1) / (_TOP[k] - 1)))
    ws = {"trunk": trunk, "neck": neck, "legs": legs, "knee_adjustment": knee_add, "table_a": table_a,
          "load_force": load, "score_a": score_a, "side": side, "upper_arm": arm["upper_arm"],
          "lower_arm": arm["lower_arm"], "wrist": arm["wrist"], "table_b": arm["table_b"], "coupling": coupling,
          "score_b": score_b, "table_c": table_c, "activity": activity, "reba_score": score,
          "action_level": level, "risk": risk, "adjustments": {**arm["adjustments"], **adj},
          "arms": {s: {k: v for k, v in a.items() if k != "adjustments"} for s, a in arms.items()}}
    a = p.arms[side]
    measured = {"trunk_flexion": p.trunk_flexion, "trunk_side_bend": p.trunk_side_bend, "trunk_twist": p.trunk_twist,
                "neck_flexion": p.neck_flexion, "neck_side_bend": p.neck_side_bend, "neck_twist": p.neck_twist,
                "knee_flexion": dict(p.knee_flexion), "feet_bearing": bearing,
                "upper_arm_flexion": a.upper_arm_flexion, "upper_arm_abduction": a.upper_arm_abduction,
                "shoulder_elevation": a.shoulder_elevation, "elbow_flexion": a.elbow_flexion,
                "wrist_flexion": a.wrist_flexion, "wrist_deviation": a.wrist_deviation,
                "forearm_pronation": a.forearm_pronation}
    return Assessment("reba", score, level, f"{risk} risk; action {text}", ws, measured, p.FRAME, flags, worst)


METHOD = register(Method("reba", "REBA (Rapid Entire Body Assessment)",
                         "Hignett S. & McAtamney L. (2000) Applied Ergonomics 31(2):201-205", VALIDITY, assess, (0, 4)))
