"""The real-log suites in one place: each set's figures as measured once, before anything was tuned on it, and as
the code answers it now, read from the reports `hexar eval --suite ...` wrote under docs/eval/ (`<suite>-before/`
and `<suite>/`). The README's tables are this module's output between two markers; `scripts/real_logs_table.py`
writes them and `--check` fails when the README and the reports disagree."""

from __future__ import annotations

import json
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexar.evals.real_modules import FILES as MODULE_FILES
from hexar.evals.real_modules import MODULES, load_excerpts
from hexar.evals.real_nav2_suite import SUITES as NAV2_SUITES

BEGIN = "<!-- real-logs-table: written by scripts/real_logs_table.py from docs/eval/*/report.json -->"
END = "<!-- /real-logs-table -->"
# the sets tuned on or read while the explainers were built: no figure of theirs was ever blind
TUNED = frozenset({"real-nav2", "real-modules"})
NAV2_FIRST_RUN = 20  # blind sets from this one on are whole consoles of the real Nav2 run here


@dataclass(frozen=True)
class Figures:
    """A report's text-graded summary: excerpts, those whose lines show the cause, and the four counts."""

    n: int = 0
    shown: int = 0
    named: int = 0
    no_unsupported: int = 0
    honest: int = 0
    wrong: int = 0

    @classmethod
    def of(cls, summary: dict[str, Any]) -> Figures:
        text = summary["text"]
        return cls(summary["n"], summary["n_shown"], text["named"], text["no_unsupported"], text["honest"],
                   text["wrong"])

    def __add__(self, other: Figures) -> Figures:
        return Figures(self.n + other.n, self.shown + other.shown, self.named + other.named,
                       self.no_unsupported + other.no_unsupported, self.honest + other.honest,
                       self.wrong + other.wrong)

    def cells(self) -> list[str]:
        rate = f" ({100 * self.named / self.shown:.1f} %)" if self.shown else ""
        return [f"{self.named}/{self.shown}{rate}", f"{self.no_unsupported}/{self.n}", str(self.honest),
                str(self.wrong)]


@dataclass(frozen=True)
class SetRow:
    suite: str
    label: str
    origin: str
    now: Figures
    before: Figures | None  # None: never measured blind (tuned on, or measured only after it was read)
    modules: dict[str, tuple[Figures, Figures | None]]


def _report(docs: Path, name: str) -> dict[str, Any] | None:
    path = docs / name / "report.json"
    if not path.is_file():
        return None
    report: dict[str, Any] = json.loads(path.read_text(encoding="utf-8"))
    return report


def _origin(sources: set[str]) -> str:
    """Where a set's lines come from: a fault script run here, or how many public sources."""
    scripts = {s.split()[0] for s in sources if s.startswith("scripts/")}
    if scripts and len(scripts) == len({s.split()[0] for s in sources}):
        return ", ".join(f"`{s.removeprefix('scripts/')}` run here" for s in sorted(scripts))
    return f"{len(sources)} public source{'s' if len(sources) != 1 else ''}"


def _row(docs: Path, suite: str, label: str, sources: set[str]) -> SetRow | None:
    now = _report(docs, suite)
    if now is None:
        return None
    before = None if suite in TUNED else _report(docs, f"{suite}-before")
    once = before.get("by_module", {}) if before else {}
    by_module = {m: (Figures.of(s), Figures.of(once[m]) if m in once else None)
                 for m, s in now.get("by_module", {}).items()}
    return SetRow(suite, label, _origin(sources), Figures.of(now["summary"]),
                  Figures.of(before["summary"]) if before else None, by_module)


def nav2_rows(docs: Path) -> list[SetRow]:
    rows = []
    for suite, (_, load) in NAV2_SUITES.items():
        number = suite.removeprefix("real-nav2-blind")
        label = {"real-nav2": "corpus (tuned on)", "real-nav2-heldout": "held-out"}.get(
            suite, f"blind {number or 1}")
        row = _row(docs, suite, label, {e.source for e in load()})
        if row is not None:
            rows.append(row)
    return rows


def module_rows(docs: Path) -> list[SetRow]:
    rows = []
    for suite in MODULE_FILES:
        number = suite.removeprefix("real-modules-heldout")
        label = "corpus (tuned on)" if suite == "real-modules" else f"held-out {number or 1}"
        row = _row(docs, suite, label, {e.source for e in load_excerpts(suite)})
        if row is not None:
            rows.append(row)
    return rows


def _sum(figures: Iterable[Figures | None]) -> Figures | None:
    """The figures added up; None where one of them is missing (a sum is blind only if every part was)."""
    total = Figures()
    for f in figures:
        if f is None:
            return None
        total += f
    return total


HEAD = ("| set | lines from | measured once: named | no unsupported | honest | wrong "
        "| now: named | no unsupported | honest | wrong |\n|---|---|---|---|---|---|---|---|---|---|")


def _line(lead: list[str], now: Figures, before: Figures | None) -> str:
    once = before.cells() if before is not None else ["–"] * 4
    return "| " + " | ".join([*lead, *once, *now.cells()]) + " |"


def _set_line(row: SetRow) -> str:
    return _line([f"[{row.label}](docs/eval/{row.suite}/results.md)", row.origin], row.now, row.before)


def _sum_line(label: str, rows: list[SetRow]) -> str:
    return _line([f"**{label}**", ""], sum((r.now for r in rows), Figures()), _sum(r.before for r in rows))


def table(docs: Path) -> str:
    """The README's tables: Nav2's sets, the modules' sets, and the modules' held-out sets per module."""
    nav2, modules = nav2_rows(docs), module_rows(docs)
    blind = [r for r in nav2 if r.suite.startswith("real-nav2-blind")]
    run_here = [r for r in blind if int(r.suite.removeprefix("real-nav2-blind") or 1) >= NAV2_FIRST_RUN]
    heldout = [r for r in modules if r.suite not in TUNED]
    out = ["Navigation (Nav2):", "", HEAD, *map(_set_line, nav2),
           _sum_line(f"blind 1-{len(blind)}", blind),
           _sum_line(f"blind {NAV2_FIRST_RUN}-{NAV2_FIRST_RUN + len(run_here) - 1} (the real Nav2 run here)",
                     run_here),
           "", "The arm, its controllers and the robot's start (MoveIt 2, ros2_control, launch, rclpy, DDS):", "",
           HEAD, *map(_set_line, modules), _sum_line(f"held-out 1-{len(heldout)}", heldout),
           "", f"Held-out 1-{len(heldout)} per module (the module an excerpt's source says failed):", "",
           "| module | measured once: named | no unsupported | honest | wrong | now: named | no unsupported "
           "| honest | wrong |", "|---|---|---|---|---|---|---|---|---|"]
    for module in MODULES:
        got = [r.modules[module] for r in heldout if module in r.modules]
        out.append(_line([module], sum((n for n, _ in got), Figures()), _sum(b for _, b in got)))
    return "\n".join(out) + "\n"


def replace_block(text: str, block: str) -> str:
    """`text` with what stands between BEGIN and END replaced by `block`."""
    start, end = text.find(BEGIN), text.find(END)
    if start < 0 or end < start:
        raise ValueError(f"the markers {BEGIN!r} and {END!r} are not in the text")
    return text[:start + len(BEGIN)] + "\n" + block + text[end:]


__all__ = ["BEGIN", "END", "Figures", "module_rows", "nav2_rows", "replace_block", "table"]
