"""`hexar web --live`: the robot's run on the page from real DDS traffic on loopback, updated as tasks arrive,
the chat answering from the newest data, the page writing nothing on the robot's network, and bad options as
one-line errors."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from hexar.cli import main
from tests.live.conftest import NO_RCLPY, TRANSPORTS
from tests.live.dds_helpers import NO_DDS, fresh_domain
from tests.live.dds_helpers import other as other_vendor
from tests.web.live_robot import NAV, Robot, live_page
from tests.web.test_server import get, post

BLOCKED = "navigation.blocked_path"


def wait_for(fetch: Callable[[], Any], ok: Callable[[Any], bool], timeout: float = 10.0) -> Any:
    deadline = time.monotonic() + timeout
    while True:
        got = fetch()
        if ok(got) or time.monotonic() > deadline:
            return got
        time.sleep(0.1)


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_live_run_shows_the_failed_task_then_the_next(tmp_path: Path, transport: str) -> None:
    """The page on either transport, the robot on the other vendor's where both exist."""
    domain = fresh_domain()
    robot = Robot(domain, other_vendor(transport))
    try:
        with live_page(domain, tmp_path / "t.sqlite", transport=transport) as (url, store):
            _, runs = get(url + "api/runs")
            assert [(r["recording"], r.get("live")) for r in runs["runs"]] == [("live", True)]
            _, empty = get(url + "api/run?name=live")  # no task yet: the CLI's line, not an error
            assert empty["no_task"].startswith("no task to explain:") and empty["live"]
            status, other = get(url + "api/run?name=bagfile_5_1")  # no folder given: nothing else can be named
            assert status == 400 and other["error"] == "ERROR: no recording named 'bagfile_5_1' here: only the live " \
                "robot is shown"

            robot.blocked_trip("nav1", "Bring me a coffee from the kitchen")
            robot.heard_by(store)
            status, run = wait_for(lambda: get(url + "api/run?name=live"),
                                   lambda r: r[1].get("task", {}).get("outcome") == "failed")
            assert status == 200 and run["task"]["task_id"] == "nav1"
            failed = [s for s in run["spans"] if s["status"] == "failed"]
            assert [(s["skill"], s["error_msg"]) for s in failed] == [(NAV, "Navigation to kitchen failed")]
            # the failure first; the planner's finding on this one-step plan for a fetch follows it
            assert run["findings"][0]["causes"] == [BLOCKED], run["findings"]
            assert any("Failed to make progress" in e["item"] for e in run["events"])
            assert run["path"]["poses"] >= 10 and run["path"]["stop_label"].startswith("stopped here")
            _, runs = get(url + "api/runs")
            row = runs["runs"][0]
            assert row["latest"]["outcome"] == "failed" and BLOCKED in row["causes"]

            # the page's poll: the same version is answered "unchanged", without the run
            _, same = get(url + f"api/run?name=live&since={run['version']}")
            assert same == {**same, "unchanged": True, "version": run["version"]} and "spans" not in same
            # the robot idles after the failure: new poses and lines change the snapshot, not the failed task's view
            before = store.live.snapshot().version
            robot.pose(-0.2, 1.0)
            robot.log("amcl", 20, "initialPoseReceived")
            wait_for(lambda: store.live.snapshot().version, lambda v: v != before)
            _, idle = get(url + f"api/run?name=live&since={run['version']}")
            assert idle.get("unchanged") is True
            _, lines = get(url + "api/lines?name=live")
            assert any("Goal failed" in ln["item"] for ln in lines["lines"])
            status, png = get(url + "api/plot.png?name=live")
            assert status == 200 and png[:8] == b"\x89PNG\r\n\x1a\n"

            robot.blocked_trip("nav2", "Go to the kitchen again")
            robot.heard_by(store)
            _, later = wait_for(lambda: get(url + f"api/run?name=live&since={run['version']}"),
                                lambda r: r[1].get("task", {}).get("outcome") == "failed"
                                and r[1]["task"]["task_id"] == "nav2")
            assert later["version"] != run["version"]
            assert [t["task_id"] for t in later["tasks"]] == ["nav1", "nav2"]
            _, first = get(url + "api/run?name=live&task=nav1")  # the earlier task stays selectable
            assert first["task"]["task_id"] == "nav1" and first["task"]["outcome"] == "failed"
    finally:
        robot.close()


