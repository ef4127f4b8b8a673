"""Contact with the robot (live/contact.py): a robot whose participant DDS dropped (its lease ran out, as on a
Wi-Fi dropout) is told in the answers about what it did then, with when the node heard nothing from it."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from hexar.events import contract as c
from hexar.events.reader import read_recording
from hexar.events.tasks import build_tasks
from hexar.live.contact import Contact, annotate, note
from hexar.live.node import FAILURE_QUESTION, LiveNode
from hexar.live.recheck import AFTER_S
from hexar.live.topics import TopicQos
from tests.live.conftest import LOOPBACK_CYCLONE, NO_RCLPY
from tests.live.dds_helpers import NO_DDS, Listener, fresh_domain, live_node, replay_process
from tests.live.test_replay_explains import expected

LEASE_S = 2
ROBOT, LAPTOP = b"\x01" * 12, b"\x02" * 12


class Clock:
    def __init__(self) -> None:
        self.now = 1_800_000_000.0

    def __call__(self) -> float:
        return self.now


def _contact() -> tuple[Contact, Clock, list[str], list[int]]:
    clock, lines, newest = Clock(), [], [0]
    contact = Contact(lambda: newest[0], wall=clock, clock=clock, report=lines.append)
    return contact, clock, lines, newest


def test_a_participant_dropped_and_heard_again_is_one_gap_with_its_times() -> None:
    contact, clock, lines, newest = _contact()
    contact.heard(ROBOT)
    contact.seen({ROBOT: "bt_navigator, controller_server"})
    clock.now += 1.0
    newest[0] = 10
    contact.heard(ROBOT)  # its last record before the link dropped
    clock.now += 20.0
    contact.seen({})  # its lease ran out
    assert contact.stats() == {"gaps": 1, "not_back": 1, "missed": 0}
    assert "lost contact with bt_navigator, controller_server" in lines[0] and "20 s ago" in lines[0]
    clock.now += 20.0
    newest[0] = 50
    contact.heard(ROBOT)
    assert contact.stats() == {"gaps": 1, "not_back": 0, "missed": 0}
    assert "again, 40 s after its last record" in lines[1]
    gap, = contact.gaps(0, None)
    assert (gap.since_t, gap.until_t, gap.alone) == (10, 50, True)
    assert contact.gaps(0, 9) == [] and contact.gaps(51, None) == []  # a task that ended before, or began after
    said = note(contact.gaps(0, None))
    assert said.startswith("I heard nothing from the robot from ") and "(40 s)" in said
    assert said.endswith("(40 s), so I may have missed what happened then.")


def test_a_participant_never_heard_leaves_no_gap_and_one_that_left_is_not_back() -> None:
    contact, clock, lines, newest = _contact()
    contact.seen({ROBOT: "", LAPTOP: "rviz2"})
    contact.seen({})  # LAPTOP wrote nothing the node read: nothing was missed
    assert contact.stats()["gaps"] == 0 and lines == []
    contact.heard(ROBOT)
    contact.seen({ROBOT: ""})
    clock.now += 30.0
    contact.seen({})
    newest[0] = 5
    assert note(contact.gaps(0, None), now=clock.now + 5).startswith(
        "I have not heard from the robot since ")
    assert "(35 s)" in note(contact.gaps(0, None), now=clock.now + 5)
    assert contact.gaps(1, None) == []  # a task that began after it left: not told of it


def test_a_process_lost_while_the_rest_of_the_robot_spoke_is_named() -> None:
    contact, clock, _, _ = _contact()
    contact.heard(ROBOT)
    contact.heard(LAPTOP)
    contact.seen({ROBOT: "amcl", LAPTOP: "map_server"})
    clock.now += 5.0
    contact.heard(LAPTOP)  # the other process goes on talking: not the robot's link
    clock.now += 10.0
    contact.seen({LAPTOP: "map_server"})
    said = note(contact.gaps(0, None), now=clock.now)
    assert said.startswith("I have not heard from amcl since ") and "the robot" not in said


def test_a_jump_in_a_writers_sequence_numbers_is_told_as_messages_that_never_came() -> None:
    contact, clock, lines, newest = _contact()
    writer, odom = ROBOT + b"\x00\x00\x01\x03", ROBOT + b"\x00\x00\x02\x03"
    for seq in (1, 2, 3):
        contact.sequence(writer, "/task_info", seq)
    newest[0] = 10
    contact.sequence(writer, "/task_info", 4)
    contact.sequence(odom, "/odom", 1)
    clock.now += 16.0
    newest[0] = 30
    contact.sequence(odom, "/odom", 40)  # a busy reader of a 50 Hz stream: nothing hidden
    contact.sequence(odom[:-1] + b"\x04", "/power/is_charging", 1)
    contact.sequence(odom[:-1] + b"\x04", "/power/is_charging", 9)  # a state published again and again
    contact.sequence(writer, "/task_info", 9)
    contact.sequence(writer, "/task_info", 5)  # a resend of one already had
    assert contact.stats()["missed"] == 4 and len(lines) == 1 and "4 messages on /task_info" in lines[0]
    gap, = contact.gaps(0, None)
    assert (gap.since_t, gap.until_t, gap.missed) == (10, 30, 4)
    said = note([gap])
    assert said.startswith("4 messages the robot sent on /task_info from ") and "never reached me, so" in said
    contact.heard(ROBOT)
    contact.seen({ROBOT: ""})
    clock.now += 20.0
    contact.seen({})  # dropped right after: one hole, told with both
    said = note(contact.gaps(0, None), now=clock.now)
    assert said.startswith("I have not heard from the robot since ")
    assert ", and 4 messages it sent on /task_info never reached me, so I may have missed" in said


def _steady(contact: Contact, clock: Clock, newest: list[int], who: bytes, n: int = 6, every: float = 1.0) -> None:
    for _ in range(n):
        clock.now += every
        newest[0] += int(every * 1e9)
        contact.heard(who, c.DIAGNOSTICS)


def test_a_steady_participant_silent_for_a_lease_is_a_hole_though_dds_never_dropped_it() -> None:
    """A robot that dropped the node (a Fast DDS robot's longer lease against a Cyclone node's) stays known to the
    node's DDS: its silence, for as long as the node's own lease, is the only sign."""
    contact, clock, lines, newest = _contact()
    contact.quiet_after(10.0)
    _steady(contact, clock, newest, ROBOT)
    last = (clock.now, newest[0])
    clock.now += 12.0
    newest[0] += 12 * 10**9
    contact.heard(ROBOT, c.ROSOUT)  # the link is back: a line of the log comes first
    gap, = contact.gaps(0, None)
    assert (gap.since, gap.since_t, gap.until, gap.quiet, gap.alone) == (last[0], last[1], clock.now, True, True)
    assert "12 s after its last record" in lines[-1] and "its DDS participant was never dropped" in lines[-1]
    assert note([gap]).startswith("I heard nothing from the robot from ")
    # the steady rhythm must come back before another silence counts
    clock.now += 15.0
    contact.heard(ROBOT, c.DIAGNOSTICS)
    assert len(contact.gaps(0, None)) == 1


def test_short_silences_idle_participants_and_the_rclpy_transport_make_no_hole() -> None:
    for quiet, records, silence in ((10.0, (c.DIAGNOSTICS,), 8.0),  # a link both sides kept: resent
                                    (10.0, (c.ROSOUT,), 30.0),  # speaks only when there is something to say
                                    (None, (c.DIAGNOSTICS,), 30.0)):  # rclpy counts lost messages instead
        contact, clock, _, newest = _contact()
        if quiet is not None:
            contact.quiet_after(quiet)
        for topic in records:
            for _ in range(6):
                clock.now += 1.0
                contact.heard(ROBOT, topic)
        clock.now += silence
        contact.heard(ROBOT, c.DIAGNOSTICS)
        assert contact.gaps(0, None) == [], (quiet, records, silence)
    contact, clock, _, newest = _contact()
    contact.quiet_after(10.0)
    _steady(contact, clock, newest, ROBOT)
    clock.now += 8.0
    contact.heard(ROBOT, c.ROSOUT)  # its diagnostics had stopped before it went quiet: an idle robot, not a link
    clock.now += 20.0
    contact.heard(ROBOT, c.ROSOUT)
    assert contact.gaps(0, None) == []


def test_a_silent_process_while_the_rest_of_the_robot_spoke_is_not_the_robot() -> None:
    contact, clock, _, newest = _contact()
    contact.quiet_after(10.0)
    _steady(contact, clock, newest, ROBOT)
    for _ in range(240):  # another process of the robot goes on, at 20 Hz: not the robot's link
        clock.now += 0.05
        contact.heard(LAPTOP, c.ODOM)
    contact.heard(ROBOT, c.DIAGNOSTICS)
    gap, = contact.gaps(0, None)
    assert not gap.alone and note([gap]).startswith("I heard nothing from one of the robot's processes from ")


def test_an_answer_without_a_cause_starts_with_the_gap_and_one_with_a_cause_ends_with_it(suite: Path) -> None:
    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session

    session = Session(RunSettings(recording=suite / "bagfile_5_1", llm="none"))
    task = next(t for t in session.context.log.tasks if t.outcome == "failed")
    contact, clock, _, newest = _contact()
    newest[0] = task.created + 1
    contact.heard(ROBOT)
    contact.seen({ROBOT: ""})
    clock.now += 15.0
    contact.seen({})
    newest[0] = task.last_update + 1
    contact.heard(ROBOT)
    told = dict(session.ask(FAILURE_QUESTION, task=task.task_id))
    annotate(told, session.context.log.tasks, contact)
    assert told["causes"] and told["answer"].endswith("(15 s), so I may have missed what happened then.")
    assert told["contact"][0]["seconds"] == 15.0
    unknown = {"task_id": task.task_id, "answer": "I don't have enough information to say.", "causes": []}
    annotate(unknown, session.context.log.tasks, contact)
    assert unknown["answer"].startswith("I heard nothing from the robot from ")
    assert "The last I heard" not in unknown["answer"]  # the task ended: its end came
    running = build_tasks([u for u in session.context.log.task_updates if u.task_id == task.task_id][:-1])
    annotate(unknown, running, contact)  # its failing update never came: the task is still running as heard
    assert "The last I heard, I was still at step 1 (to go to the kitchen)." in unknown["answer"]
    other_task = {"task_id": "not-a-task", "answer": "Something.", "causes": []}
    annotate(other_task, session.context.log.tasks, contact)
    assert other_task == {"task_id": "not-a-task", "answer": "Something.", "causes": []}


def _told(listener: Listener, robot: subprocess.Popen[str], failures: dict[str, list[str]],
          timeout: float) -> tuple[list[dict[str, Any]], dict[str, list[str]]]:
    """Once the robot's replay ended: the failures explained unasked, and each one's causes after the node's
    corrections. Resends of what the robot sent as it came back can reach the node after its first answer; its
    looks again 1, 4 and 8 s later correct that (live/recheck.py). On a loaded machine the resends can come after
    those, and the node's last look, 15 s after its answer, corrects it: only then is a cause not yet the
    recording's waited for."""
    _, err = robot.communicate(timeout=120)
    assert robot.returncode == 0, err
    got = listener.wait_answers(len(failures), "failure", timeout=timeout)
    deadline = time.monotonic() + AFTER_S[-1] + 2.0
    time.sleep(9.0)
    while True:
        corrected = {a["task_id"]: a["causes"] for _, a in listener.answers("correction")}
        told = {a["task_id"]: corrected.get(a["task_id"], a["causes"]) for a in got}
        if told == failures or time.monotonic() >= deadline:
            return got, told
        time.sleep(0.1)


