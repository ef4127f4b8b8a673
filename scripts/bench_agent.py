"""Benchmark: answer time per backend on the eval cases, with peak RSS.

    .venv/bin/python scripts/bench_agent.py [--backends none,embedded] [--repeats 3]

`none` runs all 180 cases three times; `embedded` all 180 once, routing with the model and template phrasing
(the default). Besides the median over all answers it reports the median over answers whose route needed the
router (nothing failed), since failures are routed without any model call. Each question is a fresh conversation in a
session per recording, as `hexar ask --questions` does. Targets (issue): none <= 20 ms, embedded <= 3 s on 2 cores.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import tempfile
import time
from pathlib import Path

from hexar.agent.backends import resolve
from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.evals.cases import Case, cases
from hexar.evals.scenarios.suite import simulate_suite

TARGET_S = {"none": 0.020, "embedded": 3.0}


def peak_rss_mb() -> float:
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) for line in f if line.startswith("VmHWM")) / 1024


def run(backend_name: str, picked: list[Case], suite: Path, repeats: int) -> dict[str, float]:
    backend = resolve(backend_name)
    sessions: dict[str, Session] = {}
    times: list[float] = []
    routed: list[float] = []
    right = 0
    for rep in range(repeats):
        for case in picked:
            if case.recording not in sessions:
                sessions[case.recording] = Session(RunSettings(recording=suite / case.recording, llm=backend_name),
                                                   backend=backend)
            t = time.perf_counter()
            result = sessions[case.recording].ask(case.question)
            times.append(time.perf_counter() - t)
            if result["route"] != "failure_check":
                routed.append(times[-1])
            right += rep == 0 and result["explainers"][:1] == [case.scenario.explainer]
    return {"cases": len(picked), "repeats": repeats, "median_s": statistics.median(times),
            "routed_answers": len(routed), "routed_median_s": statistics.median(routed) if routed else 0.0,
            "p90_s": sorted(times)[int(0.9 * (len(times) - 1))], "selection": right / len(picked),
            "peak_rss_mb": peak_rss_mb()}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--backends", default="none,embedded")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    suite = Path(tempfile.mkdtemp(prefix="hexar-suite-"))
    simulate_suite(suite)
    results = {}
    for name in args.backends.split(","):
        results[name] = run(name, cases(), suite, args.repeats if name == "none" else 1)
        r = results[name]
        verdict = "meets" if r["median_s"] <= TARGET_S.get(name, float("inf")) else "misses"
        print(f"{name:10} {r['cases']:4} cases x{r['repeats']}  median {r['median_s'] * 1000:8.1f} ms  "
              f"p90 {r['p90_s'] * 1000:8.1f} ms  routed median {r['routed_median_s'] * 1000:7.1f} ms "
              f"(n={r['routed_answers']})  selection {r['selection']:.3f}  peak RSS {r['peak_rss_mb']:.0f} MB  "
              f"({verdict} target {TARGET_S.get(name, 0) * 1000:.0f} ms)")
    print(json.dumps(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
