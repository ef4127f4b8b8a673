"""`hexar serve` and `hexar replay` as a user runs them: two processes over DDS, and one-line errors for bad
input."""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from hexar.cli import main
from tests.live.dds_helpers import Listener, fresh_domain, replay


def test_serve_and_replay_processes(suite: Path) -> None:
    domain = fresh_domain()
    serve = subprocess.Popen([sys.executable, "-m", "hexar", "serve", "--transport", "dds", "--domain", str(domain),
                              "--duration", "120"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    listener = Listener(domain)
    try:
        assert serve.stderr is not None
        line = serve.stderr.readline()  # printed once the node listens
        assert "listening over dds" in line and "writes only /hexar/answer" in line
        assert "replayed" in replay(suite / "bagfile_7_1", domain, rate=20.0)
        failure = listener.wait_answers(1, "failure")
        listener.ask("Why didn't you bring me the coffee?")
        question = listener.wait_answers(1, "question", timeout=15)
        time.sleep(0.2)
    finally:
        listener.close()
        serve.send_signal(signal.SIGTERM)
        out, err = serve.communicate(timeout=30)
    assert failure[0]["causes"] == ["navigation.charging"]
    assert question[0]["causes"] == ["navigation.charging"]
    printed = [json.loads(x) for x in out.splitlines()]
    assert [p["trigger"] for p in printed] == ["failure", "question"]
    assert serve.returncode == 0 and "Traceback" not in err


@pytest.mark.parametrize(("argv", "message"), [
    (["serve", "--transport", "rclpy"], "needs a ROS 2 install"),
    (["serve", "--transport", "zenoh"], "unknown transport"),
    (["serve", "--transport", "dds", "--domain", "500"], "out of range"),
    (["serve", "--proactive", "loud"], "unknown --proactive"),
    (["serve", "--voice", "robot", "--transport", "dds", "--domain", "230"], "--voice robot needs"),
    (["serve", "--transport", "dds", "--tts-topic", "tts"], "absolute ROS topic"),
    (["serve", "--mic", "--wav", "q.wav"], "not both"),
    (["replay", "no/such/recording"], "recording not found"),
    (["replay", "RUN", "--rate", "0"], "--rate must be above 0"),
    (["replay", "RUN", "--start", "-1"], "--start must not be negative"),
])
def test_bad_input_is_one_line(argv: list[str], message: str, suite: Path, capsys: pytest.CaptureFixture[str],
                               monkeypatch: pytest.MonkeyPatch) -> None:
    if "rclpy" in argv:
        monkeypatch.setitem(sys.modules, "rclpy", None)  # as on any machine without ROS 2
    argv = [str(suite / "bagfile_7_1") if a == "RUN" else a for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("ERROR: ") and message in err and "\n" not in err and "Traceback" not in err


def test_bad_ros_domain_id(suite: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_DOMAIN_ID", "robot")
    assert main(["replay", str(suite / "bagfile_7_1"), "--transport", "dds"]) == 2
    assert capsys.readouterr().err.strip() == "ERROR: ROS_DOMAIN_ID='robot' is not a number"


def test_not_a_recording(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["replay", str(tmp_path), "--transport", "dds"]) == 2
    assert "has no metadata.yaml" in capsys.readouterr().err


def test_chat_live_talks_with_the_running_node(suite: Path) -> None:
    from hexar.live.chat_live import chat_live
    from tests.live.dds_helpers import live_node

    domain = fresh_domain()
    shown: list[dict[str, object]] = []
    with live_node(domain):
        replay(suite / "bagfile_19_1", domain, rate=40.0)
        time.sleep(1.0)
        assert chat_live(domain, ["Why didn't you tell Maria?", "why?"], shown.append) == 0
    answers = [a for a in shown if a["trigger"] == "question"]
    assert answers[0]["causes"] == ["tts.timeout"]
    assert answers[1]["route"] == "followup" and answers[1]["thread"] == answers[0]["thread"]


def test_chat_live_without_a_node_says_so(capsys: pytest.CaptureFixture[str]) -> None:
    from hexar.live.chat_live import chat_live
    from hexar.live.errors import LiveError

    with pytest.raises(LiveError, match="no answer from hexar serve"):
        chat_live(fresh_domain(), ["why?"], print, timeout=1.0)
    assert main(["chat"]) == 2
    assert "give a recording, or --live" in capsys.readouterr().err
