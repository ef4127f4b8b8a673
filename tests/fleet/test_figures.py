"""The figures of `hexar triage`: the counts they stack are pivot_table's, and they are 10x5 inch PNGs at 110 dpi."""

from __future__ import annotations

import struct
from pathlib import Path

import pandas as pd

from hexar.fleet.report import _stacks, draw, flag

ROWS = [("robot-b", "2025-03-11", "failure", "navigation.blocked_path"),
        ("robot-b", "2025-03-11", "failure", "navigation.blocked_path"),
        ("", "2025-03-10", "finding", "tts.timeout"),
        ("robot-a", "2025-03-10", "failure", ""),
        ("robot-a", "2025-03-12", "", ""),
        ("robot-a", "2025-03-12", "finding", "ask_human.refused")]


def _rows(rows: list[tuple[str, str, str, str]]) -> list[dict[str, str]]:
    return [{"recording": f"{robot}/r{i}", "robot": robot, "task_id": f"t{i}", "day": day, "kind": kind,
             "cause": cause} for i, (robot, day, kind, cause) in enumerate(rows)]


def test_the_stacked_counts_are_pivot_tables() -> None:
    flagged_rows = flag(_rows(ROWS))
    flagged = pd.DataFrame(flagged_rows)
    for key in ("day", "robot"):
        expected = flagged.assign(robot=flagged["robot"].replace("", "(unnamed)")).pivot_table(
            index=key, columns="cause", values="task_id", aggfunc="count", fill_value=0)
        keys, causes, counts = _stacks(flagged_rows, key)
        assert keys == list(expected.index) and causes == list(expected.columns)
        assert counts.tolist() == expected.to_numpy().T.tolist()


def test_two_pngs_of_10x5_inches_at_110_dpi(tmp_path: Path) -> None:
    names = draw(_rows(ROWS), tmp_path)
    assert names == ["causes_over_time.png", "causes_per_robot.png"]
    for name in names:
        head = (tmp_path / name).read_bytes()[:24]
        assert head[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">II", head[16:24]) == (1100, 550)


def test_no_figures_when_nothing_is_worth_a_look(tmp_path: Path) -> None:
    assert draw(_rows([("robot-a", "2025-03-12", "", "")]), tmp_path) == []
    assert not list(tmp_path.iterdir())
