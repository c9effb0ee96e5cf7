"""Recovery files: one per scene, written on a worker thread from a snapshot (edits during the
write do not reach the file), orphans of dead runs offered, the old single file read once."""

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from jackpy.document import Document, recovery
from jackpy.document import session as doc_session
from jackpy.document.recovery import Autosaver
from jackpy.document.session import default_scene, load_session

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def _home(tmp_path, monkeypatch):
    monkeypatch.setenv("JACKPY_HOME", str(tmp_path / "home"))


def _doc() -> Document:
    env, base = default_scene()
    doc = Document(env)
    doc.scene_dir = base
    return doc


def _human(doc: Document):
    return next(f for f in doc.env.figures.values() if getattr(f, "body_spec", None) is not None)


def test_the_write_runs_on_a_worker_and_edits_during_it_do_not_reach_the_file(monkeypatch):
    """autosave returns while the write waits (it is not on the caller's thread); the file holds
    the document as it was when autosave was called, whole, though the document was edited (a
    figure moved, one removed, extras changed) during the write."""
    doc = _doc()
    fig = _human(doc)
    fig.q = np.clip(fig.q + 0.2, fig.lower, fig.upper)
    before = {n: (f.q.copy(), f.location.copy()) for n, f in doc.env.figures.items()}
    go, threads, real = threading.Event(), [], doc_session.write

    def write_when_told(snap, path):  # the real write, held until the edits below are done
        threads.append(threading.current_thread())
        assert go.wait(60)
        return real(snap, path)

    monkeypatch.setattr(doc_session, "write", write_when_told)
    saver = Autosaver()
    try:
        future = saver.save(doc, None)
        assert not future.done() and saver.busy  # autosave returned; the write waits on the worker
        assert saver.save(doc, None) is future  # never two writes at once
        fig.q = np.clip(fig.q - 0.4, fig.lower, fig.upper)
        fig.location[:3, 3] += 1.0
        del doc.env.figures[next(n for n in doc.env.figures if n != fig.name)]
        doc.extras["note"] = list(range(1000))
        go.set()
        path = future.result(timeout=120)
    finally:
        go.set()
        saver.close(discard=False)
    assert threads and threads[0] is not threading.main_thread()
    env, data = load_session(path)
    assert set(env.figures) == set(before)
    for name, (q, loc) in before.items():
        assert np.array_equal(env.figure(name).q, q) and np.array_equal(env.figure(name).location, loc), name
    assert "note" not in data["extras"] and data["view"]["autosave_of"] is None


def test_scenes_have_their_own_recovery_and_a_second_run_does_not_take_the_first_ones(tmp_path):
    doc = _doc()
    a, b = tmp_path / "a.env", tmp_path / "b.env"
    first, second = Autosaver(), Autosaver()  # two workbenches on scene a
    try:
        pa = first.save(doc, a).result(timeout=120)
        assert pa == recovery.recovery_path(a) and pa.name.startswith("a-")
        pa2 = second.save(doc, a).result(timeout=120)
        assert pa2 != pa and pa2.is_file() and pa.is_file()  # the second did not overwrite the first
        assert recovery.orphans() == []  # both alive
        pb = first.save(doc, b).result(timeout=120)  # the first went on to scene b
        assert pb == recovery.recovery_path(b) and pb.is_file() and not pa.exists()
        first.close(discard=False)  # ... and crashed
        assert recovery.orphans() == [pb] and recovery.offer_for(b) == pb
        assert recovery.offer_for(a) is None  # a's recovery is the second run's, alive
        second.drop().result(timeout=60)  # the second saved its work: nothing to recover
        assert not pa2.exists()
    finally:
        first.close(discard=False)
        second.close()
    assert recovery.orphans() == [pb]


def test_the_old_single_recovery_file_is_offered_once_for_its_scene(tmp_path):
    doc = _doc()
    scene = tmp_path / "s.env"
    doc.view_state["autosave_of"] = str(scene.resolve())
    legacy = doc_session.save(doc, recovery.recovery_dir() / recovery.LEGACY_NAME)  # an older version's
    assert recovery.offer_for(scene) == legacy and recovery.offer_for(None) is None
    assert recovery.orphans() == [legacy]  # listed in File > Recover too
    recovery.discard_recovery(legacy)
    assert recovery.orphans() == [] and not (legacy.parent / "recovery_psurf").exists()


def test_a_failed_write_is_reported_not_raised(tmp_path, monkeypatch):
    blocker = tmp_path / "not_a_folder"
    blocker.write_text("")
    monkeypatch.setenv("JACKPY_HOME", str(blocker))  # the recovery folder cannot be made
    saver = Autosaver()
    future = saver.save(_doc(), None)
    assert isinstance(future.exception(timeout=60), OSError)
    assert len(saver.failures()) == 1 and saver.failures() == []
    saver.close()


_CHILD = """
import sys, numpy as np
from jackpy.document import Document
from jackpy.document.recovery import Autosaver
from jackpy.document.session import default_scene
env, base = default_scene()
doc = Document(env); doc.scene_dir = base
fig = next(f for f in env.figures.values() if getattr(f, "body_spec", None) is not None)
saver = Autosaver()
if sys.argv[1] == "exit":
    fig.q = np.clip(fig.q + 0.3, fig.lower, fig.upper)
    future = saver.save(doc, None)
    print("pending" if not future.done() else "done", flush=True)
    sys.exit(0)  # during the write: the interpreter waits for it
saver.save(doc, None).result()
print("ready", flush=True)
for k in range(1000):
    fig.q = np.clip(fig.q + 0.01, fig.lower, fig.upper)
    saver.save(doc, None).result()
"""


def _child(mode: str, tmp_path: Path) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    return subprocess.Popen([sys.executable, "-c", textwrap.dedent(_CHILD), mode], env=env, cwd=tmp_path,
                            stdout=subprocess.PIPE, text=True)


def _whole(home: Path) -> Path:
    files = list((home / "recovery").glob("untitled-*.env"))
    assert len(files) == 1
    env, data = load_session(files[0])  # every figure, surfaces and the session line read back
    assert data is not None and len(env.figures) == 3
    return files[0]


def test_an_exit_during_a_write_waits_for_it_and_a_kill_leaves_a_whole_file(tmp_path):
    home = Path(os.environ["JACKPY_HOME"])
    proc = _child("exit", tmp_path)
    out, _ = proc.communicate(timeout=240)
    assert proc.returncode == 0 and out.strip() == "pending"
    _whole(home)
    (home / "recovery").rename(home / "first")
    proc = _child("kill", tmp_path)
    try:
        assert proc.stdout.readline().strip() == "ready"
        time.sleep(0.5 + np.random.default_rng(1).uniform(0.0, 2.0))  # somewhere in a later write
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait(60)
    path = _whole(home)
    assert recovery.orphans() == [path]  # the killed run's lock died with it
