"""``jackpy open``: ``--flock PORT`` (also as ``jackpy --flock PORT open``) connects the workbench
to a Flock of Birds with ``--sensors``' configuration; a bad sensor file is one line before any
window opens."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from jackpy.cli import build_parser
from jackpy.devices.flock.simulator import FlockSimulator

REACH_SENSORS = Path(__file__).resolve().parents[2] / "examples" / "flock" / "reach-sensors.json"


def _open(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, JACKPY_HOME=str(tmp_path))
    return subprocess.run([sys.executable, "-m", "jackpy", *args], env=env, capture_output=True, text=True,
                          timeout=240)


def test_flock_is_an_option_of_open_and_of_the_command():
    parser = build_parser()
    a = parser.parse_args(["open", "--flock", "/tmp/f", "--sensors", "s.json", "--birds", "2"])
    b = parser.parse_args(["--flock", "/tmp/f", "open"])
    assert (a.flock, a.sensors, a.birds) == ("/tmp/f", "s.json", 2)
    assert (b.flock, b.sensors, b.birds) == ("/tmp/f", None, 4)


def test_open_connects_to_a_flock_with_a_sensor_configuration(tmp_path):
    """The workbench opens the simulator's pty, configures the birds and they stream to it."""
    with FlockSimulator(4, autoconfig_delay=0.05) as sim:
        done = _open(tmp_path, "open", "--flock", sim.paths[0], "--sensors", str(REACH_SENSORS), "--frames", "5")
        sent = sim.records_sent
    assert done.returncode == 0, done.stderr[-3000:]
    assert sent > 0, "the birds never streamed to the workbench"


def test_a_bad_sensor_configuration_is_one_line_before_the_window(tmp_path):
    bad = tmp_path / "sensors.json"
    bad.write_text('{"sensors": [\n  {"bird": 1,, }\n]}\n')
    done = _open(tmp_path, "open", "--sensors", str(bad), "--frames", "1")
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(lines) == 1, done.stderr
    assert lines[0].startswith(f"jackpy: error: {bad}:2:") and "Traceback" not in done.stderr
