"""Recordings cut short by a crash or a power loss, read as `ros2 bag reindex` would recover them.

rosbag2 writes `metadata.yaml` only when the recorder closes the bag, and the MCAP writer writes its summary and
footer only then too. A recorder killed mid-run leaves a folder of storage files without metadata, or an MCAP file
that simply stops. `ros2 bag reindex` rebuilds the metadata from the storage; here the same is done in memory:
sqlite3 files are read through their own `topics` and `messages` tables, and an MCAP file without its footer is
walked record by record up to the cut (a complete chunk is read whole; an uncompressed chunk cut in the middle
gives the messages that fit before the cut) and rewritten, whole and unchunked, into a temporary file.

What is recovered is said in the event log's warnings. Damage in the middle of a file (a file that still ends
like an MCAP file, a chunk that fails its CRC) is never "recovered": it stays the one-line error of mcap_index.
"""

from __future__ import annotations

import mmap
import re
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from struct import Struct
from typing import Any

from hexar.events.errors import CorruptRecordingError
from hexar.events.log import EventLog
from hexar.events.mcap_index import MAGIC, _chunk_records, _decompressor

_RECORD = Struct("<BQ")
_U16, _U32, _U64 = Struct("<H"), Struct("<I"), Struct("<Q")
_KEEP = frozenset({0x03, 0x04, 0x05})  # schema, channel, message: what a reader needs
_CHUNK, _DATA_END, _FOOTER = 0x06, 0x0F, 0x02


@dataclass
class Salvage:
    """The records of an MCAP file that were whole before it was cut, in file order."""

    records: list[bytes] = field(default_factory=list)  # each a whole record: opcode, length, body
    messages: int = 0
    cut_at: int = 0  # the file's length: where the recording stops
    lost_chunk: bool = False  # a compressed chunk was cut, and its messages cannot be read


STORAGE = (".db3", ".mcap")
# rosbag2 splits a recording into <bag>_0.mcap, <bag>_1.mcap, ... (its writer's file naming)
_SPLIT = re.compile(r"^(?P<stem>.+)_\d+$")


def storage_files(folder: Path) -> list[Path]:
    return sorted([*folder.glob("*.db3"), *folder.glob("*.mcap")])


def _one_recording(files: list[Path]) -> bool:
    """Whether storage files without a metadata.yaml are one recording: a single file, or the numbered splits of
    one bag in one storage format. Files of other names (MCAP files `hexar annotate` or another tool wrote
    beside each other) are recordings of their own, never read as one."""
    if len(files) <= 1:
        return True
    stems = {m.group("stem") if (m := _SPLIT.match(f.stem)) else None for f in files}
    return None not in stems and len(stems) == 1 and len({f.suffix for f in files}) == 1


def holds_storage(folder: Path) -> bool:
    """A folder with rosbag2 storage files but no metadata.yaml, which are one recording: a recording whose
    recorder never closed it."""
    if not folder.is_dir() or (folder / "metadata.yaml").is_file():
        return False
    files = storage_files(folder)
    return bool(files) and _one_recording(files)


def loose_storage(folder: Path) -> list[Path]:
    """Storage files side by side in a folder without metadata.yaml that are not one recording: each file is a
    recording of its own."""
    if not folder.is_dir() or (folder / "metadata.yaml").is_file():
        return []
    files = storage_files(folder)
    return [] if _one_recording(files) else files


def is_cut_short(path: Path) -> bool:
    """An MCAP file that starts like one but does not end like one: the writer stopped before its footer."""
    try:
        with path.open("rb") as f:
            head = f.read(len(MAGIC))
            size = f.seek(0, 2)
            if size < 2 * len(MAGIC):
                return head == MAGIC[:size] and size > 0
            f.seek(size - len(MAGIC))
            tail = f.read(len(MAGIC))
    except OSError:
        return False
    return head == MAGIC and tail != MAGIC


def _walk_chunk(buf: Any, q: int, end: int, into: Salvage) -> None:
    """The schema, channel and message records of one chunk's records from `q` to `end`, up to the first that
    does not fit (a chunk cut by the end of the file)."""
    while q + 9 <= end:
        opcode, length = _RECORD.unpack_from(buf, q)
        if q + 9 + length > end or opcode not in _KEEP:
            return
        into.records.append(bytes(buf[q : q + 9 + length]))
        into.messages += opcode == 0x05
        q += 9 + length


