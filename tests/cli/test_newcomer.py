"""What a newcomer met at the command line (issue 24): runs and triage over fleets as people keep them (links,
crashed recordings, a virtualenv beside the runs), pipes, question files with blank lines, `--verbose`,
`--plot`, progress while waiting, and small talk in a chat."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from hexar.cli import main

ROOT = Path(__file__).resolve().parents[2]
HEXAR = str(Path(sys.executable).with_name("hexar"))


def _crashed(src: Path, out: Path) -> Path:
    """A copy of `src` as a recorder killed mid-run leaves it: storage files, no metadata.yaml."""
    bag = shutil.copytree(src, out)
    (bag / "metadata.yaml").unlink()
    return bag


def test_runs_lists_recordings_only_and_says_wrong_plan_and_recovered(suite: Path, tmp_path: Path,
                                                                      capsys: pytest.CaptureFixture[str]) -> None:
    folder = tmp_path / "runs"
    shutil.copytree(suite / "bagfile_3_1", folder / "bagfile_3_1")
    _crashed(suite / "bagfile_5_1", folder / "crashed")
    (folder / ".venv" / "bin").mkdir(parents=True)  # a virtualenv beside the runs holds no recording
    (folder / ".venv" / "pyvenv.cfg").write_text("home = /usr/bin\n")
    (folder / "notes").mkdir()
    assert main(["runs", str(folder), "--json"]) == 0
    rows = {r["recording"]: r for r in json.loads(capsys.readouterr().out)}
    assert set(rows) == {"bagfile_3_1", "crashed"}
    # the robot counted the wrong plan a success; the list says what it was
    assert rows["bagfile_3_1"]["outcome"] == "succeeded" and rows["bagfile_3_1"]["verdict"] == "wrong plan"
    assert rows["crashed"]["recovered"] and rows["crashed"]["outcome"] == "failed"
    assert main(["runs", str(folder)]) == 0
    table = capsys.readouterr().out
    assert "wrong plan" in table and "failed (recovered)" in table and ".venv" not in table


def test_triage_follows_links_lists_recovered_and_unreadable(suite: Path, tmp_path: Path) -> None:
    fleet = tmp_path / "fleet"
    (fleet / "links").mkdir(parents=True)
    (fleet / "links" / "r3").symlink_to(suite / "bagfile_3_1")  # a fleet folder of links to recordings
    (fleet / "links" / "r5").symlink_to(suite / "bagfile_5_1")
    robot = fleet / "robot2"
    _crashed(suite / "bagfile_12_1", robot / "crashed")
    (robot / "broken").mkdir()
    (robot / "broken" / "bag_0.db3").write_bytes(b"not sqlite at all" * 10)  # a folder it cannot read
    out = tmp_path / "out"
    done = subprocess.run([HEXAR, "triage", str(fleet), "--out", str(out), "--workers", "1", "--no-figures"],
                          capture_output=True, text=True, cwd=ROOT, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    rows = [json.loads(line) for line in (out / "tasks.jsonl").read_text().splitlines()]
    recordings = {r["recording"] for r in rows}
    assert {"links/r3", "links/r5", "robot2/crashed"} <= recordings
    report = (out / "report.md").read_text()
    assert "## Recovered recordings" in report and "robot2/crashed" in report and "no metadata.yaml" in report
    assert "## Unreadable recordings" in report and "robot2/broken" in report
    # the tables by robot and day count only the tasks worth a look, and the report says so
    assert "count the" in report and "went as planned and are counted only under Outcomes" in report
    assert "recovered robot2/crashed" in " ".join(done.stdout.split())


def test_inspect_json_into_head_ends_quietly(suite: Path) -> None:
    done = subprocess.run(f"'{HEXAR}' inspect '{suite / 'bagfile_5_1'}' --json | head -2", shell=True,
                          capture_output=True, text=True, cwd=ROOT, timeout=120, check=False)
    assert done.stdout.splitlines()[0] == "{" and len(done.stdout.splitlines()) == 2
    assert "BrokenPipe" not in done.stderr and "internal error" not in done.stderr


def test_verbose_shows_every_cited_line_in_time_order_and_the_fix(suite: Path,
                                                                  capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["ask", str(suite / "bagfile_5_1"), "Why didn't you bring me the coffee?", "--llm", "none",
                 "--verbose"]) == 0
    out = capsys.readouterr().out
    assert "Goal failed" in out and "Fix: Clear the way to the kitchen" in out
    times = [line.split()[0] for line in out.splitlines() if line.startswith("  ") and line[2:4].isdigit()]
    assert len(times) >= 5 and times == sorted(times)


def test_evidence_lines_wrap_inside_their_column_at_80(suite: Path, tmp_path: Path) -> None:
    done = subprocess.run([HEXAR, "ask", str(suite / "bagfile_5_1"), "why?", "--llm", "none", "--verbose"],
                          capture_output=True, text=True, cwd=ROOT, timeout=120, check=False,
                          env={**os.environ, "COLUMNS": "80"})
    lines = done.stdout.splitlines()
    assert all(len(line) <= 80 for line in lines)
    cited = [i for i, line in enumerate(lines) if "planner_server" in line]
    assert cited
    # a long log line goes on under its own start, not under the times at the left edge
    start = lines[cited[0]].index("[planner_server]")
    follow = lines[cited[0] + 1]
    assert follow[:start].strip() == "" and follow[start:].strip()


def test_plot_says_where_it_wrote(suite: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    png = tmp_path / "fig.png"
    assert main(["ask", str(suite / "bagfile_5_1"), "why?", "--llm", "none", "--plot", str(png)]) == 0
    assert png.read_bytes()[:4] == b"\x89PNG" and f"wrote the figure of this answer to {png}" in capsys.readouterr().err
    assert main(["inspect", str(suite / "bagfile_5_1"), "--plot", str(tmp_path / "i.png")]) == 0
    assert "wrote the figure of the latest task to" in capsys.readouterr().err


def test_progress_says_what_a_wait_is_for(suite: Path, monkeypatch: pytest.MonkeyPatch,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    # asked for (a log, as a terminal gets it by itself), every step is said once it takes longer than the delay
    monkeypatch.setenv("HEXAR_PROGRESS", "1")
    monkeypatch.setenv("HEXAR_PROGRESS_AFTER", "0")
    assert main(["ask", str(suite / "bagfile_10_1"), "what happened", "--llm", "none"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert "hexar: reading bagfile_10_1…" in err and "hexar: working out the answer…" in err
    assert any(line.startswith("hexar: reading bagfile_10_1: done in ") for line in err)
    # a pipe that did not ask gets the answer alone
    monkeypatch.delenv("HEXAR_PROGRESS")
    assert main(["ask", str(suite / "bagfile_10_1"), "what happened", "--llm", "none"]) == 0
    assert "hexar:" not in capsys.readouterr().err


def test_chat_takes_typos_and_small_talk(suite: Path, tmp_path: Path) -> None:
    done = subprocess.run([HEXAR, "chat", str(suite / "bagfile_5_1"), "--llm", "none", "--checkpoints",
                           str(tmp_path / "t.sqlite")], input="wher is my cofee\nok thanks\n", capture_output=True,
                          text=True, cwd=ROOT, timeout=120, check=False)
    out = " ".join(done.stdout.split())
    assert done.returncode == 0 and "is not a question" not in out
    assert "something blocked my path" in out and "You're welcome." in out


def test_chat_ends_when_told_bye(suite: Path, tmp_path: Path) -> None:
    """"bye" (or "quit", "that's all") ends the chat as Ctrl-D does: what is typed after it is never asked."""
    for farewell in ("ok bye", "quit", "that's all, thanks"):
        done = subprocess.run([HEXAR, "chat", str(suite / "bagfile_5_1"), "--llm", "none", "--checkpoints",
                               str(tmp_path / "t.sqlite")], input=f"why did you stop?\n{farewell}\nwhat happened?\n",
                              capture_output=True, text=True, cwd=ROOT, timeout=120, check=False)
        out = " ".join(done.stdout.split())
        assert done.returncode == 0 and "something blocked my path" in out, farewell
        assert out.rstrip().endswith("Goodbye.") and "I did none" not in out and "steps of my plan" not in out, out


def _fleet(suite: Path, root: Path) -> Path:
    """Runs as a team keeps them: by robot and date, the same run name under two robots, a link to a recording,
    and a virtualenv beside them that holds a copy of a recording (a package's test data), which is no run."""
    shutil.copytree(suite / "bagfile_5_1", root / "tiago-1" / "2026-11-30" / "bagfile_5_1")
    shutil.copytree(suite / "bagfile_10_1", root / "tiago-1" / "2026-12-01" / "bagfile_10_1")
    shutil.copytree(suite / "bagfile_5_2", root / "tiago-2" / "bagfile_5_1")
    (root / "tiago-2" / "linked").symlink_to(suite / "bagfile_3_1")
    venv = root / ".venv"
    shutil.copytree(suite / "bagfile_7_1", venv / "lib" / "site-packages" / "pkg" / "data" / "bag")
    (venv / "pyvenv.cfg").write_text("home = /usr/bin\n")
    return root


def test_runs_lists_one_recording_and_nested_fleets_by_their_paths(suite: Path, tmp_path: Path,
                                                                   capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["runs", str(suite / "bagfile_5_1"), "--json"]) == 0  # a recording is a folder of one
    rows = json.loads(capsys.readouterr().out)
    assert [(r["recording"], r["outcome"]) for r in rows] == [("bagfile_5_1", "failed")]
    fleet = _fleet(suite, tmp_path / "fleet")
    assert main(["runs", str(fleet), "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["recording"] for r in rows] == ["tiago-1/2026-11-30/bagfile_5_1", "tiago-1/2026-12-01/bagfile_10_1",
                                              "tiago-2/bagfile_5_1", "tiago-2/linked"]
    assert [r["outcome"] for r in rows] == ["failed", "succeeded", "failed", "succeeded"]


def test_runs_at_80_columns_never_cuts_a_recording_name(tmp_path: Path) -> None:
    from hexar.evals.scenarios.arm import simulate_arm_suite

    simulate_arm_suite(tmp_path / "arm", "sqlite3", 0)
    done = subprocess.run([HEXAR, "runs", str(tmp_path / "arm")], capture_output=True, text=True, check=False,
                          timeout=120, env={**os.environ, "COLUMNS": "80", "TERM": "dumb"})
    assert done.returncode == 0, done.stderr
    for name in ("armfile_controllers_not_found_1", "armfile_controllers_not_found_3", "armfile_tolerance_2"):
        assert f"│ {name} " in done.stdout  # whole, so it can be copied into `hexar ask`
    assert all(len(line) <= 80 for line in done.stdout.splitlines())
    assert done.stdout.count("│ failed") == 12 and done.stdout.count("│ succeeded") == 3


def test_ask_runs_over_a_fleet_names_each_answer_by_its_path(suite: Path, tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    fleet = _fleet(suite, tmp_path / "fleet")
    assert main(["ask", "--runs", str(fleet), "what happened", "--llm", "none"]) == 0
    answers = dict(line.split(": ", 1) for line in capsys.readouterr().out.splitlines())
    assert list(answers) == ["tiago-1/2026-11-30/bagfile_5_1", "tiago-1/2026-12-01/bagfile_10_1",
                             "tiago-2/bagfile_5_1", "tiago-2/linked"]
    assert "something blocked my path" in answers["tiago-2/bagfile_5_1"]
    assert answers["tiago-1/2026-12-01/bagfile_10_1"].startswith("I did all 4 steps of my plan")


def test_ask_takes_the_metadata_file_of_a_recording(suite: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["ask", str(suite / "bagfile_5_1" / "metadata.yaml"), "what happened", "--llm", "none"]) == 0
    assert "something blocked my path" in " ".join(capsys.readouterr().out.split())
