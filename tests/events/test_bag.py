"""events.bag opens a recording to the same connections, times and types as rosbags' own AnyReader, fails with the
same error text, and builds the types of recordings that store the same definitions once."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest
from rosbags.highlevel import AnyReader

from hexar.evals.scenarios.bag import BagBuilder
from hexar.events import contract as c
from hexar.events.bag import Directory, Reader
from hexar.events.humble import humble
from tests.events.helpers import T0, two_skill_task

# offered_qos_profiles as rosbag2 (Foxy to Humble) writes it into metadata.yaml: one YAML string per topic
QOS = ("- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n  deadline:\n    sec: 0\n    nsec: 0\n"
       "  lifespan:\n    sec: 0\n    nsec: 0\n  liveliness: 1\n  liveliness_lease_duration:\n    sec: 0\n"
       "    nsec: 0\n  avoid_ros_namespace_conventions: false")


def _bag(tmp_path: Path, name: str, storage: str) -> Path:
    b = BagBuilder()
    b.log(T0 + 5, "controller_server", 40, "Failed to make progress")
    b.flag(T0 + 1, c.JOY_PRIORITY, True)
    two_skill_task(b, T0, f"task-{name}", fail_second=True)
    return b.write(tmp_path / name, storage)  # type: ignore[arg-type]


def _opened(cls: type[AnyReader], path: Path) -> tuple[Any, ...]:
    with cls([path], default_typestore=humble()) as r:
        return ([conn._replace(owner=None) for conn in r.connections], r.message_count, r.start_time, r.end_time,
                [reader.storage.metadata for reader in r.readers], sorted(r.typestore.fielddefs.items()))


def _with_qos_strings(path: Path) -> None:
    meta = path / "metadata.yaml"
    meta.write_text(meta.read_text().replace("offered_qos_profiles: []", f"offered_qos_profiles: {json.dumps(QOS)}"))


@pytest.mark.parametrize("storage", ["sqlite3", "mcap"])
def test_opens_a_recording_as_rosbags_does(tmp_path: Path, storage: str) -> None:
    plain = _bag(tmp_path, "plain", storage)
    qos = _bag(tmp_path, "qos", storage)
    _with_qos_strings(qos)
    for path in (plain, qos):
        with Reader([path], default_typestore=humble()) as r:
            assert all(isinstance(reader.storage, Directory) for reader in r.readers)  # the fast way was taken
        assert _opened(Reader, path) == _opened(AnyReader, path)
    conn = _opened(Reader, qos)[0][0]
    assert conn.ext.offered_qos_profiles and conn.ext.offered_qos_profiles[0].depth == 0


def _metadata(text: str) -> Any:
    return lambda path: (path / "metadata.yaml").write_text(text)


@pytest.mark.parametrize("damage", [
    _metadata("not: [yaml"),
    _metadata("rosbag2_bagfile_information:\n  version: 42\n"),
    _metadata("rosbag2_bagfile_information:\n  version: 5\n"),
    lambda path: next(path.glob("*.db3")).unlink(),
], ids=["not yaml", "future version", "fields missing", "storage file missing"])
def test_a_damaged_recording_fails_with_rosbags_own_words(tmp_path: Path, damage: Any) -> None:
    path = _bag(tmp_path, "bad", "sqlite3")
    damage(path)
    errors = []
    for cls in (AnyReader, Reader):
        with pytest.raises(Exception) as err:  # the point: the same class and text from both
            _opened(cls, path)
        errors.append((type(err.value), str(err.value)))
    assert errors[0] == errors[1]


def test_recordings_with_the_same_definitions_share_their_types(tmp_path: Path) -> None:
    a, b = _bag(tmp_path, "a", "sqlite3"), _bag(tmp_path, "b", "sqlite3")
    with Reader([a], default_typestore=humble()) as ra, Reader([b], default_typestore=humble()) as rb:
        assert ra.typestore is rb.typestore
        with AnyReader([a], default_typestore=humble()) as plain:
            assert ra.typestore is not plain.typestore
