"""`hexar triage --compare`: the causes of two triage runs, or of two periods of one run, side by side."""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path
from typing import Any

from hexar.fleet.errors import TriageError
from hexar.fleet.report import Row, _md, flag, read_table

_PERIOD = re.compile(r"^(\d{4}-\d{2}-\d{2})(?:\.\.(\d{4}-\d{2}-\d{2}))?$")


def _side(spec: str, base: Path | None) -> list[Row]:
    """A triage output folder, its tasks.jsonl/.parquet, or a day range DAY[..DAY] of the run in --out."""
    path = Path(spec)
    if path.is_dir():
        path = path / "tasks.parquet" if (path / "tasks.parquet").is_file() else path / "tasks.jsonl"
    if path.is_file():
        try:
            return read_table(path)
        except (ValueError, OSError, ImportError) as err:  # pyarrow's ArrowInvalid is a ValueError
            raise TriageError(f"cannot read triage results {path}: {err}") from err
    m = _PERIOD.match(spec)
    if m and base is not None and (base / "tasks.jsonl").is_file():
        first, last = m.group(1), m.group(2) or m.group(1)
        return [row for row in _side(str(base), None) if first <= row["day"] <= last]
    raise TriageError(f"cannot compare {spec!r}: give a triage output folder, a tasks file, or a day range "
                      "YYYY-MM-DD[..YYYY-MM-DD] of the run in --out")


def compare(a: str, b: str, base: Path | None) -> dict[str, Any]:
    """Per cause: tasks in A and in B, per 100 tasks, and the change; causes that appeared or disappeared."""
    da, db = _side(a, base), _side(b, base)
    ca, cb = Counter(row["cause"] for row in flag(da)), Counter(row["cause"] for row in flag(db))
    na, nb = max(len(da), 1), max(len(db), 1)
    rows = [{"cause": cause, "a": ca[cause], "b": cb[cause], "a_per_100": round(100 * ca[cause] / na, 1),
             "b_per_100": round(100 * cb[cause] / nb, 1), "change": cb[cause] - ca[cause]}
            for cause in sorted(set(ca) | set(cb), key=lambda k: (-abs(cb[k] - ca[k]), k))]
    return {"a": a, "b": b, "tasks_a": len(da), "tasks_b": len(db),
            "failed_a": sum(row["kind"] == "failure" for row in da),
            "failed_b": sum(row["kind"] == "failure" for row in db),
            "new": [r["cause"] for r in rows if r["a"] == 0], "gone": [r["cause"] for r in rows if r["b"] == 0],
            "causes": rows}


def compare_markdown(result: dict[str, Any]) -> str:
    lines = [f"# Triage: {_md(result['a'])} vs {_md(result['b'])}", "",
             f"Tasks: {result['tasks_a']} -> {result['tasks_b']}; failed: {result['failed_a']} -> "
             f"{result['failed_b']}.", ""]
    if result["new"]:
        lines.append(f"New causes: {', '.join(result['new'])}.")
    if result["gone"]:
        lines.append(f"Gone: {', '.join(result['gone'])}.")
    lines += ["", "| cause | A | B | A per 100 tasks | B per 100 tasks | change |", "|---|---:|---:|---:|---:|---:|"]
    lines += [f"| {r['cause']} | {r['a']} | {r['b']} | {r['a_per_100']} | {r['b_per_100']} | {r['change']:+d} |"
              for r in result["causes"]]
    return "\n".join(lines) + "\n"
