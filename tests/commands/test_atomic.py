"""Atomic writes leave no temporary file behind: a killed writer's leftover is removed by the next
write, a live writer's temporary file is never touched."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from jackpy.atomic import atomic_write_bytes, clean_stale_temps

WRITER = """
import sys, jackpy.atomic as a
real = a.os.replace
def hang(*args):
    print("writing", flush=True)
    import time; time.sleep(60)
a.os.replace = hang
a.atomic_write_bytes(sys.argv[1], b"x" * 1_000_000)
"""


def _start_writer(target: Path) -> subprocess.Popen:
    proc = subprocess.Popen([sys.executable, "-c", WRITER, str(target)], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "writing"  # the temp file is written and locked now
    return proc


def _temps(folder: Path) -> list[str]:
    return sorted(n for n in os.listdir(folder) if n.endswith(".tmp"))


def test_killed_writers_leftovers_go_on_the_next_write(tmp_path: Path) -> None:
    target = tmp_path / "scene.env"
    atomic_write_bytes(target, b"old")
    for _ in range(3):
        proc = _start_writer(target)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    # each writer removed its killed predecessor's leftover: only the last one is there
    assert len(_temps(tmp_path)) == 1 and target.read_bytes() == b"old"
    (tmp_path / ".scene.env.notours.tmp").write_text("keep")  # not our naming: kept
    (tmp_path / ".other.env.abcdefgh.tmp").write_text("keep")  # another file's: kept
    atomic_write_bytes(target, b"new")
    assert target.read_bytes() == b"new"
    assert _temps(tmp_path) == [".other.env.abcdefgh.tmp", ".scene.env.notours.tmp"]


def test_a_live_writers_temp_file_is_not_removed(tmp_path: Path) -> None:
    target = tmp_path / "scene.env"
    proc = _start_writer(target)
    try:
        assert clean_stale_temps(target) == []
        assert len(_temps(tmp_path)) == 1
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    time.sleep(0.05)
    assert len(clean_stale_temps(target)) == 1 and _temps(tmp_path) == []
