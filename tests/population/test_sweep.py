"""``jackpy sweep`` on the example workplace: a local process pool and a real Dask cluster (a
scheduler and two worker processes started here) give identical per-body tables; Ctrl+C keeps
every finished row and --resume finishes the sweep."""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from jackpy.population.evaluate import SweepContext, evaluate_body
from jackpy.population.journal import PARTIAL, Journal
from jackpy.population.run import population_bodies, sweep
from jackpy.population.study import load_study
from jackpy.scene.workplace import load_workplace

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "examples" / "workplace" / "workplace.json"
STUDY = ROOT / "examples" / "workplace" / "study.json"
N = 500


def _cli(*args: str) -> list[str]:
    return [sys.executable, "-m", "jackpy", "sweep", str(SCENE), "--study", str(STUDY), "--no-progress", *args]


def _table(folder: Path) -> list[dict[str, str]]:
    with open(folder / "bodies.csv", newline="") as f:
        return list(csv.DictReader(f))


@pytest.mark.timeout(1800)
def test_local_pool_and_dask_cluster_give_identical_per_body_tables(tmp_path: Path) -> None:
    from dask.distributed import Client, LocalCluster

    local = tmp_path / "local"
    run = subprocess.run(_cli("--n", str(N), "--workers", "2", "-o", str(local)), capture_output=True, text=True,
                         cwd=ROOT)
    assert run.returncode == 0, run.stderr
    assert "reach:shelf.box_handle:" in run.stdout and "all:" in run.stdout
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        pids = set(client.run(os.getpid).values())
        assert len(pids) == 2 and os.getpid() not in pids  # real worker processes
        bodies = population_bodies(N, sex_mix=0.5, seed=0)
        result, table = sweep(SCENE, STUDY, bodies, tmp_path / "dask", client=client, progress=False)
    assert result.complete and len(result.rows) == N
    assert (local / "bodies.csv").read_bytes() == (tmp_path / "dask" / "bodies.csv").read_bytes()
    rows = _table(local)
    assert [int(r["index"]) for r in rows] == list(range(N))
    assert sum(r["sex"] == "female" for r in rows) == N // 2
    shares = {a.criterion: a for a in table}
    # the shelf handle is too high for short bodies, the switch too low for tall eyes (35 deg cone)
    assert 0.0 < shares["reach:shelf.box_handle"].share < 1.0
    assert shares["reach:shelf.box_handle"].binding_dimension in ("stature", "span", "sitting_height")
    assert shares["reach:shelf.box_handle"].fails_when == "small"
    assert shares["view:panel.switch"].fails_when == "large"
    for name in ("accommodation.csv", "report.html", "scatter.svg", "accommodation.svg"):
        assert (local / name).exists() and (tmp_path / "dask" / name).exists()


@pytest.mark.timeout(1800)
def test_interrupt_keeps_finished_rows_and_resume_finishes(tmp_path: Path) -> None:
    out = tmp_path / "sweep"
    n = 96  # on a fast machine 48 bodies could all finish before the interrupt landed (kept == n)
    proc = subprocess.Popen(_cli("--n", str(n), "--workers", "2", "-o", str(out)), cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 900
    kept_before = 0
    while time.monotonic() < deadline and proc.poll() is None:
        if (out / PARTIAL).exists():
            kept_before = len((out / PARTIAL).read_text().splitlines()) - 1
            if kept_before >= 4:
                break
        time.sleep(0.2)
    assert proc.poll() is None, "the sweep ended before it could be interrupted"
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=600)
    assert proc.returncode == 130, err
    assert "--resume" in err
    study = load_study(STUDY)
    from jackpy.population.evaluate import columns

    kept = Journal(out).finished(columns(study))
    assert kept_before <= len(kept) < n
    assert not (out / "bodies.csv").exists()
    run = subprocess.run(_cli("--resume", "--workers", "2", "-o", str(out)), capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, run.stderr
    rows = _table(out)
    assert [int(r["index"]) for r in rows] == list(range(n))
    # rows kept across the interruption are the rows; a few bodies recomputed here agree with the table
    wp, bodies = load_workplace(SCENE), Journal(out).bodies()
    ctx = SweepContext(wp, study).prepare()
    for i in (min(kept), n - 1):
        fresh = evaluate_body(ctx, bodies[i])
        assert {k: str(v) if not isinstance(v, float) else repr(v) for k, v in fresh.items()} == rows[i]
