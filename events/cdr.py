"""Hand decoders for the two hot message types of a recording.

`/rosout` dominates a recording (hundreds of thousands of lines an hour); rosbags' generic deserialiser builds
a full message object per line, which caps decoding well below 100k lines/s. These decoders read only the
fields HEXAR uses and return None on anything unexpected, so the caller falls back to rosbags.
"""

from __future__ import annotations

from struct import error as StructError
from struct import unpack_from


def _string(raw: bytes, pos: int, endian: str) -> tuple[str, int]:
    pos = 4 + ((pos - 4 + 3) & ~3)
    (size,) = unpack_from(endian + "I", raw, pos)
    pos += 4
    end = pos + size
    if size == 0 or end > len(raw):
        raise ValueError("string out of bounds")
    return raw[pos : end - 1].decode("utf-8", errors="replace"), end


def decode_log(raw: bytes) -> tuple[int, int, int, str, str] | None:
    """(sec, nanosec, level, name, msg) of an rcl_interfaces/msg/Log in CDR, or None."""
    try:
        endian = "<" if raw[1] == 1 else ">"
        sec, nanosec = unpack_from(endian + "iI", raw, 4)
        level = raw[12]
        name, pos = _string(raw, 13, endian)
        msg, _ = _string(raw, pos, endian)
    except (IndexError, ValueError, StructError):
        return None
    return sec, nanosec, level, name, msg


def decode_string(raw: bytes) -> str | None:
    """The data of a std_msgs/msg/String in CDR, or None."""
    try:
        endian = "<" if raw[1] == 1 else ">"
        (size,) = unpack_from(endian + "I", raw, 4)
        if size == 0 or 8 + size > len(raw):
            return None
        return raw[8 : 8 + size - 1].decode("utf-8", errors="replace")
    except (IndexError, StructError):
        return None
