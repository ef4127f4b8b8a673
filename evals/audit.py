"""`hexar eval --audit N`: N graded answers beside their ground truth and grades, so that a person can confirm
the graders. Half (at most) are answers the graders marked wrong or the judge disputed, where a grader error
would matter most; the rest are spread evenly over all answers."""

from __future__ import annotations

from typing import Any

from rich.console import Console
from rich.table import Table

from hexar.safe_text import safe, visible

Row = tuple[dict[str, Any], str]  # (case, method)


def _spread(rows: list[Row], n: int) -> list[Row]:
    if n <= 0 or not rows:
        return []
    if n >= len(rows):
        return list(rows)
    return [rows[int(i * len(rows) / n)] for i in range(n)]


def _flagged(case: dict[str, Any], method: str) -> bool:
    res = case["results"][method]
    judge = res.get("judge") or {}
    disputed = any(judge.get(k) is not None and judge[k] != res["grades"][k] for k in ("root_cause", "incorrect_facts"))
    return not res["grades"]["accuracy"] or disputed


def pick(report: dict[str, Any], n: int) -> list[Row]:
    rows = [(c, m) for c in report["cases"] for m in report["methods"]]
    flagged = [r for r in rows if _flagged(*r)]
    chosen = _spread(flagged, min(len(flagged), n // 2))
    rest = [r for r in rows if not any(r[0] is c and r[1] == m for c, m in chosen)]
    chosen += _spread(rest, n - len(chosen))
    order = {id(c): i for i, c in enumerate(report["cases"])}
    return sorted(chosen, key=lambda r: (order[id(r[0])], report["methods"].index(r[1])))


def _yes(v: Any) -> str:
    return "-" if v is None else ("yes" if v else "no")


def grades_text(res: dict[str, Any]) -> str:
    g = res["grades"]
    lines = [f"root cause: {_yes(g['root_cause'])}", f"incorrect facts: {_yes(g['incorrect_facts'])}",
             f"accuracy: {_yes(g['accuracy'])}"]
    if g["selection"] is not None:
        lines.append(f"selection: {_yes(g['selection'])} ({', '.join(res['explainers'] or []) or 'none'})")
    lines.append("claims: " + (", ".join(g["claims"]) or "none"))
    if g["false_claims"]:
        lines.append("false: " + ", ".join(g["false_claims"]))
    judge = res.get("judge")
    if judge:
        lines.append(f"judge: rc {_yes(judge['root_cause'])}, if {_yes(judge['incorrect_facts'])}")
    return "\n".join(lines)


def table(report: dict[str, Any], n: int) -> Table:
    t = Table(show_lines=True, title=f"Audit: {n} answers")
    for name in ("case", "question", "ground truth", "answer", "grades"):
        t.add_column(name, overflow="fold")
    for case, method in pick(report, n):
        res = case["results"][method]
        answer = res["answer"] or f"(no answer: {res['error']})"
        # answers quote the recording; questions and ground truth may come from a user's case file
        t.add_row(safe(f"{case['id']}\n{method}", keep_newlines=True), safe(case["question"]),
                  safe(f"{case['truth']['root_cause']}\n[{case['truth']['cause']}]", keep_newlines=True),
                  safe(answer, keep_newlines=True), safe(grades_text(res), keep_newlines=True))
    return t


def show(report: dict[str, Any], n: int, console: Console) -> None:
    console.print(table(report, n))


def markdown(report: dict[str, Any], n: int) -> str:
    out = ["# Grader audit", "", "| case | question | ground truth | answer | grades |", "|---|---|---|---|---|"]
    for case, method in pick(report, n):
        res = case["results"][method]
        truth = f"{case['truth']['root_cause']} `{case['truth']['cause']}`"
        cells = [visible(c) for c in (f"{case['id']} {method}", case["question"], truth,
                                      res["answer"] or f"(no answer: {res['error']})")]
        cells.append(visible(grades_text(res), keep_newlines=True).replace("\n", "<br>"))
        out.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    return "\n".join(out) + "\n"
