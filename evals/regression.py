"""Prompt and behaviour regression: a run against a committed baseline of the same backend.

A run fails the gate when, over the cases both cover, a metric of a method is worse than the baseline's by more
than the tolerance (percentage points / 100), or when a case that was right turns wrong (root cause lost,
incorrect fact added, accuracy or selection lost). Prompt hashes that changed are listed to point at the cause.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hexar.errors import HexarError

BASELINE_SCHEMA = 1
DEFAULT_TOLERANCE = 0.02
GATED = ("root_cause", "incorrect_facts", "accuracy", "selection")
LOWER_IS_BETTER = frozenset({"incorrect_facts"})


def _case_grades(result: dict[str, Any]) -> dict[str, Any]:
    g = result["grades"]
    return {**{k: g[k] for k in GATED}, "answer": result["answer"]}


def baseline_of(report: dict[str, Any]) -> dict[str, Any]:
    """What a baseline keeps of a report: per method and case, the gated grades and the answer."""
    methods: dict[str, Any] = {}
    for m in report["methods"]:
        methods[m] = {c["id"]: _case_grades(c["results"][m]) for c in report["cases"]}
    return {"schema": BASELINE_SCHEMA, "backend": report["backend"], "created": time.strftime("%Y-%m-%d"),
            "prompts": report["prompts"], "selection": report["selection"], "methods": methods}


def write_baseline(report: dict[str, Any], path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(baseline_of(report), indent=1, ensure_ascii=False) + "\n", encoding="utf-8")


def read_baseline(path: Path) -> dict[str, Any]:
    from hexar.inputs import read_text_arg

    try:
        data: dict[str, Any] = json.loads(read_text_arg(path, "--baseline"))
    except ValueError as err:
        raise HexarError(f"cannot read baseline {path}: {err}") from err
    if data.get("schema") != BASELINE_SCHEMA or "methods" not in data:
        raise HexarError(f"{path} is not a hexar eval baseline (schema {BASELINE_SCHEMA})")
    return data


@dataclass(frozen=True)
class MetricDrop:
    method: str
    metric: str
    baseline: float
    now: float


@dataclass(frozen=True)
class CaseFlip:
    method: str
    case: str
    metric: str
    baseline_answer: str
    answer: str


@dataclass
class Regression:
    backend: str
    tolerance: float
    compared: dict[str, int] = field(default_factory=dict)  # method -> cases compared
    drops: list[MetricDrop] = field(default_factory=list)
    flips: list[CaseFlip] = field(default_factory=list)
    prompts_changed: list[str] = field(default_factory=list)
    answers_changed: int = 0

    @property
    def failed(self) -> bool:
        return bool(self.drops or self.flips)

    def as_dict(self) -> dict[str, Any]:
        return {"backend": self.backend, "tolerance": self.tolerance, "compared": self.compared,
                "failed": self.failed, "drops": [d.__dict__ for d in self.drops],
                "flips": [f.__dict__ for f in self.flips], "prompts_changed": self.prompts_changed,
                "answers_changed": self.answers_changed}


def _mean(values: list[Any]) -> float | None:
    usable = [bool(v) for v in values if v is not None]
    return sum(usable) / len(usable) if usable else None


def _worse(metric: str, before: Any, now: Any) -> bool:
    if before is None or now is None:
        return False
    return bool(now) and not before if metric in LOWER_IS_BETTER else bool(before) and not now


def compare(report: dict[str, Any], baseline: dict[str, Any], tolerance: float = DEFAULT_TOLERANCE) -> Regression:
    if baseline["backend"] != report["backend"]:
        raise HexarError(f"the baseline is for backend {baseline['backend']!r}, this run used "
                         f"{report['backend']!r}: compare runs of the same backend")
    out = Regression(report["backend"], tolerance)
    old_prompts, new_prompts = baseline.get("prompts", {}), report["prompts"]
    out.prompts_changed = sorted(k for k in {*old_prompts, *new_prompts} if old_prompts.get(k) != new_prompts.get(k))
    for method in report["methods"]:
        before = baseline["methods"].get(method)
        if before is None:
            continue
        rows = [(c["id"], before[c["id"]], _case_grades(c["results"][method]))
                for c in report["cases"] if c["id"] in before]
        out.compared[method] = len(rows)
        out.answers_changed += sum(old["answer"] != new["answer"] for _, old, new in rows)
        for metric in GATED:
            was = _mean([old[metric] for _, old, _ in rows])
            now = _mean([new[metric] for _, _, new in rows])
            if was is None or now is None:
                continue
            change = (now - was) if metric in LOWER_IS_BETTER else (was - now)
            if change > tolerance + 1e-12:
                out.drops.append(MetricDrop(method, metric, was, now))
            for case_id, old, new in rows:
                if _worse(metric, old[metric], new[metric]):
                    out.flips.append(CaseFlip(method, case_id, metric, old["answer"], new["answer"]))
    return out


def differences(report: dict[str, Any], baseline: dict[str, Any]) -> list[str]:
    """Every case, method and metric whose grade differs from the baseline's, better or worse."""
    out: list[str] = []
    for method in report["methods"]:
        before = baseline["methods"].get(method, {})
        for c in report["cases"]:
            if c["id"] not in before:
                continue
            now = _case_grades(c["results"][method])
            out += [f"{method} {c['id']} {k}: {before[c['id']][k]} -> {now[k]}" for k in GATED
                    if before[c["id"]][k] != now[k]]
    return out
