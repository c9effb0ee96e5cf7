"""Assessments as rows of text: for the ``jackpy ergo`` table, the report's sections, CSV and the panel."""

from __future__ import annotations

import math
from typing import Any

from jackpy.ergonomics.base import Assessment


def value_text(v: Any) -> str:
    """A worksheet value as short text (floats to 3 significant decimals, booleans yes/no)."""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        if math.isinf(v):
            return "inf"
        v = v + 0.0  # no "-0"
        return f"{v:.3g}" if abs(v) < 1000 else f"{v:.0f}"
    if isinstance(v, (list, tuple)):
        return ", ".join(value_text(x) for x in v) or "-"
    return str(v)


def flat(d: dict[str, Any], prefix: str = "") -> list[tuple[str, Any]]:
    """Nested dicts flattened to ``("a.b.c", value)``; lists of dicts numbered ``a[0].b``; an
    adjustment (``{"measured", "value", "overridden"}``) as its value, marked when overridden."""
    out: list[tuple[str, Any]] = []
    for k, v in d.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict) and set(v) == {"measured", "value", "overridden"}:  # an adjustment
            out.append((name, f"{value_text(v['value'])}" + (" (overridden)" if v["overridden"] else "")))
        elif isinstance(v, dict):
            out += flat(v, name + ".")
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for i, x in enumerate(v):
                out += flat(x, f"{name}[{i}].")
        else:
            out.append((name, v))
    return out


def headline(a: Assessment) -> str:
    """``rula 7 (level 4): investigate and change immediately``."""
    unit = f" {a.unit}" if a.unit else ""
    lvl = f" (level {a.level})" if a.level is not None else ""
    return f"{a.method} {value_text(float(a.score)) if isinstance(a.score, float) else a.score}{unit}{lvl}: {a.action}"


def text(a: Assessment) -> str:
    """A multi-line worksheet: headline, flags, worksheet values and posture measurements."""
    lines = [headline(a)]
    lines += [f"  ! {f}" for f in a.flags]
    lines.append("  worksheet:")
    lines += [f"    {k}: {value_text(v)}" for k, v in flat(a.worksheet)]
    lines.append(f"  posture ({a.frame}):")
    lines += [f"    {k}: {value_text(v)}" for k, v in flat(a.posture)]
    return "\n".join(lines)


def json_ready(o: Any) -> Any:
    """``o`` with numpy scalars as Python numbers and non-finite floats as None (strict JSON)."""
    if isinstance(o, dict):
        return {str(k): json_ready(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [json_ready(v) for v in o]
    if hasattr(o, "item") and not isinstance(o, (str, bytes)):
        o = o.item()
    if isinstance(o, float) and not math.isfinite(o):
        return None
    return o


#: action-level colours from the lowest level to the highest (RGB in [0, 1])
LEVEL_COLOURS = ((0.2, 0.7, 0.25), (0.85, 0.8, 0.15), (0.95, 0.5, 0.1), (0.85, 0.1, 0.1))


def level_colour(a: Assessment) -> tuple[float, float, float]:
    """Green (the method's lowest action level) through yellow and orange to red (its highest)."""
    from jackpy.ergonomics.base import method

    lo, hi = method(a.method).levels
    if a.level is None:
        return LEVEL_COLOURS[0]
    t = (a.level - lo) / max(hi - lo, 1)
    return LEVEL_COLOURS[min(len(LEVEL_COLOURS) - 1, max(0, round(t * (len(LEVEL_COLOURS) - 1))))]


_SPINE = ("l5", "l4", "l3", "l2", "l1") + tuple(f"t{i}" for i in range(12, 0, -1))
_PART_SEGMENTS = {
    "upper_arm": ("{side}_upper_arm",), "lower_arm": ("{side}_forearm", "{side}_forearm_mid", "{side}_forearm_distal"),
    "wrist": ("{side}_palm",), "neck": ("neck", "head"), "trunk": _SPINE, "back": _SPINE,
    "legs": tuple(f"{s}_{p}" for s in ("left", "right") for p in ("thigh", "shank")),
    "arms": tuple(f"{s}_{p}" for s in ("left", "right") for p in ("upper_arm", "forearm")),
    "l5_s1": ("l5", "l4", "l3"),
}


def worst_segments(a: Assessment) -> list[str]:
    """The segments of the body part an assessment names as its worst contributor (a method's part
    name, NIOSH's multiplier -> the arms, or a joint name -> the segment it moves)."""
    side = a.worksheet.get("side", "right") if isinstance(a.worksheet.get("side"), str) else "right"
    w = a.worst or ""
    if w in _PART_SEGMENTS:
        return [s.format(side=side) for s in _PART_SEGMENTS[w]]
    if a.method == "niosh":
        return list(_PART_SEGMENTS["arms"])
    for part in ("shoulder", "elbow", "wrist", "hip", "knee", "ankle"):
        if w.endswith(part):
            s = w[: -len(part) - 1]
            return {"shoulder": [f"{s}_upper_arm"], "elbow": [f"{s}_forearm"], "wrist": [f"{s}_palm"],
                    "hip": [f"{s}_thigh"], "knee": [f"{s}_shank"], "ankle": [f"{s}_foot"]}[part]
    if w == "atlanto_occipital":
        return ["head"]
    return []
