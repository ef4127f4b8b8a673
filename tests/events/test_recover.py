"""Recordings cut short by a crash: a .db3 without metadata.yaml and an MCAP without its footer are read from
their storage, as `ros2 bag reindex` recovers them, and said to be recovered; damage in the middle is not."""

from __future__ import annotations

import json
import shutil
import struct
from pathlib import Path

import pytest

from hexar.cli import main
from hexar.evals.cases import scenario
from hexar.evals.scenarios.suite import record
from hexar.events.errors import CorruptRecordingError, NotARecordingError
from hexar.events.reader import read_recording
from hexar.events.recover import salvage_mcap


@pytest.fixture(scope="module")
def whole_mcap(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Scenario 5 (a blocked path) as an MCAP recording, closed properly."""
    return record(scenario(5), 1).write(tmp_path_factory.mktemp("mcap") / "bag", "mcap")


def test_db3_without_metadata_reads_like_the_whole_recording(suite: Path, tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    bag = shutil.copytree(suite / "bagfile_5_1", tmp_path / "crashed")
    (bag / "metadata.yaml").unlink()
    whole, cut = read_recording(suite / "bagfile_5_1"), read_recording(bag)
    assert cut.warnings[0].startswith("recovered: crashed has no metadata.yaml")
    assert "ros2 bag reindex" in cut.warnings[0] and "bagfile_5_1.db3" in cut.warnings[0]
    assert [(t.task_id, t.outcome) for t in cut.tasks] == [(t.task_id, t.outcome) for t in whole.tasks]
    assert [ln.msg for ln in cut.logs] == [ln.msg for ln in whole.logs] and cut.storage == "sqlite3"
    # the storage file named directly is the same recording
    assert read_recording(next(bag.glob("*.db3"))).tasks[0].task_id == whole.tasks[0].task_id
    assert main(["ask", str(bag), "why didn't you bring it?", "--llm", "none"]) == 0
    out = capsys.readouterr()
    assert "something blocked my path" in out.out and "note: crashed: recovered:" in out.err


def test_mcap_cut_inside_its_chunk_gives_the_messages_before_the_cut(whole_mcap: Path, tmp_path: Path,
                                                                    capsys: pytest.CaptureFixture[str]) -> None:
    bag = shutil.copytree(whole_mcap, tmp_path / "bag")
    (bag / "metadata.yaml").unlink()  # the recorder died: no summary, no footer, no metadata
    mcap = next(bag.glob("*.mcap"))
    data = mcap.read_bytes()
    cut_at = data.index(b"Goal failed") + 40  # the last navigation line is whole, the task's end is not
    mcap.write_bytes(data[:cut_at])
    whole, cut = read_recording(whole_mcap), read_recording(bag)
    assert any(w.startswith("recovered: bag has no metadata.yaml") for w in cut.warnings)
    told = next(w for w in cut.warnings if "without its MCAP footer" in w)
    assert f"ends at byte {cut_at}" in told and f"read the {salvage_mcap(mcap).messages} messages" in told
    assert 0 < len(cut.logs) < len(whole.logs) + 1
    assert [ln.msg for ln in cut.logs] == [ln.msg for ln in whole.logs][: len(cut.logs)]
    assert any(ln.msg.startswith("Goal failed") for ln in cut.logs)
    # the task's own "failed" update came after the cut: the answer says what the recording holds up to it
    assert main(["ask", str(bag), "what happened", "--llm", "none", "--json"]) == 0
    answer = json.loads(capsys.readouterr().out)["answer"]
    assert "still running when the recording ends" in answer


def test_mcap_cut_before_any_message_is_one_line(whole_mcap: Path, tmp_path: Path,
                                                 capsys: pytest.CaptureFixture[str]) -> None:
    bag = shutil.copytree(whole_mcap, tmp_path / "bag")
    mcap = next(bag.glob("*.mcap"))
    mcap.write_bytes(mcap.read_bytes()[:60])
    with pytest.raises(CorruptRecordingError, match="before any whole message"):
        read_recording(bag)
    assert main(["inspect", str(bag)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("ERROR: cannot recover") and err.count("\n") == 1


def test_damage_in_the_middle_is_not_recovered(whole_mcap: Path, tmp_path: Path) -> None:
    # the file still ends like an MCAP file: a length gone wrong inside it is damage, never a cut
    bag = shutil.copytree(whole_mcap, tmp_path / "bag")
    mcap = next(bag.glob("*.mcap"))
    data = bytearray(mcap.read_bytes())
    chunk = data.index(b"\x06", 8)
    struct.pack_into("<Q", data, chunk + 1, 2**50)
    mcap.write_bytes(bytes(data))
    with pytest.raises(CorruptRecordingError, match="runs past the end of the file"):
        read_recording(bag)


def test_a_folder_with_no_storage_is_still_no_recording(tmp_path: Path) -> None:
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "readme.txt").write_text("not a bag")
    with pytest.raises(NotARecordingError, match=r"no metadata\.yaml and no \.db3 or \.mcap file"):
        read_recording(tmp_path / "notes")
