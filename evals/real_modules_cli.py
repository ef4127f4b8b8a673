"""`hexar eval --suite real-modules|real-modules-heldout`: run, write report.json and results.md (per module and
per cause), print the per-module table."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from rich.console import Console

from hexar.errors import HexarError
from hexar.evals.real_modules import FILES, SUITE, run_suite
from hexar.evals.real_nav2_cli import check_cases, data_path, pct, summary_table, unknown_suite


def _row(name: str, row: dict[str, Any]) -> str:
    g = row["text"]
    return (f"| {name} | {row['n']} | {g['named']}/{row['n_shown']} ({pct(g['named_rate'])}) | "
            f"{g['no_unsupported']}/{row['n']} | {g['honest']} | {g['wrong']} |")


def render(report: dict[str, Any]) -> str:
    head = ["| {0} | excerpts | cause named (logs show it) ↑ | no unsupported cause ↑ | honest not-enough | wrong ↓ |",
            "|---|---|---|---|---|---|"]
    lines = [f"# hexar eval --suite {report['suite']} ({report['backend']})", "",
             f"{report['n']} real console excerpts ({data_path(report, 'real_modules')}), each written as a "
             "rosbag2 recording; half of each outcome with a task on /task_info, half with none. Graded from the "
             "answer's text.", "", "### By module", "", head[0].format("module"), head[1],
             *(_row(k, v) for k, v in report["by_module"].items()), _row("all", report["summary"]), "",
             "### By cause", "", head[0].format("cause"), head[1],
             *(_row(k, v) for k, v in report["by_cause"].items()), "", "### Excerpts not named", ""]
    for e in report["excerpts"]:
        if e["text"]["verdict"] != "named":
            said = e["answer"] or e["error"]
            lines.append(f"- `{e['id']}` ({e['module']}, diagnosed {e['cause']}, logs show it: "
                         f"{'yes' if e['logs_show_cause'] else 'no'}, task: {'yes' if e['with_task'] else 'no'}): "
                         f"{e['text']['verdict']}; claims {', '.join(e['claims']) or 'none'}. Answer: "
                         f"{said[:300]!r}")
    return "\n".join(lines) + "\n"


def real_modules_main(suite: str, out: Path, runs: Path | None, llm: str, console: Console,
                      others: dict[str, object], cases: Path | None = None) -> int:
    """Checks the options that apply, runs the suite and writes its report under `out`."""
    from hexar.agent.backends import resolve

    if suite not in FILES:
        raise unknown_suite(suite)
    check_cases(suite, cases, SUITE)
    if given := [name for name, value in others.items() if value]:
        raise HexarError(f"{', '.join(given)} do not apply to --suite {suite}")
    if out.exists() and not out.is_dir():
        raise HexarError(f"--out must be a folder: {out}")
    if runs is not None and runs.exists() and not runs.is_dir():
        raise HexarError(f"--runs must be a folder: {runs}")
    report = run_suite(resolve(llm), suite, runs, cases=cases)
    out.mkdir(parents=True, exist_ok=True)
    (out / "report.json").write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    (out / "results.md").write_text(render(report), encoding="utf-8")
    console.print(summary_table(report, by="module"))
    console.print(f"report: {out / 'report.json'}, table: {out / 'results.md'}")
    return 0
