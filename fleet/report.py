"""The outputs of `hexar triage`: a Parquet and a JSON-lines table of all tasks, a Markdown report and figures."""

from __future__ import annotations

import json
import re
from collections import Counter
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from hexar.fleet.errors import TriageError
from hexar.safe_text import visible

if TYPE_CHECKING:
    import numpy.typing as npt
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

COLUMNS = ["recording", "robot", "storage", "task_id", "order", "instruction", "recovery", "outcome", "failed_skill",
           "kind", "explainer", "cause", "causes", "explanation", "evidence", "time", "day", "t_ns", "duration_s"]
TOP = 10
DPI = 110
Row = dict[str, Any]


def table(results: list[dict[str, Any]]) -> list[Row]:
    """Every task row, by recording, with the columns in COLUMNS' order (None for one an older results file lacks).
    Plain rows rather than a data frame: importing pandas took longer than triaging a small fleet."""
    return [{c: row.get(c) for c in COLUMNS} for r in sorted(results, key=lambda r: r["recording"])
            for row in r["rows"]]


def _schema() -> Any:
    """The Parquet columns' types: the ones pandas wrote for this table (large strings, a list of strings)."""
    import pyarrow as pa

    text, whole = pa.large_string(), pa.int64()
    kinds = {"order": whole, "recovery": pa.bool_(), "causes": pa.list_(pa.string()), "evidence": whole,
             "t_ns": whole, "duration_s": pa.float64()}
    return pa.schema([(c, kinds.get(c, text)) for c in COLUMNS])


def write_parquet(jsonl: Path, path: Path) -> None:
    """tasks.jsonl as Parquet, parsed by Arrow's JSON reader: building the table from Python values makes pyarrow
    import pandas, which costs more than the rest of a small fleet's triage."""
    try:
        import pyarrow.json as pj
        import pyarrow.parquet as pq
    except ImportError as err:
        raise TriageError("Parquet output needs pyarrow: pip install 'hexar[fleet]'") from err
    schema = _schema()
    if jsonl.stat().st_size:
        tasks = pj.read_json(jsonl, parse_options=pj.ParseOptions(explicit_schema=schema,
                                                                  unexpected_field_behavior="error"))
    else:  # no task at all: Arrow's reader refuses an empty file
        tasks = schema.empty_table()
    pq.write_table(tasks, path)


def read_table(path: Path) -> list[Row]:
    """A triage run's tasks.parquet or tasks.jsonl, as rows."""
    if path.suffix == ".parquet":
        import pyarrow.parquet as pq

        rows: list[Row] = pq.read_table(path).to_pylist()
        return rows
    with path.open(encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]


def write_outputs(results: list[dict[str, Any]], out: Path, figures: bool = True,
                  parquet: bool = True) -> dict[str, int]:
    rows = table(results)
    with (out / "tasks.jsonl").open("w", encoding="utf-8") as f:
        for row in rows:
            f.write(json.dumps(row, ensure_ascii=False) + "\n")
    if parquet:
        write_parquet(out / "tasks.jsonl", out / "tasks.parquet")
    else:
        (out / "tasks.parquet").unlink(missing_ok=True)  # an earlier run's table would be read as this run's
    pictures = draw(rows, out) if figures else []
    (out / "report.md").write_text(report(rows, results, pictures), encoding="utf-8")
    return summary(rows, results)


def summary(rows: list[Row], results: list[dict[str, Any]]) -> dict[str, int]:
    kinds = Counter(row["kind"] for row in rows)
    return {"recordings": len(results), "unreadable": sum(1 for r in results if r["error"]),
            "without_tasks": sum(1 for r in results if not r["error"] and not r["rows"]), "tasks": len(rows),
            "failed": kinds["failure"], "findings": kinds["finding"]}


def count(n: int, thing: str) -> str:
    """"1 task", "6 tasks"."""
    return f"{n} {thing}" if n == 1 else f"{n} {thing}s"


