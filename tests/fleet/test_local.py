"""The local pool gives what one worker gives: on the 60 simulated recordings (three of them pizza recommendations,
which only one worker of a pool explains), `hexar triage` with one worker and with two writes the same report,
tables and results. The pool runs in a fresh interpreter, as a user starts it: one that has not imported
scikit-learn, so that its workers hand the pizza recordings over."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from hexar.fleet.command import RESULTS
from hexar.fleet.local import MATH_THREADS, one_math_thread

HEXAR = str(Path(sys.executable).with_name("hexar"))


def triage(fleet: Path, out: Path, workers: int) -> subprocess.CompletedProcess[str]:
    return subprocess.run([HEXAR, "triage", str(fleet), "--out", str(out), "--workers", str(workers),
                           "--no-figures"], capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("workers", [2, 3])
def test_a_pool_writes_what_one_worker_writes(suite: Path, tmp_path: Path, workers: int) -> None:
    one, pool = tmp_path / "one", tmp_path / "pool"
    for out, n in ((one, 1), (pool, workers)):
        done = triage(suite, out, n)
        assert done.returncode == 0, done.stderr
        assert "60 recordings, " in done.stdout
    for name in ("report.md", "tasks.jsonl"):
        assert (pool / name).read_bytes() == (one / name).read_bytes(), name
    # the results file is in the order recordings finished; its lines are the same
    assert sorted((pool / RESULTS).read_text().splitlines()) == sorted((one / RESULTS).read_text().splitlines())
    pd.testing.assert_frame_equal(pd.read_parquet(pool / "tasks.parquet"), pd.read_parquet(one / "tasks.parquet"))
    explainers = pd.read_parquet(one / "tasks.parquet")["explainer"]
    assert (explainers == "pizza_recommender").sum() == 3  # the recordings a light worker hands over


def _children(pid: int) -> list[int]:
    return [int(c) for c in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]


def test_workers_that_die_end_the_run_with_one_line_and_a_rerun_finishes(suite: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = subprocess.Popen([HEXAR, "triage", str(suite), "--out", str(out), "--workers", "2", "--no-figures"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not (out / RESULTS).is_file() or not (out / RESULTS).read_text():
        assert proc.poll() is None and time.monotonic() < deadline, "no results appeared"
        time.sleep(0.02)
    workers = _children(proc.pid)
    assert len(workers) == 2
    for pid in workers:
        os.kill(pid, signal.SIGKILL)  # as the kernel's out-of-memory killer would
    _, stderr = proc.communicate(timeout=120)
    if proc.returncode == 0:
        pytest.skip("the run finished before the worker was killed")
    assert proc.returncode == 2 and "Traceback" not in stderr
    assert stderr.startswith("ERROR: a triage worker stopped") and stderr.count("\n") == 1
    kept = len((out / RESULTS).read_text().splitlines())
    again = triage(suite, out, 2)
    assert again.returncode == 0, again.stderr
    assert f"{kept} done before, {60 - kept} to triage" in again.stdout
    assert len((out / RESULTS).read_text().splitlines()) == 60


def test_triage_gives_each_math_library_one_thread_unless_the_user_chose(monkeypatch: pytest.MonkeyPatch) -> None:
    for var in MATH_THREADS:
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("OMP_NUM_THREADS", "4")
    one_math_thread()
    assert os.environ["OPENBLAS_NUM_THREADS"] == "1"
    assert os.environ["MKL_NUM_THREADS"] == "1"
    assert os.environ["OMP_NUM_THREADS"] == "4"


def test_a_fleet_without_pizza_is_triaged_without_pandas_or_scikit_learn(suite: Path, tmp_path: Path) -> None:
    """Importing pandas took longer than triaging 57 recordings: the tables and the report are written from plain
    rows, and the Parquet table keeps the column types pandas gave it. Checked in a fresh interpreter."""
    fleet = tmp_path / "fleet"
    fleet.mkdir()
    for rec in suite.iterdir():
        if not rec.name.startswith("bagfile_20_"):  # the three pizza recommendations, LIME's answers
            (fleet / rec.name).symlink_to(rec)
    out = tmp_path / "out"
    code = (
        "import sys\nfrom hexar.cli import main\n"
        f"code = main(['triage', {str(fleet)!r}, '--out', {str(out)!r}, '--workers', '1', '--no-figures'])\n"
        "print('HEAVY', sorted({m.split('.')[0] for m in sys.modules} & {'pandas', 'sklearn', 'lime'}), code)\n"
    )
    said = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=True).stdout
    assert said.strip().splitlines()[-1] == "HEAVY [] 0"
    df = pd.read_parquet(out / "tasks.parquet")
    assert len(df) == len((out / "tasks.jsonl").read_text().splitlines()) > 57
    assert str(df["order"].dtype) == "int64" and str(df["recovery"].dtype) == "bool"
    assert str(df["duration_s"].dtype) == "float64" and str(df["cause"].dtype) == "str"
    assert {tuple(c) for c in df["causes"]} >= {("navigation.blocked_path",)}