def test_live_chat_answers_why_from_the_newest_data(tmp_path: Path) -> None:
    domain = fresh_domain()
    robot = Robot(domain)
    try:
        with live_page(domain, tmp_path / "t.sqlite") as (url, store):
            # before any task: a spoken answer, as `hexar serve` gives it; the developer's reason kept apart
            status, early = post(url + "api/chat", {"name": "live", "question": "why?"})
            assert status == 200 and early["no_task"] is True and early["evidence"] == []
            assert early["answer"].startswith("I haven't had a task since I started listening")
            assert early["error"].startswith("no task to explain")
            robot.blocked_trip("nav1", "Bring me a coffee from the kitchen")
            robot.heard_by(store)  # the chat reads a fresh snapshot: no page poll is needed before asking
            status, answer = post(url + "api/chat", {"name": "live", "question": "why?"})
            assert status == 200 and answer["causes"] == [BLOCKED] and answer["task_id"] == "nav1"
            assert "blocked" in answer["answer"]
            assert answer["evidence"] and all("key" in ev for ev in answer["evidence"])
            _, history = get(url + f"api/history?name=live&thread={answer['thread']}")
            assert [h["question"] for h in history["history"]] == ["why?"]
    finally:
        robot.close()


def test_live_chat_while_the_robot_drives_says_where_it_is(tmp_path: Path) -> None:
    """Asked while the trip is still going on, the page's chat answers as `hexar serve` does: the step the robot
    is at, not "the recording does not show whether I reached the goal"."""
    domain = fresh_domain()
    robot = Robot(domain)
    try:
        with live_page(domain, tmp_path / "t.sqlite") as (url, store):
            robot.task("nav1", "Go to the kitchen", "waiting")
            robot.task("nav1", "Go to the kitchen", "Running")
            robot.log("skill_navigate_to_zone", 20, "Navigating to kitchen at (4.20, 2.10)")
            for i in range(5):
                robot.pose(-1.8 + 0.2 * i, 0.6 + 0.05 * i)
            robot.heard_by(store)
            status, answer = post(url + "api/chat", {"name": "live", "question": "Why did you stop?"})
    finally:
        robot.close()
    assert status == 200 and answer["causes"] == [] and answer["task_id"] == "nav1"
    assert answer["answer"].startswith('I\'m still working on your request "Go to the kitchen": I\'m at step 1 (to go '
                                       "to the kitchen), for 1 s so far.")
    assert "recording" not in answer["answer"]


def test_live_chat_tells_a_robot_it_no_longer_hears(tmp_path: Path) -> None:
    """The robot's participant ends in the middle of a trip: the page's chat says when it last heard the robot
    and where it was then, as `hexar serve` does, rather than "I'm still working on it"."""
    domain = fresh_domain()
    robot = Robot(domain)
    with live_page(domain, tmp_path / "t.sqlite") as (url, store):
        try:
            robot.task("nav1", "Go to the kitchen", "waiting")
            robot.task("nav1", "Go to the kitchen", "Running")
            for i in range(5):
                robot.pose(-1.8 + 0.2 * i, 0.6 + 0.05 * i)
            robot.heard_by(store)
        finally:
            robot.close()
        wait_for(lambda: store.live.log.contact.stats(), lambda s: s["not_back"] == 1)
        status, answer = post(url + "api/chat", {"name": "live", "question": "Why did you stop?"})
    assert status == 200 and answer["task_id"] == "nav1" and "running" not in answer
    assert answer["answer"].startswith("I have not heard from the robot since ")
    assert "The last I heard, I was still at step 1 (to go to the kitchen)." in answer["answer"]
    assert answer["contact"][0]["heard_again"] is None


