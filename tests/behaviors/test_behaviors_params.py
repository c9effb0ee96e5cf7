"""Every behavior has a name, an on/off switch and documented, valid parameters for the panel."""

import dataclasses

import pytest

from jackpy.behaviors import default_behaviors, describe
from jackpy.behaviors.base import validate
from jackpy.behaviors.feet import FeetParams


def test_default_behaviors_are_described():
    names = set()
    for b in default_behaviors():
        assert b.name and b.enabled
        names.add(b.name)
        specs = describe(b.params)
        assert specs, b.name
        for s in specs:
            assert s.doc, f"{b.name}.{s.name} has no description"
            if s.range is not None:
                assert s.range[0] <= s.value <= s.range[1]
    assert {"automatic root", "feet", "balance", "stepping", "torso", "pelvis", "gaze", "hands",
            "limit springs"} <= names


def test_validate_rejects_out_of_range():
    p = FeetParams()
    p = dataclasses.replace(p, level=7)
    with pytest.raises(ValueError, match="level"):
        validate(p)
