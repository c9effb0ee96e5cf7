"""The revised NIOSH lifting equation (Waters et al. 1993; Applications Manual, Waters et al. 1994).

``RWL = LC · HM · VM · DM · AM · FM · CM`` (kg; LC = 23 kg), ``LI = load / RWL``. Metric multipliers:
``HM = 25/H`` (1 for H ≤ 25 cm, 0 beyond 63 cm), ``VM = 1 - 0.003 |V - 75|`` (0 above 175 cm),
``DM = 0.82 + 4.5/D`` (1 for D ≤ 25 cm, 0 beyond 175 cm), ``AM = 1 - 0.0032 A`` (0 beyond 135°); FM
and CM from the manual's Tables 5 and 7 (:mod:`jackpy.ergonomics.constants`).

Measured from the posture when the lift does not give them (the origin of the lift is the figure's
posture): H, the horizontal distance (cm) from the midpoint of the ankle joint centres to the
midpoint of the two grip sites; V, the grips' height above the floor (the lowest foot contact,
cm); A, the angle (degrees) between that horizontal line and the body's forward direction; the
coupling's "fingers flexed about 90°" from the fingers of both hands. Values the multipliers zero
(H > 63, V > 175, D > 175, A > 135 cm/°) are scored as the equation says and flagged. A frequency
between two table rows takes the next higher row (the conservative reading); below 0.2 lifts/min
it is 0.2 (the manual). Several lifts: the composite lifting index (Waters et al. 1994, multi-task
procedure) is the score.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

import numpy as np

from jackpy.ergonomics import constants as C
from jackpy.ergonomics.base import Assessment, ErgonomicsError, Lift, Method, Task, register
from jackpy.ergonomics.posture import Posture
from jackpy.peabody.kinematics import FKResult
from jackpy.peabody.model import Figure

VALIDITY = ("two-handed, smooth lifting or lowering of a load in front of the body, unrestricted posture, "
            "good footing, moderate environment; H 25-63 cm, V 0-175 cm, D 25-175 cm, A 0-135°, "
            "F 0.2-15 lifts/min, work up to 8 h")


def hm(h_cm: float) -> float:
    lo, hi = C.NIOSH_H_CM
    return 1.0 if h_cm <= lo else (0.0 if h_cm > hi else lo / h_cm)


def vm(v_cm: float) -> float:
    return 0.0 if v_cm > C.NIOSH_V_MAX_CM else 1.0 - 0.003 * abs(v_cm - C.NIOSH_V_REF_CM)


def dm(d_cm: float) -> float:
    lo, hi = C.NIOSH_D_CM
    return 1.0 if d_cm <= lo else (0.0 if d_cm > hi else 0.82 + 4.5 / d_cm)


def am(a_deg: float) -> float:
    return 0.0 if a_deg > C.NIOSH_A_MAX_DEG else 1.0 - 0.0032 * a_deg


def _duration_column(duration_h: float) -> int:
    if not (isinstance(duration_h, (int, float)) and math.isfinite(duration_h)) or duration_h <= 0:
        raise ErgonomicsError(f"lift duration_h: must be > 0 hours, got {duration_h!r}")
    for k, top in enumerate(C.NIOSH_DURATIONS_H):
        if duration_h <= top:
            return k
    raise ErgonomicsError(f"lift duration_h {duration_h:g} h is off the NIOSH frequency table (at most 8 h)")


def fm(frequency: float, duration_h: float, v_cm: float) -> float:
    """Frequency multiplier (manual Table 5): lifts/min, work duration (h), V (cm)."""
    if not (isinstance(frequency, (int, float)) and math.isfinite(frequency)) or frequency <= 0:
        raise ErgonomicsError(f"lift frequency: must be > 0 lifts/min, got {frequency!r}")
    top = float(C.NIOSH_FREQUENCIES[-1])
    if frequency > top:
        raise ErgonomicsError(f"lift frequency {frequency:g} lifts/min is off the NIOSH frequency table "
                              f"(0.2-{top:g} lifts/min; above that FM = 0: the task needs redesign)")
    row = int(np.searchsorted(C.NIOSH_FREQUENCIES, max(frequency, 0.2) - 1e-12))
    col = 2 * _duration_column(duration_h) + (1 if v_cm >= C.NIOSH_V_REF_CM else 0)
    return float(C.NIOSH_FM[row, col])


def cm(coupling: str, v_cm: float) -> float:
    """Coupling multiplier (manual Table 7)."""
    if coupling not in C.NIOSH_CM:
        raise ErgonomicsError(f"lift coupling: {coupling!r} is not one of good, fair, poor, auto")
    return C.NIOSH_CM[coupling][1 if v_cm >= C.NIOSH_V_REF_CM else 0]


def coupling_type(lift: Lift, fingers_flexed: bool) -> str:
    """The manual's coupling decision tree (auto coupling)."""
    if lift.container:
        if not lift.optimal_object:
            return "poor"
        return "good" if lift.optimal_handles else ("fair" if fingers_flexed else "poor")
    if not lift.optimal_object:  # bulky loose object
        return "poor"
    return "good" if lift.optimal_handles else ("fair" if fingers_flexed else "poor")