@NO_DDS
def test_the_live_page_writes_nothing_on_the_robots_network(tmp_path: Path) -> None:
    from cyclonedds.builtin import BuiltinDataReader, BuiltinTopicDcpsPublication, BuiltinTopicDcpsSubscription

    from hexar.live.dds import DdsEndpoint

    domain = fresh_domain()
    with live_page(domain, tmp_path / "t.sqlite") as (_, store):
        spy = DdsEndpoint(domain)
        writers = BuiltinDataReader(spy.participant, BuiltinTopicDcpsPublication)
        readers = BuiltinDataReader(spy.participant, BuiltinTopicDcpsSubscription)
        guid = store.live.watcher.endpoint.participant.guid
        time.sleep(1.0)
        wrote = {s.topic_name for s in writers.take(1000) if s.participant_key == guid}
        read = {s.topic_name for s in readers.take(1000) if s.participant_key == guid}
        spy.close()
        assert store.live.watcher.writer_topics() == []
    assert wrote == set()
    assert {"rt/task_info", "rt/rosout", "rt/amcl_pose"} <= read and "rt/hexar/question" not in read


@NO_RCLPY
def test_the_live_page_over_rclpy_writes_no_topic_of_the_robot_or_hexar(tmp_path: Path) -> None:
    """Over rclpy the page is a ROS node, `hexar_web`, as `ros2 node info` shows it from another node: it reads the
    robot's topics and writes only the /parameter_events every rclpy node has (no /rosout, no /hexar/*)."""
    from hexar.live.ros import RosNode

    domain = fresh_domain()
    with live_page(domain, tmp_path / "t.sqlite", transport="rclpy") as (_, store):
        spy = RosNode("hexar_test_spy", domain)
        try:
            deadline = time.monotonic() + 10
            while "hexar_web" not in spy.node.get_node_names() and time.monotonic() < deadline:
                time.sleep(0.1)
            # the node's name comes first; its endpoints as discovery reaches them
            read: set[str] = set()
            while not {"/task_info", "/rosout", "/amcl_pose"} <= read and time.monotonic() < deadline:
                time.sleep(0.1)
                read = {t for t, _ in spy.node.get_subscriber_names_and_types_by_node("hexar_web", "/")}
            wrote = {t for t, _ in spy.node.get_publisher_names_and_types_by_node("hexar_web", "/")}
        finally:
            spy.close()
        assert store.live.watcher.writer_topics() == []
    assert wrote == {"/parameter_events"}
    assert {"/task_info", "/rosout", "/amcl_pose"} <= read and "/hexar/question" not in read


def test_hexar_web_live_command(tmp_path: Path) -> None:
    """The command as a person runs it, without a folder: the page lists only the robot, fed over DDS."""
    import signal
    import subprocess

    domain = fresh_domain()
    robot = Robot(domain)
    cmd = [sys.executable, "-m", "hexar", "web", "--live", "--domain", str(domain), "--port", "0", "--llm", "none",
           "--checkpoints", str(tmp_path / "t.sqlite")]
    # a test run started in the background ignores SIGINT, and a child would inherit that (as in fleet's test)
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert f"the live robot on DDS domain {domain}" in line and "recordings" not in line
        url = line.split()[2]
        robot.blocked_trip("nav1", "Bring me a coffee from the kitchen")
        # DDS orders samples per topic, not across them: the page catches up once the failing update arrived, and
        # its cause once the log lines that show it arrived too (on a loaded machine they can come after the update;
        # each new snapshot is explained again)
        _, runs = wait_for(lambda: get(url + "api/runs"),
                           lambda r: (r[1]["runs"][0]["latest"] or {}).get("outcome") == "failed" and
                           BLOCKED in (r[1]["runs"][0]["causes"] or []), timeout=30)
        assert [(r["recording"], r["latest"]["outcome"]) for r in runs["runs"]] == [("live", "failed")]
        assert BLOCKED in runs["runs"][0]["causes"], runs["runs"][0]["causes"]
    finally:
        robot.close()
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
    assert proc.returncode == 0 and "Traceback" not in err


