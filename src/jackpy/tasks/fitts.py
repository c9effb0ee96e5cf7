"""Fitts' law timing exactly as [SH6] §6.1.7 gives it (digest task-commands.md §2.3).

Arm (Fitts & Peterson, eq. 6.3): ``MT = 74·ID − 70`` ms, ``ID = log2(2A/W)``, A and W in cm, W = 1 cm.
Head (Jagacinski & Monk, eq. 6.4–6.5): ``MT = 199·ID' − 268`` ms, ``ID' = log2(2A/(W − W0))``,
A, W, W0 in degrees, W0 = 0.33°. The book omits the log base; log2 is the only base giving plausible
amplitudes for Table 6.1 (digest §2.3). The head W is not printed; 1° is jackpy's default.

Degenerate cases (A ≤ W/2, or a raw time below ``t_min_ms``) are clamped to ``t_min_ms`` and flagged;
amplitudes outside the validated ranges (arm 5–30 cm, head 2.45–7.50°) are flagged as extrapolated.
The duration is ``pace × max(raw, t_min)``: the book scales the man by 3 ("sluggish") and the
woman by 1.5 ("quick but not too quick").
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import asdict, dataclass

ARM_A_MS, ARM_B_MS = -70.0, 74.0
HEAD_A_MS, HEAD_B_MS = -268.0, 199.0
ARM_VALID_CM = (5.0, 30.0)
HEAD_VALID_DEG = (2.45, 7.50)
BOOK_PACE = {"male": 3.0, "female": 1.5}


@dataclass(frozen=True)
class FittsConfig:
    """Every timing constant in one place (reported with the timing table)."""

    arm_width_cm: float = 1.0
    head_width_deg: float = 1.0
    head_w0_deg: float = 0.33
    t_min_ms: float = 100.0
    t_constraint_s: float = 0.2


def arm_id(amplitude_cm: float, width_cm: float = 1.0) -> float:
    """Index of difficulty (bits) of an arm move; ``-inf`` at A = 0."""
    return math.log2(2.0 * amplitude_cm / width_cm) if amplitude_cm > 0 else -math.inf


def head_id(amplitude_deg: float, width_deg: float = 1.0, w0_deg: float = 0.33) -> float:
    """ID' (bits) of a head move (peg of diameter W0 into a hole W); ``-inf`` at A = 0."""
    if width_deg <= w0_deg:
        raise ValueError(f"head target width {width_deg}° must exceed W0 = {w0_deg}°")
    return math.log2(2.0 * amplitude_deg / (width_deg - w0_deg)) if amplitude_deg > 0 else -math.inf


def arm_ms(index: float) -> float:
    """Raw eq. 6.3 movement time (ms) for an ID in bits (may be negative)."""
    return ARM_B_MS * index + ARM_A_MS


def head_ms(index: float) -> float:
    """Raw eq. 6.4 movement time (ms) for an ID' in bits (may be negative)."""
    return HEAD_B_MS * index + HEAD_A_MS


@dataclass
class Timing:
    """One row of the timing table: durations in ms, A in cm (arm) or degrees (head)."""

    actor: str
    action: str
    limb: str
    amplitude: float
    width: float
    index: float
    raw_ms: float
    scaled_ms: float
    pace: float
    flag: str = "ok"
    start_s: float = 0.0

    @property
    def seconds(self) -> float:
        return self.scaled_ms / 1000.0


def timing(actor: str, action: str, limb: str, amplitude: float, pace: float,
           config: FittsConfig = FittsConfig(), index: float | None = None) -> Timing:
    """Fitts time of one move. ``limb`` is ``"arm"`` (A in cm) or ``"head"`` (A in degrees);
    ``index`` overrides the ID computed from A (to reproduce a printed table)."""
    if limb == "arm":
        width = config.arm_width_cm
        idx = arm_id(amplitude, width) if index is None else index
        raw = arm_ms(idx) if math.isfinite(idx) else -math.inf
        valid = ARM_VALID_CM
    elif limb == "head":
        width = config.head_width_deg
        idx = head_id(amplitude, width, config.head_w0_deg) if index is None else index
        raw = head_ms(idx) if math.isfinite(idx) else -math.inf
        valid = HEAD_VALID_DEG
    else:
        raise ValueError(f"limb must be 'arm' or 'head', not {limb!r}")
    flag = "ok"
    if raw < config.t_min_ms:
        flag = "clamped"
    elif index is None and not valid[0] <= amplitude <= valid[1]:
        flag = "extrapolated"
    effective = max(raw, config.t_min_ms)
    return Timing(actor, action, limb, float(amplitude), width, idx if math.isfinite(idx) else float("nan"),
                  raw if math.isfinite(raw) else float("nan"), pace * effective, pace, flag)


TABLE_COLUMNS = ["actor", "action", "limb", "start_s", "amplitude", "width", "index", "raw_ms", "scaled_ms",
                 "pace", "flag"]


def table_csv(rows: list[Timing]) -> str:
    """The timing table as CSV text (A in cm for the arm, degrees for the head; times in ms)."""
    out = io.StringIO()
    w = csv.DictWriter(out, TABLE_COLUMNS, lineterminator="\n")
    w.writeheader()
    for r in rows:
        d = asdict(r)
        w.writerow({k: (f"{d[k]:.4f}" if isinstance(d[k], float) else d[k]) for k in TABLE_COLUMNS})
    return out.getvalue()
