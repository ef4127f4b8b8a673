"""Messages of selected topics straight from an indexed MCAP file.

rosbags' MCAP reader opens every chunk that holds a wanted channel as a generator and merges them all through a
heap to yield messages in time order. HEXAR sorts its records by their own stamps anyway, so this reader walks
the chunk index once, skips chunks without a wanted channel, and scans each chunk buffer with struct; on
anything it does not expect (no summary, unknown compression) it returns None and the caller uses rosbags.

Storage damage is never read as data: a chunk or summary whose CRC does not match, a chunk that runs past the
end of the file, or records that do not fit their chunk raise CorruptRecordingError naming the byte offset.
rosbags neither checks CRCs nor writes them (its chunks carry CRC 0, which MCAP defines as "not computed"), so
`check_mcap` walks a file without a summary the same way before rosbags reads it.
"""

from __future__ import annotations

import mmap
import zlib
from collections.abc import Callable, Iterator
from pathlib import Path
from struct import Struct
from typing import Any, TypeVar

from hexar.events.errors import CorruptRecordingError

MAGIC = b"\x89MCAP0\r\n"
_U16, _U32, _U64 = Struct("<H"), Struct("<I"), Struct("<Q")
_RECORD = Struct("<BQ")
_MESSAGE = Struct("<HIQQ")
_CHUNK_INDEX = Struct("<QQQQ")
K = TypeVar("K")
_CHUNK_OPCODES = frozenset({0x03, 0x04, 0x05})  # schema, channel, message: all a chunk may hold


def _string(buf: bytes, pos: int) -> tuple[str, int]:
    (n,) = _U32.unpack_from(buf, pos)
    return buf[pos + 4 : pos + 4 + n].decode("utf-8"), pos + 4 + n


def _decompressor(name: str) -> Callable[[bytes], bytes] | None:
    if name == "":
        return bytes
    if name == "zstd":
        try:
            from compression import zstd  # type: ignore[import-not-found,unused-ignore]
        except ImportError:
            from backports import zstd  # type: ignore[no-redef,import-not-found,unused-ignore]
        return zstd.decompress  # type: ignore[no-any-return]
    if name == "lz4":
        from lz4.frame import decompress  # type: ignore[import-untyped,unused-ignore]

        return decompress  # type: ignore[no-any-return]
    return None


def mcap_messages(path: Path, wanted: dict[tuple[str, str], K]) -> Iterator[tuple[K, int, bytes]] | None:
    """(key, log_time, data) for channels whose (topic, schema name) is in `wanted`, in file order."""
    with path.open("rb") as f:
        # mmap: only the summary and the chunks we need are ever paged in, not the images between them
        data: Any = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
    if len(data) < 2 * len(MAGIC) + 29 or data[: len(MAGIC)] != MAGIC or data[-len(MAGIC):] != MAGIC:
        return None
    footer = len(data) - len(MAGIC) - 1 - 8 - 20
    opcode, _ = _RECORD.unpack_from(data, footer)
    if opcode != 0x02:
        return None
    (summary,) = _U64.unpack_from(data, footer + 9)
    if summary == 0:
        return None
    if summary >= footer:
        raise CorruptRecordingError(f"damaged recording: {path.name}: the MCAP footer points past itself")
    (summary_crc,) = _U32.unpack_from(data, footer + 9 + 16)
    if summary_crc and zlib.crc32(memoryview(data)[summary : footer + 9 + 16]) != summary_crc:
        raise CorruptRecordingError(f"damaged recording: {path.name}: the MCAP summary (byte {summary}) fails "
                                    "its CRC check")
    schemas: dict[int, str] = {}
    topics: list[tuple[int, int, str]] = []  # channel id, schema id, topic
    chunks: list[tuple[int, str, set[int]]] = []  # chunk record offset, compression, channel ids inside
    pos = summary
    while pos < footer:
        opcode, length = _RECORD.unpack_from(data, pos)
        body = pos + 9
        if opcode == 0x03:
            (sid,) = _U16.unpack_from(data, body)
            schemas[sid], _ = _string(data, body + 2)
        elif opcode == 0x04:
            cid, sid = _U16.unpack_from(data, body)[0], _U16.unpack_from(data, body + 2)[0]
            topics.append((cid, sid, _string(data, body + 4)[0]))
        elif opcode == 0x08:
            offset = _CHUNK_INDEX.unpack_from(data, body)[2]
            (map_len,) = _U32.unpack_from(data, body + 32)
            ids = {_U16.unpack_from(data, body + 36 + i)[0] for i in range(0, map_len, 10)}
            compression, _ = _string(data, body + 36 + map_len + 8)
            chunks.append((offset, compression, ids))
        pos = body + length
    channels = {cid: wanted[(topic, schemas.get(sid, ""))] for cid, sid, topic in topics
                if (topic, schemas.get(sid, "")) in wanted}
    plan = []
    for offset, compression, ids in chunks:
        if ids & channels.keys():
            decompress = _decompressor(compression)
            if decompress is None:
                return None
            plan.append((offset, decompress))
    return _scan(data, plan, channels, path.name)


