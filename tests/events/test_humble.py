"""The standard definitions' hashes kept in events.humble, and reading without building rosbags' Humble store."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from rosbags.typesys import Stores, get_typestore

from hexar.evals.scenarios.bag import BagBuilder
from hexar.events import contract as c
from hexar.events.humble import RIHS01, has_standard, humble_hash
from tests.events.helpers import T0, two_skill_task


def test_kept_hashes_are_rosbags_humble_hashes_of_every_type_hexar_reads() -> None:
    store = get_typestore(Stores.ROS2_HUMBLE)
    accepted = {t for types in c.ACCEPTED_TYPES.values() for t in types}
    assert set(RIHS01) == {t for t in accepted if t in store.fielddefs}
    for msgtype, digest in RIHS01.items():
        assert store.hash_rihs01(msgtype) == digest, msgtype
    # a type not kept is hashed by the store itself
    assert humble_hash("sensor_msgs/msg/JointState") == store.hash_rihs01("sensor_msgs/msg/JointState")
    assert has_standard("sensor_msgs/msg/JointState") and not has_standard("rosgraph_msgs/msg/Log")


def test_a_recording_that_stores_its_definitions_is_read_without_the_humble_store(tmp_path: Path) -> None:
    b = BagBuilder()
    b.log(T0 + 5, "controller_server", 40, "Failed to make progress")
    b.pose(T0 + 7, 1.0, 2.0, 0.5, 0.31, 0.29, 0.05)
    two_skill_task(b, T0, "task-a", fail_second=True)
    path = b.write(tmp_path / "run")
    # a fresh interpreter: the test process has built the store already
    code = ("import sys; import hexar.events.humble as h; from hexar.events import read_recording; "
            "log = read_recording(sys.argv[1]); "
            "print(len(log.logs), len(log.poses), len(log.tasks), h._STORE is None)")
    done = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["1", "1", "1", "True"]
