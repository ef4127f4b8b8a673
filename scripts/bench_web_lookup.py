"""Benchmark: naming a run on the page of a large served folder.

Builds a fleet folder of ROBOTS x DAYS day folders (each with an empty notes folder) holding RUNS copies of a
simulated recording, then times `Store.path(name)` (what every request that names a run does: timeline, path,
evidence, chat) against a fresh walk of the folder (what it did before it looked the name up in the last walk).
Medians of --repeat rounds, and the ratio measured in the same run.

    .venv/bin/python scripts/bench_web_lookup.py [--robots 20] [--days 50] [--runs 60] [--repeat 7]
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import tempfile
import time
from pathlib import Path

from hexar.evals.scenarios.suite import simulate_suite
from hexar.web.store import Store


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--robots", type=int, default=20)
    ap.add_argument("--days", type=int, default=50)
    ap.add_argument("--runs", type=int, default=60)
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        base = Path(tmp)
        simulate_suite(base / "sim", only=lambda s, v: (s, v) == (5, 1))
        root = base / "fleet"
        for r in range(args.robots):
            for d in range(args.days):
                (root / f"robot{r}" / f"day{d}" / "notes").mkdir(parents=True)
        for k in range(args.runs):
            shutil.copytree(base / "sim" / "bagfile_5_1", root / f"robot{k % args.robots}" / f"day{k % args.days}"
                            / f"run{k}")
        store = Store(root, "none", base / "t.sqlite")
        name = f"robot{3 % args.robots}/day{3 % args.days}/run3"
        lookups, walks = [], []
        for _ in range(args.repeat):
            t = time.perf_counter()
            for _ in range(20):
                store.path(name)
            lookups.append((time.perf_counter() - t) / 20 * 1000)
            t = time.perf_counter()
            store._recordings()
            walks.append((time.perf_counter() - t) * 1000)
    folders = args.robots * args.days * 2
    print(f"{args.runs} runs in {folders} folders: name a run {statistics.median(lookups):.3f} ms, "
          f"walk the folder {statistics.median(walks):.1f} ms (medians of {args.repeat}); "
          f"{statistics.median(walks) / statistics.median(lookups):.0f}x")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
