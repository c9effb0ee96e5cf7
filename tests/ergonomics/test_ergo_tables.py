"""The published tables' structure: sizes, ranges and monotonicity (a worse part never lowers a score)."""

import numpy as np
import pytest

from jackpy.ergonomics import constants as C
from jackpy.ergonomics import methods


@pytest.mark.parametrize("name,shape,top", [
    ("RULA_TABLE_A", (6, 3, 4, 2), 9), ("RULA_TABLE_B", (6, 6, 2), 9), ("RULA_TABLE_C", (8, 7), 7),
    ("REBA_TABLE_A", (3, 5, 4), 9), ("REBA_TABLE_B", (2, 6, 3), 9), ("REBA_TABLE_C", (12, 12), 12),
])
def test_rula_reba_tables(name, shape, top):
    t = getattr(C, name)
    assert t.shape == shape and t.min() == 1 and t.max() == top
    for axis in range(t.ndim):
        assert (np.diff(t, axis=axis) >= 0).all(), f"{name} decreases along axis {axis}"


def test_published_cells():
    # RULA: Table A for upper arm 3, lower arm 2, wrist 2, twist 1 is 4; Table B neck 2, trunk 3, legs 1
    # is 4; Table C (5, 5) is 6 and (7, 7) is 7
    assert C.RULA_TABLE_A[2, 1, 1, 0] == 4 and C.RULA_TABLE_B[1, 2, 0] == 4
    assert C.RULA_TABLE_C[4, 4] == 6 and C.RULA_TABLE_C[6, 6] == 7
    # REBA: Table A neck 1 trunk 1 legs 1 is 1, neck 3 trunk 5 legs 4 is 9; Table C (12, 12) is 12
    assert C.REBA_TABLE_A[0, 0, 0] == 1 and C.REBA_TABLE_A[2, 4, 3] == 9 and C.REBA_TABLE_C[11, 11] == 12


def test_niosh_fm_table_falls_with_frequency_and_duration():
    fm = C.NIOSH_FM
    assert fm.shape == (17, 6)
    assert (np.diff(fm, axis=0) <= 0).all()
    for v in (0, 1):  # longer work never raises the multiplier
        assert (fm[:, v] >= fm[:, 2 + v]).all() and (fm[:, 2 + v] >= fm[:, 4 + v]).all()
    assert (fm[:, 0::2] <= fm[:, 1::2]).all()  # V >= 75 cm never lower than V < 75 cm


def test_every_method_registered_with_its_source():
    ms = methods()
    assert {"rula", "reba", "owas", "niosh", "lowback", "capable"} <= set(ms)
    for m in ms.values():
        assert m.source and m.validity and m.levels[0] < m.levels[1]
