"""Per-explainer accuracy over the 60 simulated recordings (no LLM) and runtime per explanation.

For each recording, the scenario's module explainer answers the scenario's three questions. Correct = the
ground-truth cause is among `causes`, no other cause is claimed (besides the scenario's `also`), and every
evidence item exists in the recording. Runtime: median over all calls after the first of each explainer
(the first call loads models: pgmpy network, decision tree).

    .venv/bin/python scripts/bench_explainers.py
"""

from __future__ import annotations

import json
import statistics
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

from hexar.evals.cases import recording_name, scenarios
from hexar.evals.scenarios.suite import simulate_suite
from hexar.events import read_recording
from hexar.explainers.base import Context
from hexar.explainers.evidence_check import exists
from hexar.explainers.registry import Registry


def main() -> int:
    suite = Path(tempfile.mkdtemp(prefix="hexar-suite-"))
    simulate_suite(suite)
    registry = Registry.load()
    right: dict[str, int] = defaultdict(int)
    total: dict[str, int] = defaultdict(int)
    times: dict[str, list[float]] = defaultdict(list)
    for s in scenarios():
        for variant in (1, 2, 3):
            log = read_recording(suite / recording_name(s.id, variant))
            context = Context.for_task(log, log.task(), registry)
            for template in s.questions:
                question = template.format(object=s.variants[variant - 1].object)
                t = time.perf_counter()
                exp = registry.get(s.explainer).explain(question, context)
                times[s.explainer].append(time.perf_counter() - t)
                ok = (s.cause in exp.causes and set(exp.causes) <= {s.cause, *s.also}
                      and all(exists(log, ev) for ev in exp.evidence) and bool(exp.evidence))
                right[s.explainer] += ok
                total[s.explainer] += 1
    rows = {}
    print(f"{'explainer':20}{'scenarios':>10}{'answers':>9}{'correct':>9}{'accuracy':>10}{'median ms':>11}")
    for name in total:
        warm = times[name][1:] or times[name]
        rows[name] = {"answers": total[name], "correct": right[name], "accuracy": right[name] / total[name],
                      "median_ms": statistics.median(warm) * 1000, "first_call_ms": times[name][0] * 1000}
        n_scen = sum(1 for s in scenarios() if s.explainer == name)
        print(f"{name:20}{n_scen:>10}{total[name]:>9}{right[name]:>9}{rows[name]['accuracy']:>10.3f}"
              f"{rows[name]['median_ms']:>11.1f}")
    all_right, all_total = sum(right.values()), sum(total.values())
    print(f"{'all':20}{20:>10}{all_total:>9}{all_right:>9}{all_right / all_total:>10.3f}")
    print(json.dumps(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
