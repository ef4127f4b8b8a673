"""The long fuzz run of tests/fuzz/harness.py: many seeded examples, reported as figures.

    .venv/bin/python scripts/fuzz_long.py --examples 10000 --jobs 2

Prints the examples run per kind, exit codes, commands run, findings (each reproducible by its seed with
`pytest tests/fuzz -k seed` or `example(seed, folder)`), and the rate. Exit 1 when anything was found.
"""

from __future__ import annotations

import argparse
import contextlib
import sys
import tempfile
import time
from collections import Counter
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.fuzz.harness import KINDS, example


def _batch(seeds: list[int]) -> tuple[list[str], Counter[str], Counter[int], int]:
    base = Path("/dev/shm") if Path("/dev/shm").is_dir() else None  # sqlite fsyncs cost 0.3 s a bag on disk
    found: list[str] = []
    codes: Counter[int] = Counter()
    kinds: Counter[str] = Counter()
    commands = 0
    with tempfile.TemporaryDirectory(dir=base) as tmp:
        for seed in seeds:
            kinds[KINDS[seed % len(KINDS)]] += 1
            for o in example(seed, Path(tmp)):
                commands += 1
                codes[o.code] += 1
                found += [f"seed {seed}: {o.args[0]} {o.args[2:4]}: {p}"[:500] for p in o.problems]
    return found, kinds, codes, commands


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--examples", type=int, default=10_000)
    ap.add_argument("--start", type=int, default=0, help="first seed")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--batch", type=int, default=50)
    args = ap.parse_args()
    seeds = list(range(args.start, args.start + args.examples))
    batches = [seeds[i : i + args.batch] for i in range(0, len(seeds), args.batch)]
    started = time.perf_counter()
    found: list[str] = []
    kinds: Counter[str] = Counter()
    codes: Counter[int] = Counter()
    commands = done = 0
    # Ctrl-C (SIGINT) stops after the batches in flight and still prints the figures of what ran
    with contextlib.suppress(KeyboardInterrupt), ProcessPoolExecutor(max_workers=args.jobs) as pool:
        for f, k, c, n in pool.map(_batch, batches):
            found += f
            kinds.update(k)
            codes.update(c)
            commands += n
            done += sum(k.values())
            for line in f:
                print("FINDING", line, flush=True)
            if done % 1000 < args.batch:
                print(f"{done} examples, {len(found)} findings, {time.perf_counter() - started:.0f} s", flush=True)
    elapsed = time.perf_counter() - started
    print(f"examples: {done} (seeds {args.start}..{args.start + args.examples - 1}), by kind: {dict(kinds)}")
    print(f"commands run: {commands}, exit codes: {dict(sorted(codes.items()))}")
    print(f"findings: {len(found)}")
    print(f"elapsed: {elapsed:.0f} s with {args.jobs} job(s), {done / elapsed:.1f} examples/s")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
