"""The eval report: every case, answer, grade and timing, the summary per method and module, the statistics, the
judge's agreement, the backend and the prompt hashes; written as JSON (the Markdown and figures read it)."""

from __future__ import annotations

import json
import platform
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from hexar.evals.graders import Truth
from hexar.evals.judge import agreement, rubric_hash
from hexar.evals.run import CaseResult, RunOutput, modules
from hexar.evals.stats import compare, mean_sd
from hexar.prompts import hashes

SCHEMA = 1
METRICS: tuple[str, ...] = ("root_cause", "incorrect_facts", "accuracy")
LOWER_IS_BETTER = frozenset({"incorrect_facts", "runtime_s"})
# Paper section V-E (and hexar_interfaces.md, "Reported results"): percentages, seconds, selector hits.
PAPER: dict[str, dict[str, float]] = {
    "hexar": {"root_cause": 97.22, "incorrect_facts": 7.22, "accuracy": 92.78, "runtime_s": 1.73, "selection": 179},
    "end-to-end": {"root_cause": 72.78, "incorrect_facts": 27.78, "accuracy": 65.56, "runtime_s": 7.86},
    "all-components": {"root_cause": 92.22, "incorrect_facts": 32.22, "accuracy": 67.22, "runtime_s": 10.05},
}
PAPER_Q: dict[str, float] = {"root_cause": 60.04, "incorrect_facts": 45.50, "accuracy": 50.85}
PAPER_CASES = 180


def _case_dict(row: CaseResult) -> dict[str, Any]:
    c = row.case
    out: dict[str, Any] = {
        "id": c.id, "scenario": c.scenario.id, "module": c.scenario.module, "category": c.scenario.category,
        "variant": c.variant, "kind": c.kind, "recording": c.recording, "question": c.question,
        "truth": {"cause": c.scenario.cause, "also": list(c.scenario.also), "explainer": c.scenario.explainer,
                  "root_cause": c.scenario.root_cause},
        "results": {},
    }
    for name, res in row.results.items():
        a = res.answer
        out["results"][name] = {
            "answer": a.text, "error": a.error, "runtime_s": round(a.runtime_s, 6), "causes": a.causes,
            "explainers": a.explainers, "grades": res.grades.as_dict(), "extra": a.extra,
            "judge": res.verdict.as_dict() if res.verdict is not None else None,
        }
    return out


def _outcomes(cases: Sequence[dict[str, Any]], method: str, metric: str) -> list[bool]:
    return [bool(c["results"][method]["grades"][metric]) for c in cases]


