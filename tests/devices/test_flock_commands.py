"""The flock-sim, flock-probe and flock-replay subcommands."""

from __future__ import annotations

import subprocess
import sys

from jackpy.cli import main
from jackpy.devices.flock.simulator import FlockSimulator
from jackpy.devices.recording import read_recording


def test_probe_records_then_replay(tmp_path, capsys):
    out = tmp_path / "s.jsonl"
    with FlockSimulator(2, autoconfig_delay=0.05) as sim:
        assert main(["flock-probe", sim.paths[0], "--birds", "2", "--no-reset", "--seconds", "0.5",
                     "--record", str(out)]) == 0
    text = capsys.readouterr().out
    assert "6DFOB revision 3.67" in text and "0 dropped" in text
    rec = read_recording(out)
    assert rec.birds == [1, 2] and len(rec.samples) > 20
    assert main(["flock-replay", str(out), "--speed", "0"]) == 0
    assert "bird 2  pos" in capsys.readouterr().out
    assert main(["flock-replay", str(out), "--speed", "0", "--json"]) == 0
    assert '"position_in"' in capsys.readouterr().out


def test_replay_errors_are_one_line(tmp_path, capsys):
    assert main(["flock-replay", str(tmp_path / "missing.jsonl")]) != 0
    bad = tmp_path / "bad.jsonl"
    bad.write_text("not a recording\n")
    assert main(["flock-replay", str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 2 and "jackpy: error:" in err and "Traceback" not in err


def test_flock_sim_prints_its_port():
    r = subprocess.run([sys.executable, "-m", "jackpy", "flock-sim", "--birds", "1", "--duration", "0.5"],
                       capture_output=True, text=True, timeout=30)
    assert r.returncode == 0 and "flock-sim port 0: /dev/pts/" in r.stdout
