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
    assert "6DFOB revision 3.67" in text and "0 records lost, 0 stray bytes" in text
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


def test_probe_an_erc_flock(capsys):
    with FlockSimulator(2, erc=True, autoconfig_delay=0.05) as sim:
        assert main(["flock-probe", sim.paths[0], "--birds", "2", "--no-reset", "--seconds", "0.3"]) == 0
    text = capsys.readouterr().out
    assert "6DERC revision 3.67, birds [2, 3], with an Extended Range Controller" in text
    assert "0 records lost" in text and sim.erc_commands == []


def test_flock_sim_prints_its_port():
    r = subprocess.run([sys.executable, "-m", "jackpy", "flock-sim", "--birds", "1", "--duration", "0.5"],
                       capture_output=True, text=True, timeout=30)
    assert r.returncode == 0 and "flock-sim port 0: /dev/pts/" in r.stdout


def test_header_only_recording_replays_as_empty_with_a_note(tmp_path, capsys):
    from jackpy.devices.recording import Recorder

    path = tmp_path / "empty.jsonl"
    Recorder(path).close()  # e.g. a recording stopped before its first sample
    assert main(["flock-replay", str(path)]) == 0
    err = capsys.readouterr().err
    assert err.startswith("note:") and "no samples" in err and "error" not in err
    out_fig = tmp_path / "final.fig"
    assert main(["flock-replay", str(path), "--figure", "--speed", "0", "--out", str(out_fig)]) == 0
    assert "--out not written" in capsys.readouterr().err and not out_fig.exists()
