"""Listing and inspecting hostile recordings stays fast: `hexar runs` over a folder of damaged recordings against
the same number of good ones, and `inspect` of a recording whose instruction is 10 MB, or whose /task_info nests
2,000 brackets, against a plain one.

    .venv/bin/python scripts/bench_damaged.py [--copies 8] [--repeats 5]

Each figure is the median of --repeats runs of the command in this process (no interpreter start-up); the
ratio is to the good recordings measured in the same run.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import shutil
import sqlite3
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from hexar.cli import main
from hexar.evals.cases import scenario
from hexar.evals.scenarios.bag import _T, BagBuilder, sec_ns
from hexar.evals.scenarios.suite import record
from hexar.events import contract as c


def _damage(kind: int, bag: Path) -> None:
    """One of the ways a recording arrives broken: cut short, overwritten, emptied, its index or YAML bad."""
    db = next(bag.glob("*.db3"))
    data = db.read_bytes()
    if kind == 0:
        db.write_bytes(data[: len(data) // 2])
    elif kind == 1:
        db.write_bytes(data[:4096])
    elif kind == 2:
        db.write_bytes(os.urandom(len(data)))
    elif kind == 3:
        db.write_bytes(b"")
    elif kind == 4:
        (bag / "metadata.yaml").write_text("rosbag2_bagfile_information: [")
    elif kind == 5:
        with sqlite3.connect(db) as conn:
            conn.execute("UPDATE messages SET data = randomblob(length(data))")
    elif kind == 6:
        with sqlite3.connect(db) as conn:
            conn.execute("UPDATE messages SET data = substr(data, 1, 6)")
    else:
        b = bytearray(data)
        for i in range(0, len(b), 997):
            b[i] ^= 0xFF
        db.write_bytes(bytes(b))


def _hostile_task(out: Path, payload: str) -> Path:
    b = BagBuilder()
    t0 = sec_ns(1_741_600_000)
    b.raw(t0, c.TASK_INFO, c.STRING_TYPE, _T["std_msgs/msg/String"](data=payload))
    b.log(t0 + sec_ns(1), "bt_navigator", 40, "Goal failed")
    return b.write(out)


def _median_s(fn: Callable[[], int], repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main_() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--copies", type=int, default=8, help="recordings per folder")
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        base = record(scenario(5), 1).write(work / "base")
        good, damaged = work / "good", work / "damaged"
        for i in range(args.copies):
            shutil.copytree(base, good / f"run_{i}")
            shutil.copytree(base, damaged / f"run_{i}")
            _damage(i % 8, damaged / f"run_{i}")
        step = '{"skill": "navigate_to_zone", "params": {}, "status": "failed", "error_msg": "x"}'
        plain = _hostile_task(work / "plain", '{"task_id": "t", "instruction": "Bring me the coffee", '
                                              f'"skill_sequence": [{step}]}}')
        huge = _hostile_task(work / "huge", '{"task_id": "t", "instruction": "' + "Bring me " * 1_200_000 +
                             f'", "skill_sequence": [{step}]}}')
        long = _hostile_task(work / "long", '{"task_id": "t", "instruction": "' + "Bring me " * 100_000 +
                             f'", "skill_sequence": [{step}]}}')
        deep = _hostile_task(work / "deep", "[" * 2000 + "]" * 2000)

        runs_good = _median_s(lambda: main(["runs", str(good)]), args.repeats) / args.copies
        runs_bad = _median_s(lambda: main(["runs", str(damaged)]), args.repeats) / args.copies
        print(f"hexar runs, per recording: good {runs_good * 1000:.1f} ms, damaged {runs_bad * 1000:.1f} ms "
              f"(ratio {runs_bad / runs_good:.2f}; {args.copies} each, 8 kinds of damage)")
        base_s = _median_s(lambda: main(["inspect", str(plain)]), args.repeats)
        print(f"hexar inspect, plain task: {base_s * 1000:.1f} ms")
        for name, path in (("10 MB instruction", huge), ("900 kB instruction", long), ("2,000 nested brackets", deep)):
            s = _median_s(lambda p=path: main(["inspect", str(p)]), args.repeats)  # type: ignore[misc]
            print(f"hexar inspect, {name}: {s * 1000:.1f} ms (ratio {s / base_s:.2f})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main_())
