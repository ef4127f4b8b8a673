"""The outputs of `hexar triage`: a Parquet and a JSON-lines table of all tasks, a Markdown report and figures."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import pandas as pd

from hexar.fleet.errors import TriageError
from hexar.safe_text import visible

COLUMNS = ["recording", "robot", "storage", "task_id", "order", "instruction", "recovery", "outcome", "failed_skill",
           "kind", "explainer", "cause", "causes", "explanation", "evidence", "time", "day", "t_ns", "duration_s"]
TOP = 10


def table(results: list[dict[str, Any]]) -> pd.DataFrame:
    rows = [row for r in sorted(results, key=lambda r: r["recording"]) for row in r["rows"]]
    return pd.DataFrame(rows, columns=COLUMNS)


def write_outputs(results: list[dict[str, Any]], out: Path, figures: bool = True,
                  parquet: bool = True) -> dict[str, int]:
    df = table(results)
    with (out / "tasks.jsonl").open("w", encoding="utf-8") as f:
        for row in df.to_dict(orient="records"):
            f.write(json.dumps(row, ensure_ascii=False) + "\n")
    if parquet:
        try:
            df.to_parquet(out / "tasks.parquet", index=False)
        except ImportError as err:
            raise TriageError("Parquet output needs pyarrow: pip install 'hexar[fleet]'") from err
    else:
        (out / "tasks.parquet").unlink(missing_ok=True)  # an earlier run's table would be read as this run's
    pictures = draw(df, out) if figures else []
    (out / "report.md").write_text(report(df, results, pictures), encoding="utf-8")
    return summary(df, results)


def summary(df: pd.DataFrame, results: list[dict[str, Any]]) -> dict[str, int]:
    return {"recordings": len(results), "unreadable": sum(1 for r in results if r["error"]),
            "without_tasks": sum(1 for r in results if not r["error"] and not r["rows"]), "tasks": len(df),
            "failed": int((df["kind"] == "failure").sum()), "findings": int((df["kind"] == "finding").sum())}


def _md(text: object) -> str:
    """Recorded text in a Markdown table cell: no pipes, no newlines, no HTML."""
    return re.sub(r"[|<>\n\r`]", " ", visible(text)).strip()


def _counts(series: pd.Series, title: str, what: str) -> list[str]:
    lines = [f"### By {title}", "", f"| {what} | tasks |", "|---|---:|"]
    lines += [f"| {_md(k) or '(none)'} | {v} |" for k, v in series.value_counts().items()]
    return [*lines, ""]


UNEXPLAINED = "(failed, no cause found)"


def flag(df: pd.DataFrame) -> pd.DataFrame:
    """Tasks worth a look: those with a cause, and failures no explainer found a cause for (a new problem is
    often exactly that)."""
    rows = df[(df["cause"] != "") | (df["kind"] == "failure")].copy()
    rows.loc[rows["cause"] == "", "cause"] = UNEXPLAINED
    return rows


def look_first(df: pd.DataFrame) -> pd.DataFrame:
    """Recordings with failures first, a rare cause (a new problem) before a common one, then more findings."""
    flagged = flag(df)
    if flagged.empty:
        return flagged
    freq = flagged["cause"].value_counts()
    # counted as columns, not by a Python function per group: a thousand recordings are a thousand groups
    per = flagged.assign(failures=flagged["kind"] == "failure", findings=flagged["kind"] == "finding").groupby(
        "recording").agg(failures=("failures", "sum"), findings=("findings", "sum"), cause=("cause", "first"),
                         explanation=("explanation", "first"), robot=("robot", "first"), time=("time", "first"))
    per["rarity"] = per["cause"].map(freq)
    return per.sort_values(["failures", "rarity", "findings"], ascending=[False, True, False]).head(TOP)


def report(df: pd.DataFrame, results: list[dict[str, Any]], pictures: list[str]) -> str:
    s = summary(df, results)
    flagged = flag(df)
    lines = ["# HEXAR fleet triage", "",
             f"{s['recordings']} recordings ({s['unreadable']} unreadable, {s['without_tasks']} without a task), "
             f"{s['tasks']} tasks: {s['failed']} failed "
             f"or wrongly planned, {s['findings']} succeeded with a finding worth a look. Explained without an LLM "
             "by the failure check and the component explainers; every cause is backed by recorded evidence.", ""]
    lines += ["## Most frequent causes", ""]
    for cause, n in flagged["cause"].value_counts().head(TOP).items():
        ex = flagged[flagged["cause"] == cause].iloc[0]
        lines += [f"- **{_md(cause)}**: {n} tasks. Example, {_md(ex['recording'])} ({ex['time']}): "
                  f"\"{_md(ex['explanation'])}\" ({ex['evidence']} evidence items)"]
    lines += ["", "## Counts", "",
              f"The tables by cause, module, robot and day count the {len(flagged)} tasks worth a look (a failure, "
              f"a wrong plan or a finding); the other {s['tasks'] - len(flagged)} of the {s['tasks']} tasks went as "
              "planned and are counted only under Outcomes.", ""]
    lines += _counts(flagged["cause"], "cause", "cause")
    lines += _counts(flagged["explainer"], "module (explainer)", "explainer")
    lines += _counts(flagged["robot"], "robot", "robot")
    lines += _counts(flagged["day"], "day", "day")
    lines += ["### Outcomes", "", "| outcome | tasks |", "|---|---:|"]
    lines += [f"| {k} | {v} |" for k, v in df["outcome"].value_counts().items()] + [""]
    lines += ["## Recordings to look at first", "", "| recording | robot | time | failures | findings | cause | "
              "explanation |", "|---|---|---|---:|---:|---|---|"]
    for rec, row in look_first(df).iterrows():
        lines.append(f"| {_md(rec)} | {_md(row['robot'])} | {row['time']} | {row['failures']} | {row['findings']} | "
                     f"{_md(row['cause'])} | {_md(row['explanation'])} |")
    bad = [r for r in results if r["error"]]
    if bad:
        lines += ["", "## Unreadable recordings", "", "| recording | error |", "|---|---|"]
        lines += [f"| {_md(r['recording'])} | {_md(r['error'])} |" for r in bad]
    recovered = [(r["recording"], w) for r in results for w in r.get("recovered", [])]
    if recovered:
        lines += ["", "## Recovered recordings", "", "Cut short by a crash or power loss and read as `ros2 bag "
                  "reindex` recovers them; their tasks are in the tables above.", "", "| recording | recovery |",
                  "|---|---|"]
        lines += [f"| {_md(rec)} | {_md(w.removeprefix('recovered: '))} |" for rec, w in recovered]
    if pictures:
        lines += ["", "## Figures", ""] + [f"![{p}]({p})" for p in pictures]
    return "\n".join(lines) + "\n"


def draw(df: pd.DataFrame, out: Path) -> list[str]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    flagged = flag(df)
    if flagged.empty:
        return []
    names = []
    for key, name, title in (("day", "causes_over_time.png", "Causes per day"),
                             ("robot", "causes_per_robot.png", "Causes per robot")):
        counts = flagged.assign(robot=flagged["robot"].replace("", "(unnamed)")).pivot_table(
            index=key, columns="cause", values="task_id", aggfunc="count", fill_value=0)
        fig, ax = plt.subplots(figsize=(10, 5))
        counts.plot(kind="bar", stacked=True, ax=ax, colormap="tab20", width=0.8)
        ax.set_title(title)
        ax.set_ylabel("tasks")
        ax.set_xlabel(key)
        ax.legend(fontsize=7, bbox_to_anchor=(1.01, 1), loc="upper left")
        fig.tight_layout()
        fig.savefig(out / name, dpi=110)
        plt.close(fig)
        names.append(name)
    return names
