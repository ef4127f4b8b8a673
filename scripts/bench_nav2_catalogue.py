"""Benchmark: loading the Nav2 message catalogue and classifying lines with it.

    .venv/bin/python scripts/bench_nav2_catalogue.py [--repeats 7]

Load: a fresh interpreter imports the catalogue module and parses nav2_catalogue.json (median of `repeats`
processes), then pays the lazily built literal table and role regexes on its first match and role lookup.
Classification: lines per second over a simulated failed run's /rosout, through the literal
prefilter, against the same lines matched with every pattern and no prefilter (the ratio is the prefilter's
gain). Target (issue 9): load < 20 ms.
"""

from __future__ import annotations

import argparse
import random
import statistics
import subprocess
import sys
import time

LOAD = (
    "import time\n"
    "from hexar.explainers.navigation.catalogue import catalogue\n"
    "t = time.perf_counter()\n"
    "cat = catalogue()\n"
    "t1 = time.perf_counter()\n"
    "cat.match('Failed to make progress'); cat.role('robot1.controller_server')\n"
    "print((t1 - t) * 1000, (time.perf_counter() - t1) * 1000)\n"
)


def load_ms(repeats: int) -> tuple[float, float]:
    """(parse, first match and role lookup: the lazily built literal search and role table), medians in ms."""
    runs = [subprocess.run([sys.executable, "-c", LOAD], capture_output=True, text=True, check=True).stdout.split()
            for _ in range(repeats)]
    return statistics.median(float(r[0]) for r in runs), statistics.median(float(r[1]) for r in runs)


def lines() -> list[str]:
    from hexar.evals.scenarios.bag import BagBuilder, sec_ns
    from hexar.evals.scenarios.nav import simulate_navigation, simulate_robot_state

    b, rng = BagBuilder(), random.Random(3)
    t0 = 1_700_000_000_000_000_000
    result = simulate_navigation(b, rng, t0, (0.0, 0.0), (4.0, 2.0), "blocked")
    simulate_robot_state(b, rng, t0, result.end + sec_ns(5.0), joystick=False, charging=False)
    return [str(m[3].msg) for m in b.messages if m[1] == "/rosout"]


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    from hexar.explainers.navigation.catalogue import catalogue

    cat = catalogue()
    msgs = lines()
    fast, slow = [], []
    for _ in range(args.repeats):
        cat._seen.clear()  # each repeat reads the run as the first time
        t = time.perf_counter()
        for msg in msgs:
            cat.match(msg)
        fast.append(time.perf_counter() - t)
        t = time.perf_counter()
        for msg in msgs:
            [e for e in cat.entries if e.pattern.search(msg)]
        slow.append(time.perf_counter() - t)
    sizes = cat.sizes()
    print(f"catalogue: {len(cat.entries)} patterns; per distro: "
          + ", ".join(f"{d} {sum(r.values())}" for d, r in sizes.items()))
    parse, first = load_ms(args.repeats)
    print(f"load (fresh process, median of {args.repeats}): parse {parse:.1f} ms (target < 20 ms), "
          f"then {first:.1f} ms for the first match and role lookup")
    rate, rate_all = len(msgs) / statistics.median(fast), len(msgs) / statistics.median(slow)
    print(f"classify {len(msgs)} lines of a simulated blocked run: {rate:,.0f} lines/s (literal prefilter and "
          f"repeat cache), {rate_all:,.0f} lines/s trying every pattern (x{rate / rate_all:.1f})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
