"""Fitts timing: Table 6.1 of [SH6] row by row, clamping, validity flags, monotonicity."""

import math

import pytest

from jackpy.tasks import fitts

# Table 6.1 as the book prints it: actor, action, ID, Fitts (ms), scaled (ms)
TABLE_6_1 = [
    ("John", "Look twf-1", 2.96, 321, 963),
    ("John", "Turn twf-1", 5.47, 335, 1004),
    ("John", "Look tglJ-2", 4.19, 566, 1697),
    ("John", "Look twf-2", 4.01, 530, 1590),
    ("John", "Look Jane", 4.64, 655, 1966),
    ("Jane", "Look twf-3", 4.28, 584, 876),
    ("Jane", "Look tglJ-1", 3.64, 456, 685),
    ("Jane", "Turn tglJ-1", 5.39, 329, 493),
    ("Jane", "Look twf-2", 4.16, 560, 840),
    ("Jane", "Turn twf-2", 4.99, 299, 449),
    ("Jane", "Look John", 4.33, 594, 891),
]


@pytest.mark.parametrize("actor,action,idx,fitts_ms,scaled_ms", TABLE_6_1)
def test_table_6_1_row(actor, action, idx, fitts_ms, scaled_ms):
    limb = "head" if action.startswith("Look") else "arm"
    pace = fitts.BOOK_PACE["male" if actor == "John" else "female"]
    t = fitts.timing(actor, action, limb, 0.0, pace, index=idx)
    assert round(t.raw_ms) == fitts_ms
    assert round(t.scaled_ms) == scaled_ms
    assert t.flag == "ok"


def test_arm_amplitude_inverse():
    # digest §4 claim 2: the Turn IDs are amplitudes of 22.16, 20.97 and 15.89 cm with W = 1 cm
    for a_cm, idx in ((22.16, 5.47), (20.97, 5.39), (15.89, 4.99)):
        assert fitts.arm_id(a_cm) == pytest.approx(idx, abs=0.005)
        assert fitts.timing("x", "turn", "arm", a_cm, 1.0).flag == "ok"


def test_clamping_and_flags():
    cfg = fitts.FittsConfig()
    zero = fitts.timing("John", "look", "head", 0.0, 3.0)
    assert zero.flag == "clamped" and zero.scaled_ms == pytest.approx(3.0 * cfg.t_min_ms)
    tiny = fitts.timing("John", "turn", "arm", 0.4, 1.5)  # A < W/2 → ID < 0
    assert tiny.flag == "clamped" and tiny.scaled_ms == pytest.approx(150.0)
    far = fitts.timing("John", "turn", "arm", 60.0, 1.0)
    assert far.flag == "extrapolated" and far.raw_ms == pytest.approx(74 * math.log2(120) - 70)
    assert fitts.timing("x", "look", "head", 20.0, 1.0).flag == "extrapolated"
    with pytest.raises(ValueError):
        fitts.head_id(5.0, width_deg=0.3)


def test_monotone_in_amplitude_width_and_pace():
    a = [fitts.timing("x", "r", "arm", d, 1.0).raw_ms for d in (5, 10, 20, 30)]
    assert a == sorted(a) and len(set(a)) == 4
    assert fitts.arm_id(10, 2.0) < fitts.arm_id(10, 1.0)
    assert fitts.timing("x", "r", "arm", 10, 3.0).scaled_ms == pytest.approx(
        2 * fitts.timing("x", "r", "arm", 10, 1.5).scaled_ms)


def test_table_csv_columns():
    text = fitts.table_csv([fitts.timing("John", "Turn twf-1", "arm", 22.16, 3.0)])
    head, row = text.strip().split("\n")
    assert head.split(",") == fitts.TABLE_COLUMNS
    assert row.startswith("John,Turn twf-1,arm,")
