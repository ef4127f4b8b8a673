"""`hexar annotate`: the recording copied to MCAP with one explanation per task, readable by mcap and rosbags."""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path

import pytest
from mcap.reader import make_reader
from rosbags.rosbag2 import Reader
from rosbags.typesys import Stores, get_typestore

from hexar.cli import main
from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.events import read_recording

TS = get_typestore(Stores.ROS2_HUMBLE)


def _counts(path: Path) -> Counter[str]:
    reader = Reader(path)
    reader.open()
    try:
        return Counter(conn.topic for conn, _, _ in reader.messages())
    finally:
        reader.close()


def _explanations_mcap(path: Path) -> list[dict[str, object]]:
    with path.open("rb") as fh:
        found = []
        for schema, channel, message in make_reader(fh).iter_messages(topics=["/hexar/explanations"]):
            assert schema is not None and schema.name == "std_msgs/msg/String" and schema.encoding == "ros2msg"
            assert channel.message_encoding == "cdr"
            found.append(json.loads(TS.deserialize_cdr(message.data, "std_msgs/msg/String").data))
        return found


@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
def test_one_explanation_per_task_and_every_original_message(tmp_path: Path, storage: str) -> None:
    assert main(["simulate", "--out", str(tmp_path / "runs"), "--scenario", "5", "--storage", storage]) == 0
    run = tmp_path / "runs" / "bagfile_5_1"
    out = tmp_path / "annotated.mcap"
    assert main(["annotate", str(run), "--out", str(out), "--llm", "none"]) == 0
    tasks = read_recording(run).tasks
    found = _explanations_mcap(out)
    assert [e["task_id"] for e in found] == [t.task_id for t in tasks] and len(tasks) == 2
    assert found[0]["causes"] == ["navigation.blocked_path"] and "blocked" in str(found[0]["answer"])
    assert found[0]["backend"] == "none" and found[0]["evidence"]
    # rosbags reads the file too: the originals are all there, and the log lines decode as rcl_interfaces/Log
    before, after = _counts(run), _counts(out)
    assert {k: v for k, v in after.items() if not k.startswith("/hexar/")} == before
    assert after["/hexar/explanations"] == 2
    reader = Reader(out)
    reader.open()
    lines = [TS.deserialize_cdr(raw, conn.msgtype) for conn, _, raw in reader.messages()
             if conn.topic == "/hexar/log"]
    reader.close()
    assert sum(1 for m in lines if m.name == "hexar") == 2
    failed = next(m for m in lines if m.name == "hexar" and "failed" in m.msg)
    assert failed.level == 40 and "navigation.blocked_path" in failed.msg
    assert any(m.name == "hexar.evidence" and "Failed to make progress" in m.msg for m in lines)


def test_explanation_sits_at_the_failure(tmp_path: Path, suite: Path) -> None:
    out = tmp_path / "a.mcap"
    assert main(["annotate", str(suite / "bagfile_19_1"), "--out", str(out), "--llm", "none"]) == 0
    task = read_recording(suite / "bagfile_19_1").task()
    with out.open("rb") as fh:
        times = [m.log_time for _, _, m in make_reader(fh).iter_messages(topics=["/hexar/explanations"])]
    assert task.window()[1] in times


@pytest.mark.parametrize(("target", "message"), [
    ("/definitely/not/here", "recording not found"),
    ("NOTASK", "no task to explain"),
    ("ROS1", "not ROS 1 bags"),
])
def test_bad_recordings_are_one_line(tmp_path: Path, target: str, message: str,
                                     capsys: pytest.CaptureFixture[str]) -> None:
    run = target
    if target == "NOTASK":
        b = BagBuilder()
        b.log(sec_ns(1_741_600_000), "talker", 20, "Publishing: 'Hello World: 1'")
        run = str(b.write(tmp_path / "talker"))
    if target == "ROS1":
        (tmp_path / "old.bag").write_bytes(b"#ROSBAG V2.0\n")
        run = str(tmp_path / "old.bag")
    assert main(["annotate", run, "--out", str(tmp_path / "x.mcap"), "--llm", "none"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR:") and message in err and err.count("\n") == 1
    assert not (tmp_path / "x.mcap").exists()


def test_unwritable_output_is_one_line(suite: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["annotate", str(suite / "bagfile_5_1"), "--out", "/definitely/not/here/x.mcap", "--llm", "none"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR: cannot write") and err.count("\n") == 1


def test_annotating_an_annotated_copy_replaces_its_explanations(tmp_path: Path) -> None:
    """A copy annotated again (after an upgrade, or with another model) holds today's explanations once, on one
    channel each, not the old ones beside them."""
    assert main(["simulate", "--out", str(tmp_path / "runs"), "--scenario", "5", "--storage", "mcap"]) == 0
    run = tmp_path / "runs" / "bagfile_5_1"
    once, twice = tmp_path / "once.mcap", tmp_path / "twice.mcap"
    assert main(["annotate", str(run), "--out", str(once), "--llm", "none"]) == 0
    assert main(["annotate", str(once), "--out", str(twice), "--llm", "none"]) == 0
    with twice.open("rb") as fh:
        summary = make_reader(fh).get_summary()
    assert summary is not None
    topics = Counter(ch.topic for ch in summary.channels.values())
    assert topics["/hexar/explanations"] == 1 and topics["/hexar/log"] == 1
    assert _counts(twice) == _counts(once)
    assert [e["causes"] for e in _explanations_mcap(twice)] == [e["causes"] for e in _explanations_mcap(once)]
