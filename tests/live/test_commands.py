"""`hexar serve` and `hexar replay` as a user runs them: two processes, on each transport, each ended by a signal
(exit 0, nothing left in /dev/shm, no abort); `hexar serve` on rclpy is the ROS 2 node `hexar`; one-line errors
for bad input."""

from __future__ import annotations

import importlib.util
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from hexar.cli import main
from tests.live.dds_helpers import DEFAULT, Listener, fresh_domain, other, replay, replay_process

SHM = Path("/dev/shm")


OWN_SEGMENT = re.compile(r"fastdds_[0-9a-f]{16}(_el)?")


def _segments_of(proc: Path) -> set[str]:
    """The /dev/shm files a process maps or holds open."""
    names = {line.rsplit("/", 1)[-1].split()[0] for line in (proc / "maps").read_text().splitlines()
             if "/dev/shm/" in line}
    for fd in (proc / "fd").iterdir():
        target = os.readlink(fd)
        if target.startswith("/dev/shm/"):
            names.add(target.rsplit("/", 1)[-1])
    return names


class Segments:
    """The Fast DDS participant segments (`fastdds_<16 hex>` and its `_el` lock file) that this test's processes
    map, polled while they run. pytest-xdist runs other tests at once, whose killed processes may leave segments of
    their own: only these are this test's to check."""

    def __init__(self) -> None:
        self.names: set[str] = set()
        self._pids: list[int] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._poll, daemon=True)
        self._thread.start()

    def watch(self, proc: subprocess.Popen[str]) -> subprocess.Popen[str]:
        self._pids.append(proc.pid)
        return proc

    def look(self) -> set[str]:
        for pid in list(self._pids):
            try:
                self.names |= {n for n in _segments_of(Path(f"/proc/{pid}")) if OWN_SEGMENT.fullmatch(n)}
            except OSError:
                continue  # ended meanwhile
        return self.names

    def _poll(self) -> None:
        while not self._stop.wait(0.02):
            self.look()

    def close(self) -> None:
        self._stop.set()
        self._thread.join()


@pytest.fixture
def segments() -> Iterator[Segments]:
    ours = Segments()
    yield ours
    ours.close()  # also when the test failed before it looked


def shm_leftovers(before: set[str], ours: Segments) -> set[str]:
    """This test's participant segments new in /dev/shm that no running process maps or holds open: what a
    participant that did not shut down leaves. The port segments and their semaphores (`fastdds_port<N>`,
    `sem.fastdds_port<N>_mutex`) are shared by every Fast DDS process on the machine, and one that ends while
    another opens them may leave them; they are not this test's."""
    ours.close()
    used: set[str] = set()
    for proc in Path("/proc").glob("[0-9]*"):
        try:
            used |= _segments_of(proc)
        except OSError:
            continue  # a process that ended meanwhile, or one of another user
    return {name for name in set(os.listdir(SHM)) - before if name not in used and name in ours.names}


