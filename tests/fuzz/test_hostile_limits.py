"""Every resource limit against a hostile file: a zip bomb, FIFOs, false declared counts, files
too large, references outside the scene, an unterminated-comment flood. Each gives a one-line
error within 2 s, and the reading process grows by less than 200 MB over all of them.

The files are read in one child process (a fresh interpreter, as a user's run) so its peak memory
is measured honestly; the thresholds are the issue's acceptance numbers.
"""

from __future__ import annotations

import json
import os
import struct
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent


def _bomb(path: Path, unpacked_mb: int) -> None:
    """A 3MF whose model unpacks to ``unpacked_mb`` MB of zeros (a few hundred KB packed)."""
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("[Content_Types].xml", "<Types/>")
        with z.open("3D/3dmodel.model", "w", force_zip64=True) as f:
            chunk = b"\0" * 2**20
            for _ in range(unpacked_mb):
                f.write(chunk)


def _cases(tmp: Path) -> dict[str, str]:
    """file name -> a fragment the one-line error must contain."""
    cases = {}
    _bomb(tmp / "bomb.3mf", 1024)
    cases["bomb.3mf"] = "possible zip bomb"
    os.mkfifo(tmp / "pipe.bin")
    (tmp / "fifo.gltf").write_text(json.dumps({"asset": {"version": "2.0"},
                                               "buffers": [{"uri": "pipe.bin", "byteLength": 36}]}))
    cases["fifo.gltf"] = "not a regular file"
    os.mkfifo(tmp / "fifo.stl")
    cases["fifo.stl"] = "not a regular file"
    os.mkfifo(tmp / "fifo.fig")
    cases["fifo.fig"] = "not a regular file"
    (tmp / "lie.stl").write_bytes(b"\0" * 80 + struct.pack("<I", 10_000_000) + b"\0" * 50)
    cases["lie.stl"] = "declares 10000000 triangles"
    (tmp / "short.stl").write_bytes(b"\0" * 40)
    cases["short.stl"] = "shorter than a binary STL header"
    (tmp / "lie.ply").write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 50000000\n"
                                  b"property float x\nproperty float y\nproperty float z\nend_header\n" + b"\0" * 64)
    cases["lie.ply"] = "declares 50000000 vertex elements"
    (tmp / "lie.off").write_text("OFF\n40000000 80000000 0\n0 0 0\n")
    cases["lie.off"] = "declares 40000000 vertices"
    with open(tmp / "huge.fig", "wb") as f:  # sparse: 64 MB on paper, nothing on disk
        f.truncate(64 * 2**20)
    cases["huge.fig"] = "file too large"
    (tmp / "escape.gltf").write_text(json.dumps({"asset": {"version": "2.0"},
                                                 "buffers": [{"uri": "../../../../etc/passwd", "byteLength": 36}]}))
    cases["escape.gltf"] = "outside the glTF's folder"
    (tmp / "escape.env").write_text('include "../../../../../../etc/passwd";\n')
    cases["escape.env"] = "outside the scene's folder"
    (tmp / "device.env").write_text('include "/dev/zero";\n')
    cases["device.env"] = "outside the scene's folder"
    (tmp / "comments.fig").write_text("figure f { /* " + "/* x " * 400_000)
    cases["comments.fig"] = "unterminated comment"
    (tmp / "bad.step").write_text("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=NONSENSE(;\nENDSEC;\nEND-ISO-10303-21;\n")
    cases["bad.step"] = "cannot read STEP file"
    (tmp / "text.step").write_text("root:x:0:0:root:/root:/bin/bash\n")
    cases["text.step"] = "not a STEP file"
    return cases


@pytest.mark.timeout(300)
def test_hostile_files_fail_fast_in_one_line_with_little_memory(tmp_path: Path) -> None:
    cases = _cases(tmp_path)
    proc = subprocess.run([sys.executable, str(HERE / "hostile_reads.py"), *(str(tmp_path / n) for n in cases)],
                          capture_output=True, text=True, timeout=240, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stderr.strip() == ""  # no warnings, no OpenCascade noise
    results = {Path(r["path"]).name: r for r in map(json.loads, proc.stdout.splitlines())}
    assert set(results) == set(cases)
    for name, fragment in cases.items():
        r = results[name]
        assert r["error"] is not None, name
        assert "\n" not in r["error"] and fragment in r["error"], (name, r["error"])
        assert name in r["error"] or name.replace(".env", "") in r["error"], (name, r["error"])
        assert "root:x" not in r["error"]  # nothing of an outside file leaks
        assert r["seconds"] < 2.0, (name, r["seconds"])
    assert max(r["grown_mb"] for r in results.values()) < 200.0, results
