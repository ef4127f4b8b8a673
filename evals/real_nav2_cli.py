"""The real-nav2 suite's report (JSON and Markdown tables per distro and per cause), its baseline and gate, and the
body of `hexar eval --suite real-nav2`."""

from __future__ import annotations

import copy
import json
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.table import Table

from hexar.errors import HexarError
from hexar.evals.real_nav2_suite import SUITE, SUITES, run_suite

BASELINE_SCHEMA = 1
RANK = {"wrong": 0, "honest": 1, "named": 2}
RATES = ("named_rate", "no_unsupported_rate")


@dataclass(frozen=True)
class RealNav2Options:
    out: Path
    runs: Path | None = None
    llm: str = "none"
    baseline: Path | None = None
    write_baseline: Path | None = None
    tolerance: float = 0.02
    progress: bool = True
    suite: str = SUITE
    cases: Path | None = None


def pct(x: float | None) -> str:
    return "–" if x is None else f"{100 * x:.1f} %"


def _row(name: str, row: dict[str, Any], kind: str = "text") -> str:
    g = row[kind]
    return (f"| {name} | {row['n']} | {g['named']}/{row['n_shown']} ({pct(g['named_rate'])}) | "
            f"{g['no_unsupported']}/{row['n']} ({pct(g['no_unsupported_rate'])}) | {g['honest']} | {g['wrong']} |")


HEADER = ["| {0} | excerpts | cause named ↑ | no unsupported cause ↑ | honest not-enough | wrong ↓ |",
          "|---|---|---|---|---|---|"]


def _table(title: str, rows: dict[str, dict[str, Any]], first: str, kind: str = "text") -> list[str]:
    return [f"### {title}", "", HEADER[0].format(first), HEADER[1], *(_row(k, v, kind) for k, v in rows.items()), ""]


def _sources(report: dict[str, Any]) -> str:
    """Where the excerpts come from: public threads, runs of the real stack by one of the project's scripts, or a
    user's own --cases file."""
    if report.get("made_by"):
        return f"runs of the real stack by {report['made_by']}"
    return f"{report['sources']} {'sources' if report.get('cases') else 'public threads'}"


def render(report: dict[str, Any]) -> str:
    s = report["summary"]
    lines = [
        f"# hexar eval --suite {report['suite']} ({report['backend']})", "",
        f"{report['n']} real Nav2 console excerpts from {_sources(report)} "
        f"({data_path(report, 'real_nav2')}), each written as a rosbag2 recording; half with a navigation task on "
        "/task_info, half with none. Cause named is counted over the excerpts whose pasted lines show the "
        "diagnosed cause; honest not-enough (\"the logs do not show why\") is counted apart from wrong.", "",
        *_table("All excerpts (graded on the answer's text)", {"all": s}, "set"),
        *_table("Per distro", report["by_distro"], "distro"),
        *_table("Per diagnosed cause", report["by_cause"], "cause"),
        *_table("All excerpts (graded on the cause ids HEXAR returned)", {"all": s}, "set", "structured"),
        "### Excerpts still wrong", "",
    ]
    wrong = [e for e in report["excerpts"] if e["text"]["verdict"] == "wrong"]
    for e in wrong:
        why = (f"unsupported {', '.join(e['text']['unsupported'])}" if e["text"]["unsupported"]
               else e["error"] or "the answer names no cause and does not say the logs cannot tell")
        lines.append(f"- `{e['id']}` ({e['distro']}, diagnosed {e['cause']}, task: {'yes' if e['with_task'] else 'no'})"
                     f": {why}. Answer: {e['answer'][:200]!r}")
    if not wrong:
        lines.append("none")
    return "\n".join(lines) + "\n"


def data_path(report: dict[str, Any], folder: str) -> str:
    """Where the report's excerpts came from: a data file of the suite, or the user's --cases file."""
    return report["data"] if report.get("cases") else f"evals/data/{folder}/{report['data']}"


def baseline_of(report: dict[str, Any]) -> dict[str, Any]:
    return {"schema": BASELINE_SCHEMA, "suite": report["suite"], "backend": report["backend"],
            "created": time.strftime("%Y-%m-%d"), "summary": copy.deepcopy(report["summary"]),
            "excerpts": {e["id"]: {"verdict": e["text"]["verdict"], "unsupported": e["text"]["unsupported"],
                                   "answer": e["answer"]} for e in report["excerpts"]}}


def read_baseline(path: Path, suite: str = SUITE) -> dict[str, Any]:
    try:
        data: dict[str, Any] = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as err:
        raise HexarError(f"cannot read baseline {path}: {err}") from err
    if data.get("schema") != BASELINE_SCHEMA or data.get("suite") != suite:
        raise HexarError(f"{path} is not a {suite} baseline (schema {BASELINE_SCHEMA})")
    return data