@pytest.mark.parametrize(("argv", "env", "message"), [
    (["web", "--live", "--domain", "500"], {}, "out of range"),
    (["web", "--live"], {"ROS_DOMAIN_ID": "robot"}, "ROS_DOMAIN_ID='robot' is not a number"),
    (["web", "--domain", "3"], {}, "--domain needs --live"),
    (["web", "--launch-log", "logs"], {}, "--launch-log needs --live"),
    (["web", "--transport", "rclpy"], {}, "--transport needs --live"),
    (["web", "--live", "--transport", "zenoh"], {}, "unknown transport 'zenoh'"),
    (["web", "no/such/folder", "--live", "--domain", "231"], {}, "not a folder"),
])
def test_bad_live_options_are_one_line(argv: list[str], env: dict[str, str], message: str,
                                       capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    for key, value in env.items():
        monkeypatch.setenv(key, value)
    assert main([*argv, "--llm", "none"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("ERROR: ") and message in err and "\n" not in err


def test_a_recording_named_live_is_refused_with_live(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    (tmp_path / "live").mkdir()
    (tmp_path / "live" / "metadata.yaml").write_text("rosbag2_bagfile_information: {}\n")
    assert main(["web", str(tmp_path), "--live", "--domain", str(fresh_domain()), "--llm", "none"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("ERROR: ") and "named 'live'" in err and "\n" not in err


def _without_cyclonedds(monkeypatch: pytest.MonkeyPatch) -> None:
    for name in [m for m in sys.modules if m.startswith("cyclonedds") or m in {"hexar.live.dds", "hexar.live.msgs"}]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "cyclonedds", None)  # as where the binding is not installed (CPython 3.14)


def test_live_over_dds_without_cyclonedds_is_one_line(capsys: pytest.CaptureFixture[str],
                                                      monkeypatch: pytest.MonkeyPatch) -> None:
    _without_cyclonedds(monkeypatch)
    assert main(["web", "--live", "--transport", "dds", "--llm", "none"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("ERROR: the DDS transport needs the cyclonedds binding") and "\n" not in err
    assert ("pip install 'hexar[live]'" in err) == (sys.version_info < (3, 14))
    assert ("use --transport rclpy" in err) == (sys.version_info >= (3, 14))


@NO_RCLPY
def test_live_without_cyclonedds_reads_the_robot_over_rclpy(monkeypatch: pytest.MonkeyPatch) -> None:
    from hexar.web.live import RclpyWatcher
    from hexar.web.server import live_source

    _without_cyclonedds(monkeypatch)
    source = live_source(True, fresh_domain())
    assert source is not None
    try:
        assert isinstance(source.watcher, RclpyWatcher) and source.watcher.writer_topics() == []
    finally:
        source.close()


def test_the_open_live_page_follows_the_robot(tmp_path: Path) -> None:
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    from tests.web.browser import chrome

    domain = fresh_domain()
    robot = Robot(domain)
    try:
        with live_page(domain, tmp_path / "t.sqlite") as (url, store), chrome() as driver:
            ready = "return document.body.dataset.ready"
            driver.get(f"{url}#/")
            WebDriverWait(driver, 30).until(lambda d: d.find_elements(By.CSS_SELECTOR, "tr.run[data-name='live']"))
            row = driver.find_element(By.CSS_SELECTOR, "tr.run[data-name='live']")
            assert row.find_element(By.CSS_SELECTOR, ".badge.live").text == "live" and "no task yet" in row.text
            row.click()
            WebDriverWait(driver, 30).until(lambda d: d.execute_script(ready) == "none")
            assert driver.find_element(By.ID, "no-task").text.startswith("no task to explain:")
            assert not driver.find_elements(By.CSS_SELECTOR, "p.error")
            driver.execute_script("window.notReloaded = true")

            robot.blocked_trip("nav1", "Bring me a coffee from the kitchen")
            robot.heard_by(store)
            # every record heard is in the snapshot the page draws: a snapshot rebuilt at most every REBUILD_S could
            # otherwise lag a record behind, and the chat's fresh one below would redraw the page (seen under load)
            store.live.snapshot(fresh=True)
            _, final = wait_for(lambda: get(url + "api/run?name=live"),
                                lambda r: r[1].get("task", {}).get("outcome") == "failed")
            WebDriverWait(driver, 15).until(lambda d: d.execute_script("return document.body.dataset.version")
                                            == final["version"])  # the page redrew by itself, to the end
            assert driver.execute_script(ready) == "nav1"
            assert driver.find_element(By.ID, "skill-0").get_attribute("data-status") == "failed"
            driver.find_element(By.ID, "chat-input").send_keys("why?\n")
            WebDriverWait(driver, 30).until(lambda d: d.find_elements(By.CSS_SELECTOR, ".msg.bot:not(.pending)"))
            answer = driver.find_element(By.CSS_SELECTOR, ".msg.bot:not(.pending)")
            assert [c.text for c in answer.find_elements(By.CSS_SELECTOR, ".chip")] == [BLOCKED]
            driver.find_element(By.ID, "chat-input").send_keys("and then")  # typed, not sent yet
            # an unchanged run is not redrawn by the next poll
            driver.execute_script("window.shownTimeline = document.getElementById('timeline')")
            heard = store.live.log.snapshot().topics
            time.sleep(2.5)
            # what was heard meanwhile, should the page have redrawn: the topics' counts before and after
            after = store.live.log.snapshot().topics
            assert driver.execute_script("return window.shownTimeline.isConnected"), (
                {t: i.count for t, i in heard.items()}, {t: i.count for t, i in after.items()})

            robot.blocked_trip("nav2", "Go to the kitchen again")
            WebDriverWait(driver, 15).until(lambda d: d.execute_script(ready) == "nav2")
            assert driver.execute_script("return window.notReloaded === true")
            tabs = [t.text for t in driver.find_elements(By.CSS_SELECTOR, ".tabs .tab")]
            assert len(tabs) == 2 and "Go to the kitchen again" in tabs[1]
            assert "Go to the kitchen again" in driver.find_element(By.CSS_SELECTOR, ".instruction").text
            # the chat is kept as it was: the answer, and what was being typed
            assert driver.find_elements(By.CSS_SELECTOR, ".msg.bot .chip")[0].text == BLOCKED
            assert driver.find_element(By.ID, "chat-input").get_attribute("value") == "and then"
    finally:
        robot.close()


@pytest.mark.parametrize("told", [False, True])
def test_the_live_page_reads_launchs_log_of_this_computer(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                           told: bool) -> None:
    """From where launch writes (ROS_LOG_DIR), or from the folder --launch-log names."""
    from tests.live.test_launch_log import _launch, _now_lines

    _launch(tmp_path / "ros_log", "2026-11-29-07-00-00-000000-robot-1", _now_lines())
    if not told:
        monkeypatch.setenv("ROS_LOG_DIR", str(tmp_path / "ros_log"))
    with live_page(fresh_domain(), tmp_path / "t.sqlite", launch_log=tmp_path / "ros_log" if told else None) as (
            url, _):
        status, run = wait_for(lambda: get(url + "api/run?name=live"),
                               lambda r: r[1].get("task", {}).get("outcome") == "failed")
    assert status == 200 and run["findings"][0]["causes"] == ["bringup.process_died"]
    assert "min() arg is an empty sequence" in run["findings"][0]["text"]
