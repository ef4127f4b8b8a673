"""MCAP files side by side in one folder with no metadata.yaml (what `hexar annotate --out` or another tool writes):
each is a recording of its own, never read together; the numbered splits of one bag cut short stay one recording."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from hexar.cli import main
from hexar.evals.cases import scenario
from hexar.evals.scenarios.suite import record
from hexar.events.errors import NotARecordingError
from hexar.events.reader import read_recording
from tests.web.browser import served
from tests.web.test_server import get


@pytest.fixture(scope="module")
def bags(tmp_path_factory: pytest.TempPathFactory) -> dict[int, Path]:
    """Scenario 5 (a blocked path) and 10 (all went well) as MCAP recordings, closed properly."""
    out = tmp_path_factory.mktemp("bags")
    return {n: record(scenario(n), 1).write(out / f"bag{n}", "mcap") for n in (5, 10)}


def _side_by_side(bags: dict[int, Path], folder: Path, names: dict[int, str]) -> Path:
    folder.mkdir()
    for n, name in names.items():
        shutil.copy(next(bags[n].glob("*.mcap")), folder / name)
    return folder


def test_each_file_is_read_alone(bags: dict[int, Path], tmp_path: Path) -> None:
    folder = _side_by_side(bags, tmp_path / "out", {5: "blocked.mcap", 10: "fine.mcap"})
    for n, name in ((5, "blocked.mcap"), (10, "fine.mcap")):
        alone, whole = read_recording(folder / name), read_recording(bags[n])
        assert [(t.task_id, t.outcome) for t in alone.tasks] == [(t.task_id, t.outcome) for t in whole.tasks]
        assert [ln.msg for ln in alone.logs] == [ln.msg for ln in whole.logs]
        assert not alone.warnings and alone.storage == "mcap"  # a whole file is no crashed recording
    with pytest.raises(NotARecordingError, match=r"holds 2 storage files of separate recordings \(blocked\.mcap, "
                                                 r"fine\.mcap\): give one of them"):
        read_recording(folder)


def test_runs_ask_and_the_page_name_each_file(bags: dict[int, Path], tmp_path: Path,
                                              capsys: pytest.CaptureFixture[str]) -> None:
    folder = _side_by_side(bags, tmp_path / "out", {5: "blocked.mcap", 10: "fine.mcap"})
    assert main(["runs", str(folder), "--json"]) == 0
    rows = {r["recording"]: r["outcome"] for r in json.loads(capsys.readouterr().out)}
    assert rows == {"blocked.mcap": "failed", "fine.mcap": "succeeded"}
    assert main(["ask", str(folder / "fine.mcap"), "what happened?", "--llm", "none"]) == 0
    out = capsys.readouterr()
    assert "I did all 4 steps of my plan" in " ".join(out.out.split()) and "recovered" not in out.err
    assert main(["ask", str(folder), "what happened?", "--llm", "none"]) == 2
    assert "ERROR: not one recording" in capsys.readouterr().err
    with served(folder, tmp_path / "t.sqlite") as url:
        status, data = get(url + "api/runs")
        assert status == 200 and [r["recording"] for r in data["runs"]] == ["blocked.mcap", "fine.mcap"]
        status, run = get(url + "api/run?name=blocked.mcap")
        assert status == 200 and run["task"]["outcome"] == "failed"


def test_the_splits_of_one_bag_cut_short_stay_one_recording(bags: dict[int, Path], tmp_path: Path) -> None:
    # rosbag2 names a recording's splits <bag>_0.mcap, <bag>_1.mcap: a crash leaves them without metadata.yaml
    folder = _side_by_side(bags, tmp_path / "crashed", {5: "crashed_0.mcap", 10: "crashed_1.mcap"})
    both = read_recording(folder / "crashed_0.mcap")
    assert both.warnings[0].startswith("recovered: crashed has no metadata.yaml")
    assert "crashed_0.mcap, crashed_1.mcap" in both.warnings[0]
    assert len(both.tasks) == 3  # scenario 5's task and its recovery, and scenario 10's


def test_a_file_of_its_own_is_annotated_alone(bags: dict[int, Path], tmp_path: Path) -> None:
    folder = _side_by_side(bags, tmp_path / "out", {5: "blocked.mcap", 10: "fine.mcap"})
    out = tmp_path / "annotated.mcap"
    assert main(["annotate", str(folder / "blocked.mcap"), "--out", str(out)]) == 0
    annotated, whole = read_recording(out), read_recording(bags[5])
    assert [(t.task_id, t.outcome) for t in annotated.tasks] == [(t.task_id, t.outcome) for t in whole.tasks]
    assert {"/hexar/explanations", "/rosout"} <= set(annotated.topics)
