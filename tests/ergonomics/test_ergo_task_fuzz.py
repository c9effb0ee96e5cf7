"""Task parameters from JSON-like data: a task or one ErgonomicsError, never anything else."""

from hypothesis import given, settings
from hypothesis import strategies as st

from jackpy.ergonomics import ErgonomicsError, Task
from jackpy.ergonomics.niosh import validate_lifts

KEYS = ["load_kg", "side", "static", "repeated", "coupling", "overrides", "lifts", "sex", "bogus"]
LIFT_KEYS = ["load_kg", "h", "v", "a", "d", "dest_v", "frequency", "duration_h", "coupling", "container", "x"]
values = st.one_of(st.none(), st.booleans(), st.integers(-5, 50), st.floats(allow_nan=True, allow_infinity=True),
                   st.sampled_from(["left", "right", "worst", "good", "poor", "both", "male", "x"]),
                   st.lists(st.integers(), max_size=2), st.dictionaries(st.text(max_size=3), st.booleans(), max_size=2))
lifts = st.lists(st.dictionaries(st.sampled_from(LIFT_KEYS), values, max_size=6), max_size=3)


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(st.sampled_from(KEYS), st.one_of(values, lifts), max_size=6))
def test_task_from_any_data(d):
    try:
        task = Task.from_dict(d)
        validate_lifts(task)
    except ErgonomicsError as exc:
        assert str(exc)
    else:
        assert task.load_kg >= 0
