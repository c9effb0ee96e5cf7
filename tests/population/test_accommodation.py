"""Accommodation table and binding dimension; the journal drops a torn row and keeps the rest."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from jackpy.population.accommodation import accommodation, binding
from jackpy.population.evaluate import columns
from jackpy.population.journal import PARTIAL, Journal, SweepError
from jackpy.population.generate import CONTROLLED, Body
from jackpy.population.study import parse_study

STUDY = parse_study({"jackpy_study": 1, "reach": ["shelf.handle"], "view": ["gauge"]})


def _rows(n: int = 200) -> list[dict]:
    rng = np.random.default_rng(0)
    rows = []
    for i in range(n):
        values = {k: float(v) for k, v in zip(CONTROLLED, rng.normal(1.0, 0.1, len(CONTROLLED)))}
        reach = int(values["stature"] > 1.0)  # short bodies fail the shelf
        view = int(values["sitting_height"] < 1.1)  # tall trunks fail the gauge
        rows.append({"index": i, "sex": "female" if i % 2 else "male", "label": "mc", **values,
                     "reach:shelf.handle": reach, "reach:shelf.handle:shortfall_m": 0.0,
                     "view:gauge": view, "view:gauge:visible": 1.0, "all": reach * view})
    return rows


def test_shares_and_binding_dimensions() -> None:
    rows = _rows()
    table = {a.criterion: a for a in accommodation(STUDY, rows)}
    reach = table["reach:shelf.handle"]
    assert reach.share == pytest.approx(np.mean([r["reach:shelf.handle"] for r in rows]))
    assert (reach.binding_dimension, reach.fails_when) == ("stature", "small")
    view = table["view:gauge"]
    assert (view.binding_dimension, view.fails_when) == ("sitting_height", "large")
    assert table["all"].passed == sum(r["all"] for r in rows)
    assert table["all"].share_female == pytest.approx(np.mean([r["all"] for r in rows if r["sex"] == "female"]))
    assert binding(np.ones(5), {"stature": np.arange(5.0)}) == (None, None, None)


def test_journal_keeps_rows_drops_a_torn_line_and_refuses_other_sweeps(tmp_path: Path) -> None:
    cols = columns(STUDY)
    j = Journal(tmp_path)
    rows = _rows(5)
    j.start({"columns": cols}, [Body(r["index"], r["sex"], {k: r[k] for k in CONTROLLED}) for r in rows])
    j.append(cols, rows[:3])
    with open(tmp_path / PARTIAL, "a") as f:
        f.write("3,female,mc,0.99")  # a kill in the middle of a row
    kept = j.finished(cols)
    assert sorted(kept) == [0, 1, 2] and kept[1] == rows[1]
    j.append(cols, rows[3:])
    assert sorted(j.finished(cols)) == [0, 1, 2, 3, 4]
    assert [b.index for b in j.bodies()] == list(range(5))
    with pytest.raises(SweepError):
        j.finished(cols[:-1])
    with pytest.raises(SweepError):
        Journal(tmp_path / "nothing").manifest()