def _check(lift: Lift, where: str) -> None:
    for k in ("load_kg", "h", "v", "a", "d", "dest_h", "dest_v", "dest_a"):
        v = getattr(lift, k)
        if v is not None and (not math.isfinite(v) or v < 0):
            raise ErgonomicsError(f"{where} {k}: must be >= 0, got {v!r}")
    if lift.coupling not in ("auto", "good", "fair", "poor"):
        raise ErgonomicsError(f"{where} coupling: {lift.coupling!r} is not one of good, fair, poor, auto")
    if lift.d is None and lift.dest_v is None:
        raise ErgonomicsError(f"{where}: give the vertical travel d (cm) or the destination height dest_v")


def validate_lifts(task: Task) -> None:
    """Check every lift's parameters (ErgonomicsError naming the lift and the parameter) without a
    posture: for commands to fail before any work."""
    for i, x in enumerate(task.lifts):
        where = f"lift {x.name or i + 1}"
        _check(x, where)
        fm(x.frequency, x.duration_h, C.NIOSH_V_REF_CM)
        if x.load_kg == 0 and task.load_kg == 0:
            raise ErgonomicsError(f"{where}: no load (give load_kg for the lift or the task)")


def measured_origin(p: Posture) -> dict[str, float]:
    """H, V (cm) and A (degrees) of the hands in ``p`` (see the module docstring)."""
    off = p.hands_mid - p.ankles_mid
    horiz = np.array([off[0], 0.0, off[2]])
    h = float(np.linalg.norm(horiz)) * 100.0
    v = float(p.hands_mid[1] - p.floor_m) * 100.0
    a = 0.0 if h < 1e-6 else float(np.degrees(np.arccos(np.clip(horiz @ p.forward / (h / 100.0), -1.0, 1.0))))
    return {"h": h, "v": v, "a": a}


def _rwl(h: float, v: float, d: float, a: float, f: float, dur: float, coupling: str) -> dict[str, float]:
    m = {"HM": hm(h), "VM": vm(v), "DM": dm(d), "AM": am(a), "FM": fm(f, dur, v), "CM": cm(coupling, v)}
    fi = C.NIOSH_LC_KG * m["HM"] * m["VM"] * m["DM"] * m["AM"] * m["CM"]
    return {"H_cm": h, "V_cm": v, "D_cm": d, "A_deg": a, **m, "FIRWL_kg": fi, "RWL_kg": fi * m["FM"]}


def _range_flags(r: dict[str, float], where: str) -> list[str]:
    out = []
    if r["H_cm"] > C.NIOSH_H_CM[1]:
        out.append(f"{where}: H {r['H_cm']:.0f} cm beyond 63 cm (HM = 0)")
    if r["V_cm"] > C.NIOSH_V_MAX_CM:
        out.append(f"{where}: V {r['V_cm']:.0f} cm above 175 cm (VM = 0)")
    if r["D_cm"] > C.NIOSH_D_CM[1]:
        out.append(f"{where}: D {r['D_cm']:.0f} cm beyond 175 cm (DM = 0)")
    if r["A_deg"] > C.NIOSH_A_MAX_DEG:
        out.append(f"{where}: A {r['A_deg']:.0f}° beyond 135° (AM = 0)")
    if r["FM"] == 0.0:
        out.append(f"{where}: frequency and duration give FM = 0")
    return out


def single_lift(lift: Lift, posture: Posture | None, where: str = "lift") -> dict[str, Any]:
    """One lift's worksheet: multipliers, RWL and LI at the origin (and the destination if given)."""
    _check(lift, where)
    origin = measured_origin(posture) if posture is not None else {}
    vals = {}
    for k in ("h", "v", "a"):
        val = getattr(lift, k)
        if val is None:
            if posture is None:
                raise ErgonomicsError(f"{where}: {k} not given and no posture to measure it from")
            val = origin[k]
        vals[k] = val
    d = lift.d if lift.d is not None else abs(lift.dest_v - vals["v"])
    fingers = None
    coupling = lift.coupling
    if coupling == "auto":
        fingers = (posture is not None and
                   float(np.mean([posture.finger_flexion(s) for s in posture.arms])) >= C.NIOSH_FINGERS_FLEXED_DEG)
        coupling = coupling_type(lift, bool(fingers))
    o = _rwl(vals["h"], vals["v"], d, vals["a"], lift.frequency, lift.duration_h, coupling)
    out: dict[str, Any] = {"name": lift.name, "load_kg": lift.load_kg, "frequency": lift.frequency,
                           "duration_h": lift.duration_h, "coupling": coupling, "fingers_flexed": fingers,
                           "measured": {k: getattr(lift, k) is None for k in ("h", "v", "a")}, "origin": o}
    flags = _range_flags(o, f"{where} origin")
    rwl = o["RWL_kg"]
    fi = o["FIRWL_kg"]
    if lift.dest_v is not None:
        dh = lift.dest_h if lift.dest_h is not None else vals["h"]
        da = lift.dest_a if lift.dest_a is not None else vals["a"]
        dst = _rwl(dh, lift.dest_v, d, da, lift.frequency, lift.duration_h, coupling)
        out["destination"] = dst
        flags += _range_flags(dst, f"{where} destination")
        if dst["RWL_kg"] < rwl:
            rwl, fi = dst["RWL_kg"], dst["FIRWL_kg"]
    out.update({"RWL_kg": rwl, "FIRWL_kg": fi, "LI": _ratio(lift.load_kg, rwl), "FILI": _ratio(lift.load_kg, fi),
                "flags": flags})
    return out