def salvage_mcap(path: Path) -> Salvage:
    """Every whole record of an MCAP file that ends without its footer."""
    with path.open("rb") as f:
        size = f.seek(0, 2)
        if size <= len(MAGIC):
            return Salvage(cut_at=size)
        data: Any = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
    out = Salvage(cut_at=size)
    pos = len(MAGIC)
    while pos + 9 <= size:
        opcode, length = _RECORD.unpack_from(data, pos)
        whole = pos + 9 + length <= size
        if opcode in (_DATA_END, _FOOTER):
            break
        if opcode in _KEEP and whole:
            out.records.append(bytes(data[pos : pos + 9 + length]))
            out.messages += opcode == 0x05
        elif opcode == _CHUNK and whole:
            compression_len = _U32.unpack_from(data, pos + 9 + 28)[0]
            compression = bytes(data[pos + 9 + 32 : pos + 9 + 32 + compression_len]).decode("utf-8", "replace")
            decompress = _decompressor(compression)
            if decompress is None:
                raise CorruptRecordingError(f"damaged recording: {path.name}: a chunk at byte {pos} uses "
                                            f"compression {compression!r}, which HEXAR cannot read")
            records, q, end = _chunk_records(data, pos, decompress, path.name)  # a whole chunk's CRC is checked
            _walk_chunk(records, q, end, out)
        elif opcode == _CHUNK:
            # cut inside this chunk: an uncompressed one still holds its first records whole
            p = pos + 9 + 28
            if p + 4 > size:
                break
            compression_len = _U32.unpack_from(data, p)[0]
            p += 4 + compression_len
            if p + 8 <= size and compression_len == 0:
                _walk_chunk(data, p + 8, size, out)
            else:
                out.lost_chunk = True
            break
        if not whole:
            break
        pos += 9 + length
    return out


def _record(opcode: int, body: bytes) -> bytes:
    return _RECORD.pack(opcode, len(body)) + body


def _string(text: str) -> bytes:
    raw = text.encode("utf-8")
    return _U32.pack(len(raw)) + raw


def write_whole(salvage: Salvage, out: Path) -> None:
    """The salvaged records as a whole MCAP file (no chunks, no summary), which any MCAP reader can scan."""
    header = _record(0x01, _string("ros2") + _string("hexar recover"))
    data_end = _record(_DATA_END, _U32.pack(0))
    footer = _record(_FOOTER, _U64.pack(0) + _U64.pack(0) + _U32.pack(0))
    with out.open("wb") as f:
        f.write(MAGIC + header)
        for rec in salvage.records:
            f.write(rec)
        f.write(data_end + footer + MAGIC)


def read_recovered(src: Path, cut: list[Path], read: Callable[[list[Path]], EventLog]) -> EventLog:
    """A recording cut short, read from its storage files as `ros2 bag reindex` rebuilds it (events/recover.py);
    each recovery is the first warning of the log. `read` reads the recording from a list of storage files; `src`
    is a folder, or one storage file read alone."""
    notes: list[str] = []
    with tempfile.TemporaryDirectory(prefix="hexar-recover-") as tmp:
        files: list[Path] = []
        for file in storage_files(src) if src.is_dir() else [src]:
            if file not in cut:
                files.append(file)
                continue
            salvage = salvage_mcap(file)
            if not salvage.messages:
                raise CorruptRecordingError(f"cannot recover {src}: {file.name} was cut at byte {salvage.cut_at}, "
                                            "before any whole message")
            whole = Path(tmp) / file.name
            write_whole(salvage, whole)
            files.append(whole)
            lost = "; the messages of the chunk being written when it was cut are lost" if salvage.lost_chunk else ""
            notes.append(f"recovered: {file.name} ends at byte {salvage.cut_at} without its MCAP footer (the "
                         f"recorder stopped before closing it); read the {salvage.messages} messages written before "
                         f"the cut, as `ros2 bag reindex` would{lost}")
        if src.is_dir() and not (src / "metadata.yaml").is_file():
            names = ", ".join(f.name for f in storage_files(src))
            notes.insert(0, f"recovered: {src.name} has no metadata.yaml (the recorder stopped before writing it); "
                            f"the metadata was rebuilt from {names}, as `ros2 bag reindex` does")
        log = read(files)
    log.warnings[:0] = notes
    return log