def compare(report: dict[str, Any], baseline: dict[str, Any], tolerance: float = 0.02) -> list[str]:
    """What got worse than the baseline: an excerpt's verdict, a new unsupported cause, or a rate beyond
    `tolerance`. Excerpts the baseline does not know (newly collected) are not compared."""
    worse: list[str] = []
    known = baseline["excerpts"]
    for e in report["excerpts"]:
        b = known.get(e["id"])
        if b is None:
            continue
        now = e["text"]
        if RANK[now["verdict"]] < RANK[b["verdict"]]:
            worse.append(f"{e['id']}: {b['verdict']} -> {now['verdict']}")
        elif new := sorted(set(now["unsupported"]) - set(b["unsupported"])):
            worse.append(f"{e['id']}: new unsupported {', '.join(new)}")
    for rate in RATES:
        was, now_rate = baseline["summary"]["text"][rate], report["summary"]["text"][rate]
        if was is not None and now_rate is not None and now_rate < was - tolerance:
            worse.append(f"{rate}: {100 * was:.1f} % -> {100 * now_rate:.1f} %")
    return worse


def summary_table(report: dict[str, Any], by: str = "distro") -> Table:
    """The report's text grades per `by` (the real-Nav2 suites' distros, the real-modules suites' modules)."""
    t = Table(by, "excerpts", "cause named", "no unsupported cause", "honest not-enough", "wrong",
              title=f"hexar eval --suite {report['suite']} ({report['backend']})")
    for name, row in [*report[f"by_{by}"].items(), ("all", report["summary"])]:
        g = row["text"]
        t.add_row(name, str(row["n"]), f"{g['named']}/{row['n_shown']} ({pct(g['named_rate'])})",
                  f"{g['no_unsupported']}/{row['n']}", str(g["honest"]), str(g["wrong"]))
    return t


def real_nav2_command(opts: RealNav2Options, console: Console | None = None) -> int:
    """Runs, writes report.json and results.md under `opts.out`, and gates on a baseline: 1 when worse."""
    from hexar.agent.backends import resolve

    console = console or Console(highlight=False)
    if not 0 <= opts.tolerance < 1:
        raise HexarError("--tolerance is a fraction between 0 and 1, e.g. 0.02 for two points")
    if opts.out.exists() and not opts.out.is_dir():
        raise HexarError(f"--out must be a folder: {opts.out}")
    if opts.runs is not None and opts.runs.exists() and not opts.runs.is_dir():
        raise HexarError(f"--runs must be a folder: {opts.runs}")
    baseline = read_baseline(opts.baseline, opts.suite) if opts.baseline is not None else None
    backend = resolve(opts.llm)
    if baseline is not None and baseline["backend"] != backend.name:
        raise HexarError(f"the baseline {opts.baseline} is for backend {baseline['backend']!r}, this run uses "
                         f"{backend.name!r}")
    report = run_suite(backend, opts.runs, suite=opts.suite, cases=opts.cases)
    worse = compare(report, baseline, opts.tolerance) if baseline is not None else []
    if baseline is not None:
        report["regression"] = {"baseline": str(opts.baseline), "worse": worse}
    opts.out.mkdir(parents=True, exist_ok=True)
    (opts.out / "report.json").write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    (opts.out / "results.md").write_text(render(report), encoding="utf-8")
    console.print(summary_table(report))
    if opts.write_baseline is not None:
        opts.write_baseline.parent.mkdir(parents=True, exist_ok=True)
        opts.write_baseline.write_text(json.dumps(baseline_of(report), indent=1, ensure_ascii=False) + "\n",
                                       encoding="utf-8")
        console.print(f"wrote baseline {opts.write_baseline}")
    if baseline is not None:
        console.print("REGRESSION against the baseline:\n  " + "\n  ".join(worse) if worse
                      else "no regression against the baseline")
    console.print(f"report: {opts.out / 'report.json'}, table: {opts.out / 'results.md'}")
    return 1 if worse else 0


def unknown_suite(suite: str) -> HexarError:
    """The one error for a --suite no suite has: every suite's name (the nav and the module suites alike)."""
    from hexar.evals.real_modules import FILES

    return HexarError(f"unknown suite {suite!r}: use paper, {', '.join([*SUITES, *FILES])}")


def real_nav2_main(suite: str, out: Path, runs: Path | None, llm: str, baseline: Path | None,
                   write_baseline: Path | None, tolerance: float, console: Console,
                   paper_only: dict[str, object], cases: Path | None = None) -> int:
    """`hexar eval --suite NAME` for any suite but the paper's: checks the options that apply, then runs."""
    if suite not in SUITES:
        raise unknown_suite(suite)
    check_cases(suite, cases, SUITE)
    if given := [name for name, value in paper_only.items() if value]:
        raise HexarError(f"{', '.join(given)} belong to the paper's suite, not to --suite {suite}")
    opts = RealNav2Options(out=out, runs=runs, llm=llm, baseline=baseline, write_baseline=write_baseline,
                           tolerance=tolerance, suite=suite, cases=cases)
    return real_nav2_command(opts, console)


def check_cases(suite: str, cases: Path | None, base: str) -> None:
    """--cases replaces a suite's data, so it goes with the suite that names the file's format, not a data set."""
    if cases is not None and suite != base:
        raise HexarError(f"--cases goes with --suite real-nav2 or --suite real-modules (the file's format), "
                         f"not --suite {suite}")
