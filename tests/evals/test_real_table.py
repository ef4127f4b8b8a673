"""The README's tables of the real-log suites (evals/real_table.py, scripts/real_logs_table.py): written from the
committed reports, summed right, and failing the check when the README says otherwise."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest

from hexar.evals.real_table import BEGIN, END, Figures, module_rows, nav2_rows, replace_block, table
from tests.scripts.helpers import load_script

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs" / "eval"
README = ROOT / "README.md"


def test_the_readme_shows_the_committed_reports() -> None:
    text = README.read_text(encoding="utf-8")
    assert replace_block(text, table(DOCS)) == text, "run scripts/real_logs_table.py --write"


def _cells(row: str) -> list[str]:
    return [cell.strip() for cell in row.strip().strip("|").split("|")]


def test_each_row_is_its_report_and_the_totals_are_their_sums() -> None:
    rows = nav2_rows(DOCS)
    blind = [r for r in rows if r.suite.startswith("real-nav2-blind")]
    assert len(blind) == 29 and [r.suite for r in rows[:2]] == ["real-nav2", "real-nav2-heldout"]
    for row in rows:
        summary = json.loads((DOCS / row.suite / "report.json").read_text(encoding="utf-8"))["summary"]
        assert (row.now.named, row.now.shown, row.now.n) == (summary["text"]["named"], summary["n_shown"],
                                                             summary["n"])
    block = table(DOCS)
    total = next(line for line in block.splitlines() if line.startswith("| **blind 1-29**"))
    named = sum(r.now.named for r in blind)
    shown = sum(r.now.shown for r in blind)
    once = sum(r.before.named for r in blind if r.before is not None)
    assert _cells(total)[6] == f"{named}/{shown} ({100 * named / shown:.1f} %)"
    assert _cells(total)[2].startswith(f"{once}/{shown} ")
    # a corpus was tuned on: it has no blind figure, and says so
    assert _cells(next(line for line in block.splitlines() if "corpus (tuned on)](docs/eval/real-nav2/" in line))[
        2:6] == ["–"] * 4
    modules = module_rows(DOCS)
    per_module = {m: sum(r.modules[m][0].named for r in modules[1:] if m in r.modules)
                  for m in ("manipulation", "control", "bringup", "system")}
    assert sum(per_module.values()) == sum(r.now.named for r in modules[1:])


def test_a_set_without_a_blind_measurement_leaves_its_sum_without_one(tmp_path: Path) -> None:
    docs = tmp_path / "eval"
    for name in ("real-nav2-blind", "real-nav2-blind-before", "real-nav2-blind2"):
        shutil.copytree(DOCS / name, docs / name)
    block = table(docs)
    [total] = [line for line in block.splitlines() if line.startswith("| **blind 1-2**")]
    assert _cells(total)[2:6] == ["–"] * 4
    assert "blind 3]" not in block  # a set with no report is left out, not shown as zeros


def test_figures_add_up_and_say_their_rate() -> None:
    total = Figures(10, 8, 6, 9, 1, 1) + Figures(5, 2, 1, 5, 1, 0)
    assert total == Figures(15, 10, 7, 14, 2, 1)
    assert total.cells() == ["7/10 (70.0 %)", "14/15", "2", "1"]
    assert Figures(1, 0, 0, 1, 1, 0).cells()[0] == "0/0"


def test_the_script_writes_checks_and_refuses_a_readme_without_markers(tmp_path: Path,
                                                                       capsys: pytest.CaptureFixture[str]) -> None:
    script = load_script("real_logs_table")
    readme = tmp_path / "README.md"
    readme.write_text(f"# x\n\n{BEGIN}\nold figures\n{END}\n\nafter\n", encoding="utf-8")
    assert script.main(["--readme", str(readme), "--check"]) == 1
    assert "differ from the reports" in capsys.readouterr().err
    assert script.main(["--readme", str(readme), "--write"]) == 0
    assert script.main(["--readme", str(readme), "--check"]) == 0
    text = readme.read_text(encoding="utf-8")
    assert "old figures" not in text and text.endswith(f"{END}\n\nafter\n") and "| **held-out 1-36** |" in text
    readme.write_text("# no markers\n", encoding="utf-8")
    assert script.main(["--readme", str(readme), "--check"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR: ") and err.count("\n") == 1


def test_every_relative_link_of_the_readme_and_the_history_resolves() -> None:
    for doc in (README, DOCS / "real-logs.md"):
        text = doc.read_text(encoding="utf-8")
        targets = [t for t in re.findall(r"\]\(([^)\s]+)\)", text) if not re.match(r"[a-z]+:|#", t)]
        missing = [t for t in targets if not (doc.parent / t.split("#")[0]).exists()]
        assert targets and not missing, (doc.name, missing)
