"""Messages of selected topics straight from an indexed MCAP file.

rosbags' MCAP reader opens every chunk that holds a wanted channel as a generator and merges them all through a
heap to yield messages in time order. HEXAR sorts its records by their own stamps anyway, so this reader walks
the chunk index once, skips chunks without a wanted channel, and scans each chunk buffer with struct; on
anything it does not expect (no summary, unknown compression) it returns None and the caller uses rosbags.
"""

from __future__ import annotations

import mmap
from collections.abc import Callable, Iterator
from pathlib import Path
from struct import Struct
from typing import Any, TypeVar

MAGIC = b"\x89MCAP0\r\n"
_U16, _U32, _U64 = Struct("<H"), Struct("<I"), Struct("<Q")
_RECORD = Struct("<BQ")
_MESSAGE = Struct("<HIQQ")
_CHUNK_INDEX = Struct("<QQQQ")
K = TypeVar("K")


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
    return _scan(data, plan, channels)


def _scan(data: Any, plan: list[tuple[int, Callable[[bytes], bytes]]],
          channels: dict[int, K]) -> Iterator[tuple[K, int, bytes]]:
    for start, decompress in plan:
        p = start + 9 + 24 + 4  # record header; message start/end time, uncompressed size; uncompressed crc
        compression_len = _U32.unpack_from(data, p)[0]
        p += 4 + compression_len
        (size,) = _U64.unpack_from(data, p)
        if decompress is bytes:
            # Uncompressed: walk the records in place, so the pages of unwanted messages are never touched.
            records, q, end = data, p + 8, p + 8 + size
        else:
            records = decompress(data[p + 8 : p + 8 + size])
            q, end = 0, len(records)
        while q < end:
            opcode, length = _RECORD.unpack_from(records, q)
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