def serve_process(transport: str, domain: int) -> subprocess.Popen[str]:
    return subprocess.Popen([sys.executable, "-m", "hexar", "serve", "--transport", transport, "--domain",
                             str(domain), "--duration", "120"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


def _ended(serve: subprocess.Popen[str], timeout_s: float = 30.0) -> tuple[str, str]:
    """The process's output once it ended; one that did not end in time is failed with every thread's stack, which
    `hexar serve` prints on SIGUSR1, so a hang says where it hangs."""
    try:
        return serve.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        serve.send_signal(signal.SIGUSR1)
        time.sleep(2.0)
        serve.kill()
        _, err = serve.communicate()
        pytest.fail(f"serve did not end {timeout_s:.0f} s after the signal; its threads:\n{err[-6000:]}")


def node_names(domain: int) -> list[str]:
    from hexar.live.ros import RosNode

    spy = RosNode("hexar_test_spy", domain)
    try:
        deadline = time.monotonic() + 10
        while "hexar" not in spy.node.get_node_names() and time.monotonic() < deadline:
            time.sleep(0.1)
        return sorted(set(spy.node.get_node_names()) - {"hexar_test_spy", "hexar_test_listener"})
    finally:
        spy.close()


def test_serve_and_replay_processes(suite: Path, transport: str, segments: Segments) -> None:
    domain, ours = fresh_domain(), segments
    before = set(os.listdir(SHM)) if SHM.is_dir() else set()
    serve = ours.watch(serve_process(transport, domain))
    listener = Listener(domain)
    try:
        assert serve.stderr is not None
        line = serve.stderr.readline()  # printed once the node listens
        assert f"listening over {transport}" in line and "writes only /hexar/answer" in line
        assert bool(ours.look()) == (transport == "rclpy")  # a Fast DDS participant maps its segment
        if transport == "rclpy":
            assert node_names(domain) == ["hexar"]  # as `ros2 node list` shows it
        robot = ours.watch(replay_process(suite / "bagfile_7_1", domain, 20.0, transport=other(transport)))
        played, robot_err = robot.communicate(timeout=120)
        assert robot.returncode == 0 and "Traceback" not in robot_err, robot_err
        assert "replayed" in played
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
    assert serve.returncode == 0 and "Traceback" not in err and "terminate called" not in err
    if SHM.is_dir():
        assert shm_leftovers(before, ours) == set()


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_ends_serve_cleanly(transport: str, sig: signal.Signals, segments: Segments) -> None:
    """Ctrl-C or a service manager's SIGTERM: exit 0, the summary line, no abort, nothing left behind."""
    domain, ours = fresh_domain(), segments
    before = set(os.listdir(SHM)) if SHM.is_dir() else set()
    serve = ours.watch(serve_process(transport, domain))
    assert serve.stderr is not None
    assert "listening" in serve.stderr.readline()
    assert bool(ours.look()) == (transport == "rclpy")  # a Fast DDS participant maps its segment
    serve.send_signal(sig)
    _, err = _ended(serve)
    assert serve.returncode == 0, err
    assert "hexar serve: received 0 records" in err
    assert "Traceback" not in err and "terminate called" not in err
    if SHM.is_dir():
        assert shm_leftovers(before, ours) == set()


@pytest.mark.parametrize(("argv", "message"), [
    (["serve", "--transport", "rclpy"], "needs rclpy"),
    (["serve", "--transport", "rclpy", "--domain", "500"], "out of range"),
    (["replay", "RUN", "--clock", "-1"], "--clock must be 0"),
    (["serve", "--transport", "zenoh"], "unknown transport"),
    (["chat", "--live", "--transport", "zenoh"], "unknown transport"),
    (["chat", "--transport", "rclpy"], "--transport needs --live"),
    (["serve", "--transport", "T", "--domain", "500"], "out of range"),
    (["serve", "--proactive", "loud"], "unknown --proactive"),
    (["serve", "--voice", "robot", "--transport", "T", "--domain", "230"], "--voice robot needs"),
    (["serve", "--transport", "T", "--tts-topic", "tts"], "absolute ROS topic"),
    (["serve", "--mic", "--wav", "q.wav"], "not both"),
    (["replay", "no/such/recording"], "recording not found"),
    (["replay", "RUN", "--rate", "0"], "--rate must be above 0"),
    (["replay", "RUN", "--start", "-1"], "--start must be 0 or more seconds"),
    (["replay", "RUN", "--start", "nan"], "--start must be 0 or more seconds"),
    (["replay", "RUN", "--start", "1e12"], "past the end of bagfile_7_1, which lasts"),  # was an OverflowError
    (["replay", "RUN", "--start", "inf"], "past the end of bagfile_7_1"),
    (["replay", "RUN", "--clock", "nan"], "--clock must be 0"),
    (["serve", "--transport", "T", "--horizon", "nan"], "--horizon above 0"),
    (["serve", "--transport", "T", "--duration", "-1"], "--duration must be above 0"),
    (["serve", "--transport", "T", "--speak-every", "-5"], "--speak-every must be 0 (say each) or more"),
    (["serve", "--transport", "T", "--speak-every", "nan"], "--speak-every must be 0 (say each) or more"),
])
def test_bad_input_is_one_line(argv: list[str], message: str, suite: Path, capsys: pytest.CaptureFixture[str],
                               monkeypatch: pytest.MonkeyPatch) -> None:
    if "rclpy" in argv:
        monkeypatch.setitem(sys.modules, "rclpy", None)  # as on any machine without ROS 2
    # T: the transport that is installed (DDS, or rclpy where cyclonedds has no wheel)
    argv = [str(suite / "bagfile_7_1") if a == "RUN" else DEFAULT if a == "T" else a for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("ERROR: ") and message in err and "\n" not in err and "Traceback" not in err


def test_bad_ros_domain_id(suite: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_DOMAIN_ID", "robot")
    assert main(["replay", str(suite / "bagfile_7_1"), "--transport", DEFAULT]) == 2
    assert capsys.readouterr().err.strip() == "ERROR: ROS_DOMAIN_ID='robot' is not a number"


def test_not_a_recording(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["replay", str(tmp_path), "--transport", DEFAULT]) == 2
    assert "has no metadata.yaml" in capsys.readouterr().err


def test_chat_live_talks_with_the_running_node(suite: Path, transport: str) -> None:
    from hexar.live.chat_live import chat_live
    from tests.live.dds_helpers import live_node

    domain = fresh_domain()
    shown: list[dict[str, object]] = []
    with live_node(domain, transport=transport):
        played = replay(suite / "bagfile_19_1", domain, rate=40.0, transport=other(transport))
        time.sleep(1.0)
        # the chat on the node's other transport where both exist: each crosses DDS vendors
        # piped, five questions come faster than the node takes them from one conversation: none may be lost;
        # "bye" ends the talk, and what follows it is never asked
        assert chat_live(domain, ["Why didn't you tell Maria?", "why?", "thanks", "How long did it take?",
                                  "What did you say?", "bye", "what happened?"], shown.append,
                         transport=other(transport)) == 0
    assert shown[-1] == {"trigger": "farewell", "answer": "Goodbye.", "thread": shown[-2]["thread"]}
    answers = [a for a in shown if a["trigger"] == "question"]
    assert len(answers) == 5
    assert answers[0]["causes"] == ["tts.timeout"], (answers[0], played)  # played: any topic no reader matched
    assert answers[1]["route"] == "followup" and answers[1]["thread"] == answers[0]["thread"]
    assert answers[2]["intent"] == "smalltalk" and answers[2]["answer"].startswith("You're welcome.")
    assert [a["intent"] for a in answers[3:]] == ["content", "content"], answers[3:]


def test_chat_live_without_a_node_says_so(capsys: pytest.CaptureFixture[str]) -> None:
    from hexar.live.chat_live import chat_live
    from hexar.live.errors import LiveError

    with pytest.raises(LiveError, match="no answer from hexar serve"):
        chat_live(fresh_domain(), ["why?"], print, timeout=1.0, transport=DEFAULT)
    assert main(["chat"]) == 2
    assert "give a recording, or --live" in capsys.readouterr().err


@pytest.mark.skipif(importlib.util.find_spec("ros_wheels_bootstrapper") is None,
                    reason="only the ROS 2 Kilted wheels re-execute Python at start-up")
@pytest.mark.parametrize("user_skips_bootstrap", [False, True], ids=["shell", "bootstrap-skipped"])
def test_rclpy_serve_works_when_python_starts_without_the_wheels_reexecution(user_skips_bootstrap: bool) -> None:
    """The `hexar` command starts without the wheels' re-execution (scripts/hexar_ros_lazy.pth, or the user's
    _ROS_WHEELS_BOOTSTRAP_COMPLETE); `hexar serve --transport rclpy` then re-executes itself once with the wheels'
    library path."""
    drop = {"LD_LIBRARY_PATH", "_ROS_WHEELS_BOOTSTRAP_COMPLETE", "_HEXAR_ROS_LAZY", "_HEXAR_ROS_REEXEC"}
    env = {k: v for k, v in os.environ.items() if k not in drop}
    if user_skips_bootstrap:
        env["_ROS_WHEELS_BOOTSTRAP_COMPLETE"] = "1"
    done = subprocess.run([sys.executable, "-m", "hexar", "serve", "--transport", "rclpy", "--domain",
                           str(fresh_domain()), "--duration", "1"], env=env, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert "listening over rclpy" in done.stderr and "Traceback" not in done.stderr


def test_sigusr1_prints_every_threads_stack_and_serve_goes_on(transport: str) -> None:
    """A serve that seems stuck on a robot: `kill -USR1 PID` shows where each thread is, and it keeps serving."""
    serve = serve_process(transport, fresh_domain())
    assert serve.stderr is not None
    assert "listening" in serve.stderr.readline()
    serve.send_signal(signal.SIGUSR1)
    time.sleep(1.0)
    assert serve.poll() is None
    serve.send_signal(signal.SIGTERM)
    _, err = _ended(serve)
    assert serve.returncode == 0, err
    assert "most recent call first" in err and "Thread 0x" in err and "hexar serve: received 0 records" in err
    assert "in _run" in err  # the main thread, waiting in the serving loop
