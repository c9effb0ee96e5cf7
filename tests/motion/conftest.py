"""Shared set-up: one standard human and its loop per test (fresh, since motions change them)."""

from __future__ import annotations

import pytest

from jackpy.motion import cast
from jackpy.peabody.model import Environment


@pytest.fixture
def scene():
    """(env, loops) with one 50th-percentile male named ``jack`` standing at the origin."""
    env = Environment()
    fig = env.add(cast.make_figure("jack"))
    return env, {"jack": cast.loop_for(fig)}
