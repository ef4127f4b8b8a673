"""`hexar eval`: the paper's evaluation, end to end. Returns the exit code: 0 done, 1 regression against the
baseline; user errors are raised (HexarError and friends) for the CLI's `guarded()` to report with exit 2."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

from hexar.agent.backends import Backend, resolve
from hexar.errors import HexarError
from hexar.evals import audit as audit_mod
from hexar.evals import regression as reg
from hexar.evals.judge import Judge
from hexar.evals.markdown import LABEL, ORDER, render
from hexar.evals.methods import METHODS
from hexar.evals.report import build, write_json
from hexar.evals.run import Selection, default_runs, run
from hexar.explainers.base import TextModel
from hexar.inputs import output_dir
from hexar.safe_text import safe


@dataclass(frozen=True)
class EvalOptions:
    out: Path
    runs: Path | None = None  # default: ~/.cache/hexar/eval-runs/seed-<seed>
    llm: str = "none"
    methods: Sequence[str] = ()  # empty: all three
    scenarios: Sequence[int] = ()
    modules: Sequence[str] = ()
    kinds: Sequence[str] = ()
    first: int | None = None
    judge: str | None = None
    audit: int = 0
    baseline: Path | None = None
    write_baseline: Path | None = None
    tolerance: float = reg.DEFAULT_TOLERANCE
    seed: int = 0
    resimulate: bool = False
    figures: bool = True
    progress: bool = True


def _check(opts: EvalOptions) -> Selection:
    if opts.audit < 0:
        raise HexarError("--audit must be 0 or more")
    if not 0 <= opts.tolerance < 1:
        raise HexarError("--tolerance is a fraction between 0 and 1, e.g. 0.02 for two points")
    if bad := [m for m in opts.methods if m not in METHODS]:
        raise HexarError(f"unknown method {bad[0]!r}: use {', '.join(METHODS)}")
    if opts.out.exists() and not opts.out.is_dir():
        raise HexarError(f"--out must be a folder: {opts.out}")
    return Selection(frozenset(opts.scenarios), frozenset(opts.modules), frozenset(opts.kinds), opts.first)


def _judge(spec: str | None, model: TextModel | None) -> Judge | None:
    if model is not None:
        return Judge(model)
    if not spec or spec == "none":
        return None
    backend = resolve(spec)
    if backend.model is None:
        raise HexarError(f"--judge {spec!r} gives no model: use ollama:MODEL")
    return Judge(backend.model)


def summary_table(report: dict[str, Any]) -> Table:
    t = Table("method", "root cause", "incorrect facts", "accuracy", "runtime (s)", "selection",
              title=f"hexar eval ({report['backend']})")
    for m in ORDER:
        s = report["summary"].get(m)
        if s is None:
            if m in report["not_applicable"]:
                t.add_row(LABEL[m], "n/a", "n/a", "n/a", "n/a", "n/a")
            continue
        sel = s.get("selection")
        t.add_row(LABEL[m], *(f"{100 * s[k]['mean']:.2f} %" for k in ("root_cause", "incorrect_facts", "accuracy")),
                  f"{s['runtime_s']['mean']:.3f}", f"{sel['correct']}/{sel['n']}" if sel else "–")
    return t


def regression_table(result: reg.Regression) -> Table:
    t = Table("method", "case", "metric", "baseline answer", "answer now", title="Regressions", show_lines=True)
    for d in result.drops:
        t.add_row(d.method, "(all)", d.metric, f"{100 * d.baseline:.2f} %", f"{100 * d.now:.2f} %")
    for f in result.flips:
        t.add_row(f.method, safe(f.case), f.metric, safe(f.baseline_answer), safe(f.answer))
    return t


def eval_command(opts: EvalOptions, console: Console | None = None, progress_console: Console | None = None, *,
                 backend: Backend | None = None, judge_model: TextModel | None = None) -> int:
    """Run, grade, test, write and gate. `backend`/`judge_model` replace `--llm`/`--judge` (tests inject fakes)."""
    console = console or Console(highlight=False)
    selection = _check(opts)
    baseline = reg.read_baseline(opts.baseline) if opts.baseline is not None else None
    backend = backend or resolve(opts.llm)
    if baseline is not None and baseline["backend"] != backend.name:
        raise HexarError(f"the baseline {opts.baseline} is for backend {baseline['backend']!r}, this run uses "
                         f"{backend.name!r}")
    judge = _judge(opts.judge, judge_model)
    bar = (progress_console or Console(stderr=True)) if opts.progress else None
    runs = opts.runs or default_runs(opts.seed)
    output = run(runs, backend, selection, opts.methods or METHODS, judge, opts.seed, bar, opts.resimulate)
    report = build(output, runs, selection.as_dict(), opts.seed)
    code = 0
    result = None
    if baseline is not None:
        result = reg.compare(report, baseline, opts.tolerance)
        report["regression"] = {**result.as_dict(), "baseline": str(opts.baseline)}
        code = 1 if result.failed else 0
    output_dir(opts.out, "--out")
    write_json(report, opts.out / "report.json")
    figures: list[str] = []
    if opts.figures:
        from hexar.evals.figures import draw

        figures = draw(report, opts.out)
    (opts.out / "results.md").write_text(render(report, figures), encoding="utf-8")
    console.print(summary_table(report))
    stats = report["statistics"]
    console.print(f"statistics: {stats['reason']}" if not stats["applicable"]
                  else "statistics: Cochran's Q and Holm-corrected McNemar in results.md")
    if opts.audit:
        audit_mod.show(report, opts.audit, console)
        (opts.out / "audit.md").write_text(audit_mod.markdown(report, opts.audit), encoding="utf-8")
    if opts.write_baseline is not None:
        reg.write_baseline(report, opts.write_baseline)
        console.print(f"wrote baseline {opts.write_baseline}")
    if result is not None:
        _print_regression(result, console)
    console.print(f"report: {opts.out / 'report.json'}, table: {opts.out / 'results.md'}")
    return code


def _print_regression(result: reg.Regression, console: Console) -> None:
    compared = ", ".join(f"{m} {n}" for m, n in result.compared.items()) or "nothing"
    if result.prompts_changed:
        console.print("prompts changed since the baseline: " + ", ".join(result.prompts_changed))
    if result.failed:
        console.print(regression_table(result))
        console.print(f"REGRESSION against the baseline (cases compared: {compared}; tolerance "
                      f"{100 * result.tolerance:.1f} points)")
    else:
        console.print(f"no regression against the baseline (cases compared: {compared}; "
                      f"{result.answers_changed} answers worded differently)")