def _ratio(load: float, limit: float) -> float:
    if limit > 0:
        return load / limit
    return 0.0 if load == 0 else math.inf


def composite(lifts: list[dict[str, Any]], duration_h: float) -> dict[str, Any]:
    """Composite lifting index of single-lift worksheets (Waters et al. 1994 multi-task procedure):
    tasks in decreasing single-task LI; ``CLI = STLI_1 + sum_k FILI_k (1/FM(F_1..k) - 1/FM(F_1..k-1))``,
    FM at the summed frequency with task k's V."""
    order = sorted(range(len(lifts)), key=lambda i: -lifts[i]["LI"])
    first = lifts[order[0]]
    cli = first["LI"]
    total = first["frequency"]
    steps = [{"task": order[0], "STLI": first["LI"], "cumulative_frequency": total}]
    for i in order[1:]:
        t = lifts[i]
        v = t["origin"]["V_cm"]
        prev = _fm_capped(total, duration_h, v)
        total += t["frequency"]
        now = _fm_capped(total, duration_h, v)
        delta = math.inf if now == 0 or prev == 0 else t["FILI"] * (1.0 / now - 1.0 / prev)
        cli += delta
        steps.append({"task": i, "FILI": t["FILI"], "cumulative_frequency": total, "FM_cumulative": now,
                      "delta_LI": delta})
    return {"CLI": cli, "order": order, "steps": steps}


def _fm_capped(frequency: float, duration_h: float, v: float) -> float:
    return 0.0 if frequency > C.NIOSH_FREQUENCIES[-1] else fm(frequency, duration_h, v)


def level(li: float) -> tuple[int, str]:
    if li <= 1.0:
        return 1, "nominal risk for most healthy workers (LI <= 1)"
    if li <= 3.0:
        return 2, "increased risk for some workers (1 < LI <= 3): redesign"
    return 3, "high risk for many workers (LI > 3): redesign"


def assess(figure: Figure, task: Task, posture: Posture, fk: FKResult | None = None) -> Assessment:
    """RWL and LI (composite LI for several lifts) of ``task.lifts``; the figure's posture is the
    origin of every lift whose H, V or A is not given."""
    if not task.lifts:
        raise ErgonomicsError("niosh: the task has no lift (task lifts: [{d or dest_v, frequency, duration_h, "
                              "coupling, load_kg}])")
    lifts = [replace(x, load_kg=x.load_kg or task.load_kg) for x in task.lifts]
    sheets = [single_lift(x, posture, f"lift {x.name or i + 1}") for i, x in enumerate(lifts)]
    flags = [f for s in sheets for f in s.pop("flags")]
    ws: dict[str, Any] = {"lifts": sheets}
    if len(sheets) == 1:
        score = sheets[0]["LI"]
        ws.update({"RWL_kg": sheets[0]["RWL_kg"], "LI": score})
    else:
        comp = composite(sheets, max(x.duration_h for x in lifts))
        ws.update(comp)
        score = comp["CLI"]
    lv, text = level(score)
    origin = measured_origin(posture)
    o = sheets[0]["origin"]
    mults = {k: o[k] for k in ("HM", "VM", "DM", "AM", "FM", "CM")}
    worst = min(mults, key=lambda k: mults[k])
    return Assessment("niosh", score, lv, text, ws, {"H_cm": origin["h"], "V_cm": origin["v"], "A_deg": origin["a"]},
                      "H, V: cm in the world (V above the lowest foot contact); A: degrees from the body's forward "
                      "direction", flags, worst, unit="LI")


METHOD = register(Method("niosh", "NIOSH revised lifting equation",
                         "Waters T.R. et al. (1993) Ergonomics 36(7):749-776; Applications Manual (1994) "
                         "DHHS (NIOSH) 94-110", VALIDITY, assess, (1, 3)))
