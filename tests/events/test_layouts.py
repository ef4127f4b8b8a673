"""A /rosout whose messages have another layout than the standard rcl_interfaces/msg/Log: decoded with the
definition the recording stores, or reported unreadable; never silently misread."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from rosbags.rosbag2 import Writer
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from hexar.cli import main
from hexar.evals.cases import scenario
from hexar.evals.scenarios.bag import TYPESTORE
from hexar.evals.scenarios.suite import record
from hexar.events import contract as c
from hexar.events.reader import read_recording

# A newer robot's Log: a host field between level and name, and two fields after line.
NEWER_LOG = """
builtin_interfaces/Time stamp
uint8 level
string host
string name
string msg
string file
string function
uint32 line
string robot_id
float64 battery
"""


def _newer_store() -> Any:
    store = get_typestore(Stores.EMPTY)
    store.register({"builtin_interfaces/msg/Time": TYPESTORE.fielddefs["builtin_interfaces/msg/Time"]})
    store.register(get_types_from_msg(NEWER_LOG, c.LOG_TYPE))
    return store


def _write(out: Path, store_definition: bool) -> Path:
    """Scenario 5 (a blocked path) with every /rosout line in the newer layout. With `store_definition` the
    recording carries the newer definition; without, it claims the standard one (a wrongly built recorder)."""
    newer = _newer_store()
    Log = newer.types[c.LOG_TYPE]
    with Writer(out, version=9) as writer:
        conns: dict[tuple[str, str], Any] = {}
        for t, topic, typ, m in sorted(record(scenario(5), 1).messages, key=lambda m: m[0]):
            store = TYPESTORE
            if typ == c.LOG_TYPE:
                m = Log(stamp=newer.types["builtin_interfaces/msg/Time"](sec=m.stamp.sec, nanosec=m.stamp.nanosec),
                        level=m.level, host="tiago-134", name=m.name, msg=m.msg, file=m.file, function=m.function,
                        line=m.line, robot_id="tiago-134", battery=0.81)
                store = newer
            if (topic, typ) not in conns:
                conns[(topic, typ)] = writer.add_connection(
                    topic, typ, typestore=newer if typ == c.LOG_TYPE and store_definition else TYPESTORE)
            writer.write(conns[(topic, typ)], t, store.serialize_cdr(m, typ))
    return out


def _ask(bag: Path, capsys: pytest.CaptureFixture[str]) -> dict[str, Any]:
    assert main(["ask", str(bag), "What happened?", "--llm", "none", "--json"]) == 0
    result: dict[str, Any] = json.loads(capsys.readouterr().out)
    return result


def test_newer_layout_is_read_with_the_recordings_definition(tmp_path: Path,
                                                             capsys: pytest.CaptureFixture[str]) -> None:
    bag = _write(tmp_path / "newer", store_definition=True)
    log = read_recording(bag)
    assert log.logs and not log.warnings
    assert all(line.name != "tiago-134" for line in log.logs)  # `host` is not misread as the logger name
    assert any(line.name == "bt_navigator" and line.msg.startswith("Begin navigating") for line in log.logs)
    result = _ask(bag, capsys)
    assert "navigation.blocked_path" in result["causes"]
    standard = record(scenario(5), 1).write(tmp_path / "standard")
    assert read_recording(standard).logs == log.logs


def test_newer_layout_under_the_standard_name_is_unreadable(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    bag = _write(tmp_path / "claims_standard", store_definition=False)
    log = read_recording(bag)
    assert not log.logs
    assert any(w.startswith("/rosout is unreadable and was not used") for w in log.warnings)
    result = _ask(bag, capsys)
    assert "navigation.blocked_path" not in result["causes"]
    assert all(ev["topic"] != c.ROSOUT for ev in result["evidence"])
    assert main(["inspect", str(bag)]) == 0
    assert "/rosout is unreadable" in capsys.readouterr().out