def summarise(cases: Sequence[dict[str, Any]], methods: Sequence[str]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for m in methods:
        entry: dict[str, Any] = {"n": len(cases)}
        for metric in METRICS:
            mean, sd = mean_sd([float(v) for v in _outcomes(cases, m, metric)])
            entry[metric] = {"mean": mean, "sd": sd}
        mean, sd = mean_sd([c["results"][m]["runtime_s"] for c in cases])
        entry["runtime_s"] = {"mean": mean, "sd": sd}
        selection = [c["results"][m]["grades"]["selection"] for c in cases]
        if all(s is not None for s in selection):
            entry["selection"] = {"correct": sum(bool(s) for s in selection), "n": len(cases),
                                  "mean": sum(bool(s) for s in selection) / len(cases)}
        structured = [c["results"][m]["grades"]["structured"] for c in cases]
        if all(s is not None for s in structured):
            entry["structured"] = {k: sum(bool(s[k]) for s in structured) / len(cases) for k in METRICS}
        entry["errors"] = sum(bool(c["results"][m]["error"]) for c in cases)
        out[m] = entry
    return out


def per_module(cases: Sequence[dict[str, Any]], methods: Sequence[str]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for module in modules():
        rows = [c for c in cases if c["module"] == module]
        if not rows:
            continue
        acc = {m: sum(_outcomes(rows, m, "accuracy")) / len(rows) for m in methods}
        test = compare({m: _outcomes(rows, m, "accuracy") for m in methods})
        out[module] = {"n": len(rows), "accuracy": acc, "test": test.as_dict() if test else None}
    return out


def statistics(cases: Sequence[dict[str, Any]], methods: Sequence[str], skipped: dict[str, str]) -> dict[str, Any]:
    if len(methods) < 2:
        why = "; ".join(f"{m}: {r}" for m, r in skipped.items()) or "only one method ran"
        return {"applicable": False, "reason": f"not applicable: only {', '.join(methods)} ran ({why})"}
    tests = {metric: compare({m: _outcomes(cases, m, metric) for m in methods}) for metric in METRICS}
    return {"applicable": True, "metrics": {k: v.as_dict() for k, v in tests.items() if v is not None},
            "paper_q": PAPER_Q}


def judge_summary(cases: Sequence[dict[str, Any]], methods: Sequence[str]) -> dict[str, Any]:
    from hexar.evals.judge import Verdict

    out: dict[str, Any] = {}
    for m in methods:
        rows = [(c["id"], c["results"][m]["grades"], Verdict(**c["results"][m]["judge"])) for c in cases
                if c["results"][m]["judge"] is not None]
        out[m] = [a.as_dict() for a in agreement(rows)]
    return out


def false_claims_by_scenario(rows: Sequence[CaseResult]) -> dict[str, list[str]]:
    """Per scenario, the claims that count as incorrect facts (derived from the vocabulary)."""
    return {str(r.case.scenario.id): Truth.of(r.case).false_claims() for r in rows}


def build(output: RunOutput, runs: Path, selection: dict[str, Any], seed: int) -> dict[str, Any]:
    cases = [_case_dict(row) for row in output.results]
    report: dict[str, Any] = {
        "schema": SCHEMA,
        "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "backend": output.backend,
        "methods": output.methods,
        "not_applicable": output.skipped,
        "runs": _shown(runs), "seed": seed, "simulated": output.simulated,
        "selection": selection,
        "host": {"python": platform.python_version(), "machine": platform.machine(), "system": platform.system()},
        "prompts": hashes(),
        "grading": "text-only for every method (hexar/causes.yaml phrasings, hexar/claims.py); HEXAR's "
                   "structured-cause grades are in summary.<method>.structured",
        "summary": summarise(cases, output.methods),
        "per_module": per_module(cases, output.methods),
        "statistics": statistics(cases, output.methods, output.skipped),
        "paper": {"methods": PAPER, "cochran_q": PAPER_Q, "cases": PAPER_CASES},
        "judge": None,
        "false_claims": false_claims_by_scenario(output.results),
        "cases": cases,
    }
    if output.judge is not None:
        report["judge"] = {"model": output.judge, "rubric": rubric_hash(),
                           "agreement": judge_summary(cases, output.methods)}
    return report


def write_json(report: dict[str, Any], path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")


def regrade(report: dict[str, Any]) -> dict[str, Any]:
    """The same answers graded again with the current graders (after a grader or vocabulary change), with the
    summary, per-module accuracy and statistics recomputed; the LLMs are not asked again."""
    from hexar.evals.cases import cases as all_cases
    from hexar.evals.graders import Graded, Grader

    by_id = {c.id: c for c in all_cases()}
    grader = Grader()
    out: dict[str, Any] = json.loads(json.dumps(report))
    for row in out["cases"]:
        truth = Truth.of(by_id[row["id"]])
        out.setdefault("false_claims", {})[str(row["scenario"])] = truth.false_claims()
        for res in row["results"].values():
            res["grades"] = grader.grade(truth, Graded(res["answer"], res["causes"], res["explainers"])).as_dict()
    methods = out["methods"]
    out["summary"] = summarise(out["cases"], methods)
    out["per_module"] = per_module(out["cases"], methods)
    out["statistics"] = statistics(out["cases"], methods, out["not_applicable"])
    out["prompts"] = report["prompts"]  # the prompts that produced the answers
    out["regraded"] = time.strftime("%Y-%m-%dT%H:%M:%S%z")
    return out


def _shown(path: Path) -> str:
    """The recordings folder as a reader can use it: relative to home, never this machine's absolute path."""
    try:
        return "~/" + str(Path(path).resolve().relative_to(Path.home().resolve()))
    except ValueError:
        return str(path)
