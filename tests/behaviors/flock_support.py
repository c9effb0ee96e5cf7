"""Helpers of the live sensor-drive tests (behaviors and the Devices panel): the shipped reaching
recording (``examples/flock``) as module fixtures, and the simulator that plays it on a pty.

Test modules import the fixtures (``from flock_support import final_fixture, reach_fixture``):
pytest finds a fixture in the module's namespace, under its name (``final``, ``reach``). The UI
tests put this folder on ``sys.path`` first (pytest puts only a test file's own folder there)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from jackpy.devices.flock.simulator import FlockSimulator
from jackpy.devices.recording import FrameMotion, Recording, read_recording

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "flock"
PALMS = ("left_palm", "right_palm")
RATE_HZ = 100.0
DRIVER_OPTIONS = {"measurement_rate": RATE_HZ, "rts_reset": None, "autoconfig_wait": 0.05}
""":class:`~jackpy.devices.flock.driver.FlockDriver` options for :func:`reach_simulator`'s pty."""


@pytest.fixture(scope="module", name="reach")
def reach_fixture() -> Recording:
    """The reaching recording: the standard human (male, 50th) reaching forward, 4 birds."""
    return read_recording(EXAMPLE / "reach.jsonl")


@pytest.fixture(scope="module", name="final")
def final_fixture() -> dict[str, np.ndarray]:
    """World 4x4 of each driven part at the end of the reach (the recording's truth)."""
    return {p: np.array(v) for p, v in json.loads((EXAMPLE / "reach-final.json").read_text()).items()}


def reach_simulator(recording: Recording) -> tuple[FrameMotion, FlockSimulator]:
    """A 4-bird simulator at 100 Hz playing ``recording`` frame by frame (one recording frame per
    emitted record), holding frame 0 (the neutral stance) until ``motion.play()``; use it as a
    context manager (``with sim:``) and connect with :data:`DRIVER_OPTIONS`."""
    motion = FrameMotion(recording)
    return motion, FlockSimulator(4, motion=motion, rate=RATE_HZ, autoconfig_delay=0.05)