def _md(text: object) -> str:
    """Recorded text in a Markdown table cell: no pipes, no newlines, no HTML."""
    return re.sub(r"[|<>\n\r`]", " ", visible(text)).strip()


def counted(values: Iterable[Any]) -> list[tuple[Any, int]]:
    """Each value and how often it occurs, the most frequent first, ties in order of first occurrence."""
    return Counter(values).most_common()


def _counts(rows: list[Row], key: str, title: str, what: str) -> list[str]:
    lines = [f"### By {title}", "", f"| {what} | tasks |", "|---|---:|"]
    lines += [f"| {_md(k) or '(none)'} | {v} |" for k, v in counted(row[key] for row in rows)]
    return [*lines, ""]


UNEXPLAINED = "(failed, no cause found)"


def flag(rows: list[Row]) -> list[Row]:
    """Tasks worth a look: those with a cause, and failures no explainer found a cause for (a new problem is
    often exactly that)."""
    return [{**row, "cause": row["cause"] or UNEXPLAINED} for row in rows
            if row["cause"] != "" or row["kind"] == "failure"]


def look_first(rows: list[Row]) -> list[Row]:
    """Recordings with failures first, a rare cause (a new problem) before a common one, then more findings."""
    flagged = flag(rows)
    freq = Counter(row["cause"] for row in flagged)
    per: dict[str, Row] = {}
    for row in flagged:
        got = per.setdefault(row["recording"], {"recording": row["recording"], "failures": 0, "findings": 0,
                                                 **{k: row[k] for k in ("cause", "explanation", "robot", "time")}})
        got["failures"] += row["kind"] == "failure"
        got["findings"] += row["kind"] == "finding"
    return sorted(per.values(), key=lambda g: (-g["failures"], freq[g["cause"]], -g["findings"], g["recording"]))[:TOP]


def report(rows: list[Row], results: list[dict[str, Any]], pictures: list[str]) -> str:
    s = summary(rows, results)
    flagged = flag(rows)
    lines = ["# HEXAR fleet triage", "",
             f"{s['recordings']} recordings ({s['unreadable']} unreadable, {s['without_tasks']} without a task), "
             f"{s['tasks']} tasks: {s['failed']} failed "
             f"or wrongly planned, {s['findings']} succeeded with a finding worth a look. Explained without an LLM "
             "by the failure check and the component explainers; every cause is backed by recorded evidence.", ""]
    lines += ["## Most frequent causes", ""]
    for cause, n in counted(row["cause"] for row in flagged)[:TOP]:
        ex = next(row for row in flagged if row["cause"] == cause)
        lines += [f"- **{_md(cause)}**: {count(n, 'task')}. Example, {_md(ex['recording'])} ({ex['time']}): "
                  f"\"{_md(ex['explanation'])}\" ({count(ex['evidence'], 'evidence item')})"]
    lines += ["", "## Counts", "",
              f"The tables by cause, module, robot and day count the {len(flagged)} tasks worth a look (a failure, "
              f"a wrong plan or a finding); the other {s['tasks'] - len(flagged)} of the {s['tasks']} tasks went as "
              "planned and are counted only under Outcomes.", ""]
    lines += _counts(flagged, "cause", "cause", "cause")
    lines += _counts(flagged, "explainer", "module (explainer)", "explainer")
    lines += _counts(flagged, "robot", "robot", "robot")
    lines += _counts(flagged, "day", "day", "day")
    lines += ["### Outcomes", "", "| outcome | tasks |", "|---|---:|"]
    lines += [f"| {k} | {v} |" for k, v in counted(row["outcome"] for row in rows)] + [""]
    lines += ["## Recordings to look at first", "", "| recording | robot | time | failures | findings | cause | "
              "explanation |", "|---|---|---|---:|---:|---|---|"]
    for row in look_first(rows):
        lines.append(f"| {_md(row['recording'])} | {_md(row['robot'])} | {row['time']} | {row['failures']} | "
                     f"{row['findings']} | {_md(row['cause'])} | {_md(row['explanation'])} |")
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


