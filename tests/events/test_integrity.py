"""Storage damage is detected and reported in one line, never read as if the recording were whole."""

from __future__ import annotations

import shutil
import sqlite3
import struct
from pathlib import Path

import pytest

from hexar.cli import main
from hexar.evals.cases import scenario
from hexar.evals.scenarios.suite import record
from hexar.events.errors import CorruptRecordingError
from hexar.events.reader import read_recording
from tests.fuzz.harness import add_mcap_crcs


@pytest.fixture(scope="module")
def clean_mcap(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Scenario 5 (a blocked path) as MCAP with the chunk and summary CRCs a rosbag2 recorder writes."""
    bag = record(scenario(5), 1).write(tmp_path_factory.mktemp("mcap") / "bag", "mcap")
    add_mcap_crcs(next(bag.glob("*.mcap")))
    return bag


def _copy(bag: Path, tmp_path: Path) -> tuple[Path, Path]:
    out = shutil.copytree(bag, tmp_path / "bag")
    return out, next(out.glob("*.mcap"))


def _chunks(data: bytes) -> list[int]:
    pos, found = 8, []
    while pos + 9 <= len(data):
        opcode, length = struct.unpack_from("<BQ", data, pos)
        if opcode == 0x06:
            found.append(pos)
        if opcode == 0x02:
            break
        pos += 9 + length
    return found


def _ask(bag: Path, capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = main(["ask", str(bag), "What happened?", "--llm", "none", "--json"])
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def test_clean_recording_answers_with_its_cause(clean_mcap: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = _ask(clean_mcap, capsys)
    assert code == 0 and "navigation.blocked_path" in out


def test_flipped_byte_in_a_log_line_fails_the_chunk_crc(clean_mcap: Path, tmp_path: Path,
                                                        capsys: pytest.CaptureFixture[str]) -> None:
    bag, mcap = _copy(clean_mcap, tmp_path)
    data = bytearray(mcap.read_bytes())
    pos = data.index(b"Aborting")  # inside a /rosout message of a chunk
    data[pos] ^= 0x20
    mcap.write_bytes(bytes(data))
    code, out, err = _ask(bag, capsys)
    assert code == 2 and not out and "fails its CRC check" in err and err.count("\n") == 1


def test_truncated_mcap_is_reported(clean_mcap: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # cut inside the last chunk before any whole message: nothing to recover (tests/events/test_recover.py
    # recovers a cut further on), and nothing is read as data
    bag, mcap = _copy(clean_mcap, tmp_path)
    data = mcap.read_bytes()
    mcap.write_bytes(data[: _chunks(data)[-1] + 100])
    code, out, err = _ask(bag, capsys)
    assert code == 2 and not out and "cannot recover" in err and "before any whole message" in err


def test_damaged_summary_is_reported(clean_mcap: Path, tmp_path: Path) -> None:
    bag, mcap = _copy(clean_mcap, tmp_path)
    data = bytearray(mcap.read_bytes())
    (summary,) = struct.unpack_from("<Q", data, len(data) - 8 - 20 + 0)
    data[summary + 12] ^= 0xFF
    mcap.write_bytes(bytes(data))
    with pytest.raises(CorruptRecordingError, match="damaged recording"):
        read_recording(bag)


def test_chunk_length_damaged_to_petabytes_is_refused_before_any_read(clean_mcap: Path, tmp_path: Path) -> None:
    bag, mcap = _copy(clean_mcap, tmp_path)
    data = bytearray(mcap.read_bytes())
    struct.pack_into("<Q", data, _chunks(bytes(data))[0] + 1, 2**50)
    mcap.write_bytes(bytes(data))
    with pytest.raises(CorruptRecordingError, match="runs past the end of the file"):
        read_recording(bag)


def test_unreadable_sqlite_rows_are_reported(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bag = record(scenario(5), 1).write(tmp_path / "bag")
    db3 = next(bag.glob("*.db3"))
    size = db3.stat().st_size
    page = sqlite3.connect(db3).execute("PRAGMA page_size").fetchone()[0]
    data = bytearray(db3.read_bytes())
    data[size // 2 // page * page : size // 2 // page * page + 64] = b"\xa5" * 64  # a b-tree page header
    db3.write_bytes(bytes(data))
    code, out, err = _ask(bag, capsys)
    assert code == 2 and not out and "malformed" in err and err.startswith("ERROR: cannot read")
