"""transforms.close: np.allclose's answer without its overhead (the writer asks it per site)."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from jackpy.peabody.transforms import close

VALUE = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.sampled_from([0.0, 1.0, 1 + 1e-13, 1e-16]))


@settings(max_examples=300, deadline=None, database=None)
@given(st.lists(st.tuples(VALUE, VALUE), min_size=1, max_size=4),
       st.sampled_from([(1e-15, 0.0), (1e-12, 0.0), (1e-12, 1e-5), (1e-9, 0.0)]))
def test_close_answers_as_np_allclose(pairs: list[tuple[float, float]], tols: tuple[float, float]) -> None:
    a, b = np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])
    atol, rtol = tols
    with np.errstate(all="ignore"):
        expected = bool(np.allclose(a, b, atol=atol, rtol=rtol))
    assert close(a, b, atol, rtol) == expected


def test_close_takes_a_scalar_or_a_tuple_as_the_reference() -> None:
    assert close(np.array([1.0, 1.0 + 1e-16]), 1.0, 1e-15)
    assert not close(np.array([0.0, 0.0, 0.0, 1.0 + 1e-14]), (0, 0, 0, 1), 1e-15)