# The robot's Cyclone participant announces a 2 s lease, so that a pause of a few seconds drops it, as 10-20 s of lost
# Wi-Fi drop a robot with the vendors' defaults (Cyclone DDS 10 s, Fast DDS 20 s).
SHORT_LEASE = f"{LOOPBACK_CYCLONE},<Discovery><LeaseDuration>{LEASE_S}s</LeaseDuration></Discovery>"


def robot_dropped_mid_task(node: LiveNode, run: Path, domain: int) -> tuple[subprocess.Popen[str], dict[str, int]]:
    """A robot (`hexar replay` on Cyclone, announcing a 2 s lease) replays `run` at x5 into `node`; a second after
    its task started it stops for three leases (SIGSTOP: to the node a link that carries nothing), 35 s of its
    clock, then goes on. The replay's process, and the node's contact figures while the robot was stopped."""
    cmd = [sys.executable, "-m", "hexar", "replay", str(run), "--rate", "5", "--transport", "dds",
           "--domain", str(domain)]
    proc = subprocess.Popen(cmd, env={**os.environ, "CYCLONEDDS_URI": SHORT_LEASE},
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not node.log.stats()["tasks"] and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(1.0)
    proc.send_signal(signal.SIGSTOP)
    time.sleep(3 * LEASE_S + 1.0)
    lost = node.log.contact.stats()
    proc.send_signal(signal.SIGCONT)
    return proc, lost


@NO_DDS  # the robot is a Cyclone participant announcing a 2 s lease
def test_a_robot_dropped_mid_task_is_told_in_the_failure_it_explains(suite: Path, transport: str) -> None:
    """A robot (`hexar replay` on Cyclone) stops for three leases in the middle of its navigation (SIGSTOP: to
    the node a link that carries nothing), then goes on and fails: the node drops it, finds it again, and its
    unasked explanation gives the cause and the hole in what it heard. (A frozen robot never drops the node in
    turn, which a Fast DDS robot does not get over with a Cyclone node: scripts/bench_live_outage.py cuts a real
    link instead, with root.)"""
    run = suite / "bagfile_5_1"
    failures, _ = expected(run)
    domain = fresh_domain()
    listener = Listener(domain)
    try:
        with live_node(domain, transport=transport) as node:
            proc, lost = robot_dropped_mid_task(node, run, domain)
            got, told = _told(listener, proc, failures, 10.0)
            heard = node.log.stats()
    finally:
        listener.close()
    assert (lost["gaps"], lost["not_back"]) == (1, 1)
    # what the robot sent in the hole came as resends, behind its newer messages: late, not a clock that went back
    assert heard["clock_jumps"] == 0, list(node.log.warnings)
    assert told == failures, [(a["answer"], [(e["t"], e["item"]) for e in a["evidence"]]) for a in got]
    answer = got[0]["answer"]
    assert "I heard nothing from the robot from " in answer and answer.endswith("I may have missed what happened then.")
    dropped = [g for g in got[0]["contact"] if not g["missed"]]
    assert len(dropped) == 1 and dropped[0]["heard_again"] and dropped[0]["seconds"] >= 3 * LEASE_S


def _told_failure(line: str) -> bool:
    return line.startswith("{") and json.loads(line).get("trigger") == "failure"


# The stalled node sometimes loses nothing at all (it received every one of the 30: 279 records against about 252
# when the kernel drops some), and then has no hole to tell. Seen on 3.11 and 3.13 before the test waited for the
# node's acknowledgement of the first message; after it, only on 3.13 (1 run in 7 here, beside another): skipped there.
@pytest.mark.skipif(sys.version_info >= (3, 13), reason="on 3.13's rclpy a stalled node under load may lose nothing")
@NO_RCLPY
@NO_DDS
def test_messages_a_publisher_no_longer_kept_for_the_node_are_counted(suite: Path) -> None:
    """`hexar serve` on rclpy stalls for 2 s (well inside every lease) while a robot's skill-event publisher that
    keeps its last 5 messages sends 30 of 64 KB, more than the node's socket buffers hold (212 KB by default on
    Linux): what the kernel dropped and the publisher no longer keeps never comes, as on a Wi-Fi link that stalls.
    The node counts them from the writer's sequence numbers and tells them in the failure it explains, or, where
    the failure came before the resends that reveal the hole, in a correction of it (live/node.py _recheck)."""
    from cyclonedds.util import duration

    from hexar.live import msgs
    from hexar.live.dds import DdsEndpoint

    run, domain = suite / "bagfile_5_1", fresh_domain()
    serve = subprocess.Popen([sys.executable, "-m", "hexar", "serve", "--transport", "rclpy", "--domain", str(domain),
                              "--no-follow-launch-log"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    endpoint = DdsEndpoint(domain)
    tasks = endpoint.reader(c.TASK_INFO, c.STRING_TYPE, TopicQos(depth=100))
    events = endpoint.writer(c.PIZZA_EVENTS, c.DIAG_TYPE, TopicQos(depth=5))
    assert serve.stdout is not None and serve.stderr is not None and "listening" in serve.stderr.readline()
    # both pipes drained as the node writes them: a node blocked on a full pipe would tell nothing
    out: list[str] = []
    err: list[str] = []
    readers = [threading.Thread(target=lambda f=f, into=into: into.extend(f), daemon=True)
               for f, into in ((serve.stdout, out), (serve.stderr, err))]
    for reader in readers:
        reader.start()
    try:
        # at twice the recording's pace the failure (36 s into the task) comes about 15 s after the stall ends: the
        # writer's resends and the hole they reveal have had their time (at 4x it came 6 s after, and once in about
        # 15 runs the failure was told before the hole was known)
        robot = subprocess.Popen([sys.executable, "-m", "hexar", "replay", str(run), "--rate", "2", "--transport",
                                  "dds", "--domain", str(domain)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                 text=True)
        deadline = time.monotonic() + 60
        while not tasks.take(1) and time.monotonic() < deadline:
            time.sleep(0.05)
        # stamped on the robot's clock, which replays the recording's day: just after the task began
        stamp = msgs.Header(stamp=msgs.time_of(read_recording(run).tasks[0].created + 2 * 10**9))
        # the node has this writer's first number: it matched the writer and acknowledged the first message (a loaded
        # machine discovers late; a reader that matched only after the stall would see no hole, correctly)
        deadline = time.monotonic() + 30
        while not events.get_matched_subscriptions() and time.monotonic() < deadline:
            time.sleep(0.05)
        events.write(msgs.DiagnosticArray(header=stamp))
        assert events.wait_for_acks(duration(seconds=10)), "the node never acknowledged the first message"
        time.sleep(0.5)
        serve.send_signal(signal.SIGSTOP)
        big = msgs.DiagnosticArray(header=stamp, status=[msgs.DiagnosticStatus(name="recipe", message="x" * 64_000)])
        for _ in range(30):
            events.write(big)
        time.sleep(2.0)
        serve.send_signal(signal.SIGCONT)
        events.write(msgs.DiagnosticArray(header=stamp))
        assert robot.wait(timeout=120) == 0
        # until the node told the failure (a busy computer takes longer than a quiet one), and the resends of what
        # the writer kept, and a second look at the failure, have had their time
        deadline = time.monotonic() + 60
        while not any(_told_failure(line) for line in list(out)) and time.monotonic() < deadline:
            time.sleep(0.2)
        time.sleep(4.0)
    finally:
        serve.send_signal(signal.SIGCONT)
        serve.send_signal(signal.SIGTERM)
        serve.wait(timeout=60)
        for reader in readers:
            reader.join(timeout=10)
    told = [json.loads(line) for line in out if line.startswith("{")]
    said = [a for a in told if a.get("trigger") in {"failure", "correction"}]
    assert said and said[0]["trigger"] == "failure", ("".join(err), told)
    failure = said[-1]  # the failure as last told: corrected where the hole became known after it
    assert "contact" in failure, ("".join(err), said)
    missed = [g["missed"] for g in failure["contact"]]
    # the publisher kept its last 5 for a resend; the kernel may drop them in more than one run of numbers (a fresh
    # clone's run saw 7 and 10), each told as its own hole
    assert missed and all(missed) and 1 <= sum(missed) <= 25, failure["contact"]
    for n in missed:
        assert f"{n} message{'s' if n > 1 else ''} on {c.PIZZA_EVENTS} never reached this node" in "".join(err)
    assert f" the robot sent on {c.PIZZA_EVENTS} from " in failure["answer"]



@NO_RCLPY
@NO_DDS
def test_a_fast_dds_robot_that_dropped_the_node_is_told_from_its_silence(suite: Path) -> None:
    """`hexar serve --transport dds` announcing a 2 s lease is stopped for 6 s in the middle of a Fast DDS
    robot's navigation (`hexar replay --transport rclpy`, Fast DDS's 20 s lease): the robot drops the node and
    resends nothing of what it published meanwhile, while the node's DDS never drops the robot. The robot's
    steady diagnostics went silent for longer than the node's lease: the failure explained afterwards tells the
    hole (round 32's code said nothing of it)."""
    run = suite / "bagfile_5_1"
    failures, _ = expected(run)
    domain = fresh_domain()
    listener = Listener(domain)
    serve = subprocess.Popen([sys.executable, "-m", "hexar", "serve", "--transport", "dds", "--domain", str(domain),
                              "--llm", "none"], env={**os.environ, "CYCLONEDDS_URI": SHORT_LEASE},
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    robot = None
    try:
        time.sleep(3.0)
        robot = replay_process(run, domain, 2.0, transport="rclpy")
        # the task has started (its first update comes 2.3 s into the replay), and the node has heard the robot's
        # steady diagnostics for a few seconds more: waited for, not slept, as a loaded machine starts slowly
        assert listener.wait_task() is not None
        time.sleep(2.7)
        serve.send_signal(signal.SIGSTOP)
        time.sleep(3 * LEASE_S)
        serve.send_signal(signal.SIGCONT)
        got, told = _told(listener, robot, failures, 15.0)
    finally:
        for proc in (robot, serve):
            if proc is not None and proc.poll() is None:
                proc.send_signal(signal.SIGCONT)
                proc.terminate()
        _, said = serve.communicate(timeout=30)
        listener.close()
    assert "though its DDS participant was never dropped" in said, said
    assert told == failures
    answer = got[0]["answer"]
    assert "I heard nothing from the robot from " in answer and answer.endswith("I may have missed what happened then.")
    quiet, = got[0]["contact"]
    assert quiet["heard_again"] and quiet["seconds"] >= 3 * LEASE_S - 1


@NO_DDS
def test_the_nodes_own_lease_is_read_from_cyclonedds_uri(tmp_path: Path) -> None:
    from hexar.live.dds import own_lease_s

    config = tmp_path / "cyclone.xml"
    config.write_text("<CycloneDDS><Domain><Discovery><LeaseDuration>45 s</LeaseDuration></Discovery></Domain>"
                      "</CycloneDDS>")
    assert own_lease_s("") == 10.0  # Cyclone DDS's default
    assert own_lease_s(SHORT_LEASE) == LEASE_S
    assert own_lease_s("<Discovery><LeaseDuration>500ms</LeaseDuration></Discovery>") == 0.5
    assert own_lease_s(f"file://{config}") == 45.0
    # later over earlier, as Cyclone merges them; a file it cannot read is Cyclone's own error
    assert own_lease_s(f"file://{config},<Discovery><LeaseDuration>1min</LeaseDuration></Discovery>") == 60.0
    assert own_lease_s(f"file://{tmp_path / 'missing.xml'}") == 10.0
