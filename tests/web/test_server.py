"""The page's HTTP API as the page uses it: runs, one run, lines, figure, chat; errors as the CLI's one line."""

from __future__ import annotations

import json
import shutil
import time
import urllib.error
import urllib.parse
import urllib.request
from pathlib import Path
from typing import Any

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.cli import main
from hexar.events import contract as c
from hexar.events import read_recording
from tests.web.browser import served


def get(url: str) -> tuple[int, Any]:
    try:
        with urllib.request.urlopen(url, timeout=60) as r:
            body = r.read()
            return r.status, json.loads(body) if r.headers["Content-Type"] == "application/json" else body
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read())


def post(url: str, data: dict[str, Any]) -> tuple[int, Any]:
    req = urllib.request.Request(url, json.dumps(data).encode(), {"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=120) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read())


def test_runs_list_outcomes_and_causes(webroot: Path, tmp_path: Path) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        deadline = time.monotonic() + 120
        while True:
            status, data = get(url + "api/runs")
            assert status == 200
            if data["pending"] == 0 or time.monotonic() > deadline:
                break
            time.sleep(0.5)
    rows = {r["recording"]: r for r in data["runs"]}
    assert data["pending"] == 0
    assert rows["bagfile_5_1"]["latest"]["outcome"] == "failed"
    assert rows["bagfile_5_1"]["causes"] == ["navigation.blocked_path"]
    # the trip to the kitchen succeeded before asking for help failed: navigation tells that trip, in its own window
    assert rows["bagfile_12_1"]["causes"] == ["ask_human.person_too_far", "navigation.nominal"]
    # a message too long for its time limit after a clean trip: no transform error from amcl's routine drops
    assert rows["bagfile_19_1"]["causes"] == ["navigation.nominal", "tts.timeout"]
    assert rows["bagfile_10_1"]["latest"]["outcome"] == "succeeded"
    modules = rows["bagfile_5_1"]["modules"]
    assert {"navigation", "text_to_speech"} <= set(modules) and "navigate_to_zone" not in modules  # not skills
    assert rows["corrupt_run"]["error"].startswith("cannot read")


def test_one_run_shows_what_the_explainers_used(webroot: Path, tmp_path: Path) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        _, ask = get(url + "api/run?name=bagfile_12_1")
        _, tts = get(url + "api/run?name=bagfile_19_1")
        _, pizza = get(url + "api/run?name=bagfile_20_1")
        _, nav = get(url + "api/run?name=bagfile_5_1")
        _, lines = get(url + "api/lines?name=bagfile_5_1")
        status, png = get(url + "api/plot.png?name=bagfile_5_1")
    # ask-human steps with their recorded distance
    log = read_recording(webroot / "bagfile_12_1")
    recorded = {v for r in log.statuses[c.EPISODIC_MEMORY] for k, v in r.data_items() if k == "person_distance"}
    shown = {v for r in ask["ask_human"] for k, v in r["values"] if k == "person_distance"}
    assert shown and shown <= recorded
    # the failure check's explainer first, then what every other started module found
    assert ask["findings"][0]["causes"] == ["ask_human.person_too_far"]
    assert {f["explainer"] for f in ask["findings"][1:]} <= {"navigation"}
    # the TTS utterance and what was said before the cut
    said = next(v for r in tts["tts"] for k, v in r["values"] if k == "text_said")
    text = next(v for r in tts["tts"] for k, v in r["values"] if k == "text")
    assert text.startswith(said) and len(said) < len(text)
    # LIME's weights, strongest first, the recommended pizza's top ingredient among them
    weights = pizza["pizza"]["weights"]
    assert pizza["pizza"]["recommended"] == "Margherita" and len(weights) >= 3
    assert abs(weights[0]["weight"]) == max(abs(w["weight"]) for w in weights)
    assert weights[0]["ingredient"] in pizza["pizza"]["text"].lower()
    # the navigation failure: the failed skill, its evidence rows, the path's stop, the filtered lines
    assert nav["spans"][0]["status"] == "failed" and nav["spans"][0]["error_msg"]
    assert any("Failed to make progress" in e["item"] for e in nav["events"])
    assert nav["path"]["stop_label"].startswith("stopped here") and nav["path"]["poses"] > 10
    assert {e["key"] for e in nav["events"] if e["topic"] == c.ROSOUT} <= {ln["key"] for ln in lines["lines"]}
    assert lines["kept"] <= lines["total"]
    assert status == 200 and png[:8] == b"\x89PNG\r\n\x1a\n"


def test_chat_thread_moves_between_page_and_terminal(webroot: Path, tmp_path: Path) -> None:
    ck = tmp_path / "threads.sqlite"
    with served(webroot, ck) as url:
        _, first = post(url + "api/chat", {"name": "bagfile_5_1", "question": "why?"})
        assert first["causes"] == ["navigation.blocked_path"] and first["backend"] == "none"
        assert all(ev["key"] == f"{ev['topic']}|{ev['t']}" for ev in first["evidence"])
        _, deeper = post(url + "api/chat", {"name": "bagfile_5_1", "question": "why?", "thread": first["thread"]})
        assert deeper["intent"] == "deeper" and deeper["thread"] == first["thread"]
        _, bad = post(url + "api/chat", {"name": "bagfile_5_1", "question": "", "thread": first["thread"]})
        assert bad["error"] and not bad["answer"].startswith("Traceback")
        # small talk is no question (error set, as `hexar ask` refuses it) with a reply the page shows instead
        _, hello = post(url + "api/chat", {"name": "bagfile_5_1", "question": "hi robot", "thread": first["thread"]})
        assert hello["intent"] == "smalltalk" and "is not a question" in hello["error"]
        assert hello["answer"].startswith("Hello! Ask me why I did something") and hello["explainers"] == []
    # `hexar chat` with the same recording path and conversation file sees the page's turns
    session = Session(RunSettings(recording=webroot / "bagfile_5_1", llm="none"), checkpoints=ck)
    turns = session.history(first["thread"])
    assert [t["answer"] for t in turns][:2] == [first["answer"], deeper["answer"]]
    follow = session.ask("What would have helped?", thread=first["thread"])
    assert follow["intent"] == "helped"


@pytest.mark.parametrize(("query", "message"), [
    ("api/run?name=corrupt_run", "ERROR: cannot read"),
    ("api/run?name=../bagfile_5_1", "ERROR: no recording named"),
    ("api/run?name=bagfile_5_1&task=nope", "ERROR: no task 'nope'"),
    ("api/lines?name=nothing", "ERROR: no recording named"),
    ("api/plot.png?name=hostile_run&task=9", "ERROR: no task '9'"),
    ("nowhere", "ERROR: no such page"),
])
def test_bad_requests_are_the_clis_one_line(webroot: Path, tmp_path: Path, query: str, message: str) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        status, data = get(url + query)
    assert status in {400, 404} and data["error"].startswith(message)
    assert "\n" not in data["error"] and "Traceback" not in data["error"]


def test_corrupt_recording_error_matches_the_cli(webroot: Path, tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        _, data = get(url + "api/run?name=corrupt_run")
    assert main(["inspect", str(webroot / "corrupt_run")]) == 2
    # the CLI's line, with the served folder named as the page shows it instead of where it lies on this machine
    shown = f"{webroot.parent.name}/{webroot.name}"
    assert capsys.readouterr().err.strip().replace(str(webroot), shown) == data["error"]
    assert str(webroot.parent) not in data["error"]


def test_static_page_has_no_inline_script_and_a_strict_policy(webroot: Path, tmp_path: Path) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url, urllib.request.urlopen(url) as r:
        html = r.read().decode()
        policy = r.headers["Content-Security-Policy"]
    assert "script-src 'self'" in policy and "<script type=\"module\" src=\"/static/app.js\">" in html
    assert "<script>" not in html


def test_every_module_of_the_page_is_served_as_javascript(webroot: Path, tmp_path: Path) -> None:
    """app.js and every module it imports, transitively: a browser runs a module only with a JavaScript type."""
    import re

    seen: set[str] = set()
    todo = ["app.js"]
    with served(webroot, tmp_path / "t.sqlite") as url:
        while todo:
            name = todo.pop()
            seen.add(name)
            with urllib.request.urlopen(f"{url}static/{name}") as r:
                assert r.headers["Content-Type"].startswith("text/javascript")
                text = r.read().decode()
            assert ".innerHTML" not in text and "insertAdjacentHTML" not in text  # recorded text stays text
            todo += [m for m in re.findall(r'^import .* from "\./([\w-]+\.js)";$', text, re.M) if m not in seen]
    assert {"app.js", "common.js", "runs.js", "run.js", "timeline.js", "path.js", "chat.js"} <= seen


@pytest.mark.parametrize(("args", "message"), [
    (["web", "/definitely/not/here", "--llm", "none"], "not a folder"),
    (["web", ".", "--llm", "nonsense"], "unknown LLM backend"),
    (["web", ".", "--llm", "none", "--port", "70000"], "--port must be a port number from 0 to 65535"),  # was an
    (["web", ".", "--llm", "none", "--port", "-1"], "--port must be a port number"),  # internal OverflowError
    (["mcp", ".", "--http", "--port", "0"], "--port must be a port number from 1 to 65535"),
])
def test_web_command_bad_input(args: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR:") and message in err and err.count("\n") == 1


def test_port_in_use_is_one_line(webroot: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        port = url.rsplit(":", 1)[1].strip("/")
        assert main(["web", str(webroot), "--port", port, "--llm", "none"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR: cannot listen on 127.0.0.1:") and err.count("\n") == 1


def test_hexar_web_serves_on_loopback(webroot: Path, tmp_path: Path) -> None:
    """The command as a person starts it: it says where it listens, on loopback, and serves the runs."""
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-m", "hexar", "web", str(webroot), "--port", "0", "--llm", "none",
                             "--checkpoints", str(tmp_path / "t.sqlite")], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert line.startswith("HEXAR web: http://127.0.0.1:")
        url = line.split()[2]
        status, data = get(url + "api/runs")
        assert status == 200 and any(r["recording"] == "bagfile_5_1" for r in data["runs"])
        with urllib.request.urlopen(url) as r:
            assert b"/static/app.js" in r.read()
    finally:
        proc.terminate()
        proc.wait(timeout=30)


def test_a_recording_without_task_info_is_listed_with_its_nav2_goal(tmp_path: Path) -> None:
    from hexar.evals.scenarios.bag import BagBuilder, sec_ns
    from hexar.events.records import ERROR, INFO, WARN

    # real Nav2 Humble lines (shared reference nav2_log_messages.md), no /task_info
    b = BagBuilder()
    t0 = 1_700_000_000_000_000_000
    b.log(t0, "bt_navigator", INFO, "Begin navigating from current location (0.00, 0.00) to (4.00, 1.00)")
    b.log(t0 + sec_ns(2), "planner_server", WARN, "GridBased: failed to create plan with tolerance 0.50.")
    b.log(t0 + sec_ns(3), "bt_navigator", ERROR, "Goal failed")
    root = tmp_path / "runs"
    b.write(root / "nav2_only")
    with served(root, tmp_path / "t.sqlite") as url:
        deadline = time.monotonic() + 60
        while True:
            _, data = get(url + "api/runs")
            if data["pending"] == 0 or time.monotonic() > deadline:
                break
            time.sleep(0.3)
    row = data["runs"][0]
    assert row["tasks"] == 1 and row["latest"]["outcome"] == "failed" and row["modules"] == ["navigation"]
    # a planner that found no path is a symptom, never told as the cause (issue 20): the honest finding
    assert row["causes"] == ["navigation.unexplained_failure"]


def test_a_fleet_by_robot_and_date_and_a_single_recording_are_served_by_their_paths(suite: Path,
                                                                                     tmp_path: Path) -> None:
    fleet = tmp_path / "fleet"
    shutil.copytree(suite / "bagfile_5_1", fleet / "tiago-1" / "2026-11-30" / "bagfile_5_1")
    shutil.copytree(suite / "bagfile_10_1", fleet / "tiago-2" / "bagfile_5_1")  # the same name, another robot
    (fleet / "tiago-2" / "linked").symlink_to(suite / "bagfile_3_1")  # leads out of the served folder
    with served(fleet, tmp_path / "t.sqlite") as url:
        status, data = get(url + "api/runs")
        assert status == 200
        rows = {r["recording"]: r for r in data["runs"]}
        assert list(rows) == ["tiago-1/2026-11-30/bagfile_5_1", "tiago-2/bagfile_5_1", "tiago-2/linked"]
        assert rows["tiago-2/bagfile_5_1"]["latest"]["outcome"] == "succeeded"
        assert "outside the served folder" in rows["tiago-2/linked"]["error"]
        status, run = get(url + "api/run?name=" + urllib.parse.quote("tiago-1/2026-11-30/bagfile_5_1", safe=""))
        assert status == 200 and run["task"]["outcome"] == "failed"
        assert ["navigation.blocked_path"] in [f["causes"] for f in run["findings"]]
        status, err = get(url + "api/run?name=bagfile_5_1")  # only its path names it
        assert status == 400 and "no recording named 'bagfile_5_1'" in err["error"]
    with served(suite / "bagfile_5_1", tmp_path / "t2.sqlite") as url:
        status, data = get(url + "api/runs")
        assert [r["recording"] for r in data["runs"]] == ["bagfile_5_1"]
        status, run = get(url + "api/run?name=bagfile_5_1")
        assert status == 200 and run["task"]["outcome"] == "failed"


def test_a_run_recorded_or_removed_while_serving_is_seen_at_once(suite: Path, tmp_path: Path) -> None:
    """The page looks a run's name up in its last walk of the folder; a run recorded since is found without
    waiting, and a run removed since is the same one-line refusal as any unknown name."""
    from hexar.web.errors import WebError
    from hexar.web.store import Store

    root = tmp_path / "fleet"
    shutil.copytree(suite / "bagfile_5_1", root / "robot1" / "run_a")
    store = Store(root, "none", tmp_path / "t.sqlite")
    assert store.log("robot1/run_a").task().outcome == "failed"
    shutil.copytree(suite / "bagfile_10_1", root / "robot2" / "run_b")
    assert store.path("robot2/run_b") == root / "robot2" / "run_b"
    assert store.log("robot2/run_b").task().outcome == "succeeded"
    shutil.rmtree(root / "robot1")
    with pytest.raises(WebError, match=r"^no recording named 'robot1/run_a' in "):
        store.path("robot1/run_a")
