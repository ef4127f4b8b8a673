"""`serve --record` against a hostile publisher: stamps that jump back and forth never delete what was recorded,
and a bag name already taken never switches recording off. Real /rosout messages over DDS into real bags."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

# cyclonedds has no wheel for CPython 3.14 (the lock installs it only below); these tests are of the DDS transport
pytest.importorskip("cyclonedds", reason="cyclonedds (the `live` extra) has no wheel for this Python")

from hexar.events import contract as c
from hexar.events import read_recording
from hexar.live import msgs
from hexar.live.dds import DdsEndpoint, DdsTransport
from hexar.live.node import LiveNode, NodeOptions
from hexar.live.recorder import RollingRecorder
from hexar.live.replay import QOS_OF
from tests.live.dds_helpers import fresh_domain

T0 = 1_741_600_000 * 10**9


def _flood_rosout(domain: int, stamps: list[int]) -> None:
    """/rosout lines from another participant, each with the source timestamp it claims."""
    endpoint = DdsEndpoint(domain)
    writer = endpoint.writer(c.ROSOUT, c.LOG_TYPE, QOS_OF[c.ROSOUT])
    time.sleep(1.0)
    for i, stamp in enumerate(stamps):
        writer.write(msgs.Log(stamp=msgs.time_of(stamp), level=20, name="bt_navigator", msg=f"line {i}"),
                     timestamp=stamp)
        time.sleep(0.001)
    time.sleep(1.0)
    endpoint.close()


def _recorded_lines(bags: list[Path]) -> list[str]:
    return [line.msg for bag in bags for line in read_recording(bag).logs]


def test_stamps_jumping_back_and_forth_keep_every_line(tmp_path: Path) -> None:
    domain = fresh_domain()
    recorder = RollingRecorder(tmp_path / "rec", chunk_s=600, keep=3)
    node = LiveNode(DdsTransport(domain, recorder=recorder), options=NodeOptions(llm="none"))
    node.start()
    stamps = [T0 + (1 if i % 2 else -1) * 1000 * 10**9 + i for i in range(200)]
    try:
        _flood_rosout(domain, stamps)
    finally:
        node.stop()
    assert not recorder.failed and len(recorder.bags) == 1
    assert sorted(_recorded_lines(recorder.bags)) == sorted(f"line {i}" for i in range(200))


def test_a_taken_bag_name_does_not_stop_recording(tmp_path: Path) -> None:
    folder = tmp_path / "rec"
    recorder = RollingRecorder(folder, chunk_s=0.2, keep=50)
    # another recorder (a restarted `hexar serve`) already wrote the names this one would pick next
    for n in range(1, 40):
        (folder / f"live_{time.strftime('%Y%m%d_%H%M%S', time.gmtime())}_{n:04d}").mkdir()
    from hexar.events.humble import humble

    store = humble()
    from rosbags.typesys.stores.ros2_humble import builtin_interfaces__msg__Time as Time
    from rosbags.typesys.stores.ros2_humble import rcl_interfaces__msg__Log as Log

    for i in range(6):
        msg = Log(stamp=Time(sec=1_741_600_000 - i * 1000, nanosec=0), level=20, name="n", msg=f"line {i}",
                  file="", function="", line=0)
        recorder.write(c.ROSOUT, c.LOG_TYPE, bytes(store.serialize_cdr(msg, c.LOG_TYPE)), T0 - i * 1000 * 10**9)
        time.sleep(0.25)  # each message opens the next bag
    recorder.close()
    assert not recorder.failed and len(recorder.bags) == 6 == len(set(recorder.bags))
    assert sorted(_recorded_lines(recorder.bags)) == [f"line {i}" for i in range(6)]