def _stacks(flagged: list[Row], key: str) -> tuple[list[str], list[str], npt.NDArray[np.int64]]:
    """Tasks per key (day or robot) and cause: the keys and the causes, sorted as pivot_table sorted them, and a
    causes x keys array of counts. Counted with a Counter: pivot_table took milliseconds a figure for the same
    numbers (every row has a task_id, so counting rows counts what pivot_table's count of task_id counted)."""
    keys = [row[key] for row in flagged]
    if key == "robot":
        keys = [k or "(unnamed)" for k in keys]
    causes = [row["cause"] for row in flagged]
    n = Counter(zip(keys, causes, strict=True))
    index, columns = sorted(set(keys)), sorted(set(causes))
    return index, columns, np.array([[n[k, c] for k in index] for c in columns], dtype=np.int64)


def _fit(fig: Figure, ax: Axes) -> None:
    """The margins fig.tight_layout() set, worked out as it does (the axes' decorations, the legend outside on the
    right included, plus 1.08 font sizes of padding; left as they are where they cannot fit) but without its layout
    engine, which made savefig draw every figure twice (once only to lay it out). Measured with the Agg canvas's
    renderer, the one savefig draws with at the same dpi, so the text sizes measured here are cached for the drawing."""
    from matplotlib import rcParams

    bbox = ax.get_tightbbox(for_layout_only=True)
    if bbox is None:
        return
    box, pos = fig.transFigure.inverted().transform_bbox(bbox), ax.get_position(original=True)
    width, height = fig.get_size_inches()
    pad = 1.08 * rcParams["font.size"] / 72
    left, right = max(pos.x0 - box.x0, 0) + pad / width, max(box.x1 - pos.x1, 0) + pad / width
    bottom, top = max(pos.y0 - box.y0, 0) + pad / height, max(box.y1 - pos.y1, 0) + pad / height
    if left + right < 1 and bottom + top < 1:
        fig.subplots_adjust(left=left, right=1 - right, bottom=bottom, top=1 - top)


def draw(rows: list[Row], out: Path) -> list[str]:
    flagged = flag(rows)
    if not flagged:
        return []
    # imported here so that `--no-figures` never imports matplotlib; a Figure on an Agg canvas rather than pyplot,
    # whose import and backend setup took about a third of the time the two figures took
    from matplotlib import colormaps
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    names = []
    for key, name, title in (("day", "causes_over_time.png", "Causes per day"),
                             ("robot", "causes_per_robot.png", "Causes per robot")):
        keys, causes, counts = _stacks(flagged, key)
        fig = Figure(figsize=(10, 5), dpi=DPI)
        FigureCanvasAgg(fig)
        ax = fig.add_subplot()
        # the bars pandas' DataFrame.plot(kind="bar", stacked=True, width=0.8, colormap="tab20") drew, without its
        # plotting layer (and the import of it): per cause one bar a key on top of the causes before it, at the
        # places and x limits pandas computed (the same sums, so the same rounding), coloured from tab20 sampled at
        # len(causes) even steps as pandas did, so a cause keeps its colour
        ticks = np.arange(len(keys))
        bottom = np.zeros(len(keys))
        for cause, row, colour in zip(causes, counts, colormaps["tab20"](np.linspace(0, 1, len(causes))), strict=True):
            ax.bar(ticks, row, 0.8, bottom=bottom, color=colour, label=cause)
            bottom = bottom + row
        ax.set_xlim(ticks[0] - 0.65, ticks[-1] + 0.65)  # half a bar and pandas' 0.25 beside the outer bars
        ax.set_xticks(ticks, keys, rotation=90)
        ax.set_title(title)
        ax.set_ylabel("tasks")
        ax.set_xlabel(key)
        ax.legend(fontsize=7, bbox_to_anchor=(1.01, 1), loc="upper left")
        _fit(fig, ax)
        # zlib level 1 rather than Pillow's 6: the same pixels in a file about a tenth larger, some 10 ms sooner
        fig.savefig(out / name, dpi=DPI, pil_kwargs={"compress_level": 1})
        names.append(name)
    return names