def _chunk_records(data: Any, start: int, decompress: Callable[[bytes], bytes], name: str) -> tuple[Any, int, int]:
    """The uncompressed records of the chunk at `start` as (buffer, first, end), after its CRC is checked."""
    where = f"damaged recording: {name}: chunk at byte {start}"
    if start + 9 + 40 > len(data):
        raise CorruptRecordingError(f"{where} lies past the end of the file (truncated?)")
    opcode, length = _RECORD.unpack_from(data, start)
    if opcode != 0x06 or start + 9 + length > len(data):
        raise CorruptRecordingError(f"{where} is {'cut off' if opcode == 0x06 else 'not a chunk record'}")
    size_uncompressed, crc = _U64.unpack_from(data, start + 9 + 16)[0], _U32.unpack_from(data, start + 9 + 24)[0]
    p = start + 9 + 28  # record header; message start/end time, uncompressed size, uncompressed crc
    compression_len = _U32.unpack_from(data, p)[0]
    p += 4 + compression_len
    (size,) = _U64.unpack_from(data, p)
    if p + 8 + size > start + 9 + length:
        raise CorruptRecordingError(f"{where} holds more bytes than its record")
    if decompress is bytes:
        # Uncompressed: walk the records in place, so the pages of unwanted messages are never touched.
        records, q, end = data, p + 8, p + 8 + size
    else:
        try:
            records = decompress(data[p + 8 : p + 8 + size])
        except Exception as err:  # each codec raises its own class on damaged input
            raise CorruptRecordingError(f"{where} does not decompress: {err}") from err
        q, end = 0, len(records)
    if end - q != size_uncompressed:
        raise CorruptRecordingError(f"{where} holds {end - q} bytes where its header says {size_uncompressed}")
    if crc and zlib.crc32(memoryview(records)[q:end]) != crc:
        raise CorruptRecordingError(f"{where} fails its CRC check")
    return records, q, end


def _scan(data: Any, plan: list[tuple[int, Callable[[bytes], bytes]]],
          channels: dict[int, K], name: str) -> Iterator[tuple[K, int, bytes]]:
    for start, decompress in plan:
        records, q, end = _chunk_records(data, start, decompress, name)
        while q < end:
            if q + 9 > end:
                raise CorruptRecordingError(f"damaged recording: {name}: chunk at byte {start} ends mid-record")
            opcode, length = _RECORD.unpack_from(records, q)
            if q + 9 + length > end or opcode not in _CHUNK_OPCODES:
                raise CorruptRecordingError(f"damaged recording: {name}: chunk at byte {start} holds a malformed "
                                            f"record at offset {q}")
            if opcode == 0x05:
                cid, _, log_time, _ = _MESSAGE.unpack_from(records, q + 9)
                key = channels.get(cid)
                if key is not None:
                    yield key, log_time, bytes(records[q + 9 + 22 : q + 9 + length])
            q += 9 + length
        if records is data:
            # The kernel maps whole page-cache folios on a fault, images included; let them go chunk by chunk so
            # the process never holds the recording in memory.
            lo = start & ~(mmap.PAGESIZE - 1)
            data.madvise(mmap.MADV_DONTNEED, lo, min(end, len(data)) - lo)


def check_mcap(path: Path, crc: bool = True) -> None:
    """Walk every record of an MCAP file from its start; CorruptRecordingError on the first damage found.

    With `crc=False` only the structure is checked (every record inside the file, the footer and the chunk
    index pointing at records that exist): cheap, and run before rosbags opens a file, because rosbags trusts a
    damaged length and asks for that many bytes. With `crc=True` every chunk is also decompressed and checked,
    for files the indexed reader cannot use.
    """
    name = path.name
    with path.open("rb") as f:
        if f.seek(0, 2) < 2 * len(MAGIC):
            raise CorruptRecordingError(f"damaged recording: {name} is too short to be an MCAP file")
        data: Any = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
    if data[: len(MAGIC)] != MAGIC:
        raise CorruptRecordingError(f"damaged recording: {name} does not start like an MCAP file")
    pos, size = len(MAGIC), len(data)
    starts: dict[int, int] = {}  # record offset -> its length, to check what the index points at
    chunk_index: list[tuple[int, int]] = []
    footer: tuple[int, int] | None = None
    footer_at = 0
    while footer is None:
        if pos + 9 > size:
            raise CorruptRecordingError(f"damaged recording: {name} ends at byte {size} without its MCAP "
                                        "footer (truncated)")
        opcode, length = _RECORD.unpack_from(data, pos)
        if pos + 9 + length > size:
            raise CorruptRecordingError(f"damaged recording: {name}: record at byte {pos} runs past the end of "
                                        "the file (truncated or damaged)")
        starts[pos] = length
        if opcode == 0x06 and crc and length >= 32:
            compression, _ = _string(data, pos + 9 + 28)
            decompress = _decompressor(compression)
            if decompress is not None:
                _chunk_records(data, pos, decompress, name)
        elif opcode == 0x08 and length >= 32:
            chunk_index.append(_CHUNK_INDEX.unpack_from(data, pos + 9)[2:4])
        elif opcode == 0x02 and length >= 20:
            footer = (_U64.unpack_from(data, pos + 9)[0], _U64.unpack_from(data, pos + 17)[0])
            footer_at = pos
        pos += 9 + length
    if data[pos:] != MAGIC:
        raise CorruptRecordingError(f"damaged recording: {name} does not end like an MCAP file")
    if any(offset and offset not in starts for offset in footer):
        raise CorruptRecordingError(f"damaged recording: {name}: the MCAP footer points between records")
    (summary_crc,) = _U32.unpack_from(data, footer_at + 9 + 16)
    if footer[0] and summary_crc and zlib.crc32(memoryview(data)[footer[0] : footer_at + 9 + 16]) != summary_crc:
        raise CorruptRecordingError(f"damaged recording: {name}: the MCAP summary (byte {footer[0]}) fails its "
                                    "CRC check")
    for offset, length in chunk_index:
        if starts.get(offset, -1) + 9 != length:
            raise CorruptRecordingError(f"damaged recording: {name}: the chunk index points at no chunk "
                                        f"(byte {offset})")
